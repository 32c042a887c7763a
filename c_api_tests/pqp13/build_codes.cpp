// PQP 1.3's build protocol return codes, call by call, including the out-of-order calls real
// programs make (EndModel on a model never begun, AddTri after EndModel, BeginModel on a built
// model), and what a refused triangle does to the build state. Compiles as C++98 to C++20.
#include "PQP.h"

#include <math.h>
#include <stdio.h>

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

static PQP_REAL A[3] = {0, 0, 0}, B[3] = {1, 0, 0}, C[3] = {0, 1, 0};

// Whether a distance query on m answers (m against itself), i.e. whether m is built.
static bool queryable(PQP_Model &m)
{
    PQP_REAL R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, T[3] = {0, 0, 0};
    PQP_DistanceResult r;
    return PQP_Distance(&r, R, T, &m, R, T, &m, 0, 0) == PQP_OK;
}

int main()
{
    {
        // EndModel on a model never begun, without triangles: PQP 1.3 returns -5.
        PQP_Model m;
        EXPECT(m.build_state == 0);
        EXPECT(m.EndModel() == PQP_ERR_BUILD_EMPTY_MODEL);
        EXPECT(m.build_state == 0 && !queryable(m));
        // Still usable: the usual sequence works afterwards.
        EXPECT(m.BeginModel() == PQP_OK);
        EXPECT(m.AddTri(A, B, C, 0) == PQP_OK);
        EXPECT(m.EndModel() == PQP_OK && queryable(m));
    }
    {
        // BeginModel then EndModel without triangles: -5, the model stays unprocessed.
        PQP_Model m;
        EXPECT(m.BeginModel() == PQP_OK);
        EXPECT(m.build_state == 1);
        EXPECT(m.EndModel() == PQP_ERR_BUILD_EMPTY_MODEL);
        EXPECT(m.build_state == 1 && !queryable(m));
        EXPECT(m.AddTri(A, B, C, 0) == PQP_OK);
        EXPECT(m.EndModel() == PQP_OK && m.build_state == 2);
    }
    {
        // AddTri before BeginModel begins the model implicitly (PQP_OK).
        PQP_Model m;
        EXPECT(m.AddTri(A, B, C, 0) == PQP_OK);
        EXPECT(m.build_state == 1 && m.num_tris == 1);
        EXPECT(m.EndModel() == PQP_OK);
        // After EndModel: AddTri is ignored (-4), EndModel again is -4, the model stays built.
        EXPECT(m.AddTri(A, B, C, 1) == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        EXPECT(m.num_tris == 1);
        EXPECT(m.EndModel() == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        EXPECT(m.build_state == 2 && queryable(m));
        // BeginModel on a built model clears it, begins it, and returns -4.
        EXPECT(m.BeginModel() == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        EXPECT(m.build_state == 1 && m.num_tris == 0 && !queryable(m));
        EXPECT(m.AddTri(A, B, C, 2) == PQP_OK);
        EXPECT(m.EndModel() == PQP_OK);
    }
    {
        // BeginModel twice: the second clears what was added and returns -4.
        PQP_Model m;
        EXPECT(m.BeginModel(100) == PQP_OK);
        EXPECT(m.num_tris_alloced == 100);
        EXPECT(m.AddTri(A, B, C, 0) == PQP_OK);
        EXPECT(m.BeginModel() == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        EXPECT(m.num_tris == 0 && m.build_state == 1);
    }
#ifdef PQP_PQP_H
    // pqp-rs only (PQP_PQP_H is its C header's guard, which its PQP.h includes): PQP 1.3 has no
    // code for a non-finite vertex; it stores it and later answers queries wrongly.
    {
        // A refused triangle (non-finite vertex) is not added; a fresh model is begun by it, and
        // the model stays usable.
        PQP_Model m;
        PQP_REAL bad[3] = {0, (PQP_REAL)NAN, 0};
        EXPECT(m.AddTri(A, bad, C, 0) == PQP_ERR_NONFINITE_COORDINATE);
        EXPECT(m.num_tris == 0 && m.build_state == 1);
        EXPECT(m.EndModel() == PQP_ERR_BUILD_EMPTY_MODEL);
        EXPECT(m.AddTri(A, B, C, 1) == PQP_OK);
        EXPECT(m.AddTri(A, B, bad, 2) == PQP_ERR_NONFINITE_COORDINATE);
        EXPECT(m.num_tris == 1);
        EXPECT(m.EndModel() == PQP_OK && m.num_tris == 1);
    }
#endif

    if (failures != 0) return 1;
    printf("all checks passed\n");
    return 0;
}
