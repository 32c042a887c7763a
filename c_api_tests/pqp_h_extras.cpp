// PQP.h beyond PQP 1.3's documented use: bad arguments give codes instead of crashes, models and
// results move (C++11), models live in containers, and pqp_handle() reaches the C interface.
#include "PQP.h"

#include <math.h>
#include <stdio.h>
#include <utility>
#include <vector>

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

// A single triangle in the plane z = z0, id `id`.
static void build_triangle(PQP_Model &m, double z0, int id)
{
    PQP_REAL a[3] = {0, 0, z0}, b[3] = {1, 0, z0}, c[3] = {0, 1, z0};
    EXPECT(m.BeginModel(1) == PQP_OK);
    EXPECT(m.AddTri(a, b, c, id) == PQP_OK);
    EXPECT(m.EndModel() == PQP_OK);
}

int main()
{
    PQP_REAL R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, T[3] = {0, 0, 0}, T2[3] = {0, 0, 2};
    PQP_Model a, b;
    build_triangle(a, 0.0, 1);
    build_triangle(b, 0.0, 2);
    PQP_CollideResult cres;
    PQP_DistanceResult dres;
    PQP_ToleranceResult tres;

    // NULL anywhere: PQP_ERR_NULL_POINTER.
    EXPECT(PQP_Collide(NULL, R, T, &a, R, T2, &b) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Collide(&cres, NULL, T, &a, R, T2, &b) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Collide(&cres, R, NULL, &a, R, T2, &b) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Collide(&cres, R, T, NULL, R, T2, &b) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Distance(&dres, R, T, &a, NULL, T2, &b, 0, 0) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, NULL, &b, 0, 0) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, NULL, 0, 0) == PQP_ERR_NULL_POINTER);
    EXPECT(PQP_Tolerance(NULL, R, T, &a, R, T2, &b, 1.0) == PQP_ERR_NULL_POINTER);
    EXPECT(a.AddTri(NULL, T, T, 0) == PQP_ERR_NULL_POINTER);

    // Bad values: codes, and the results keep their last answer.
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &b, 0, 0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 2.0) < 1e-12);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &b, -1, 0) == PQP_ERR_INVALID_ARGUMENT);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &b, 0, 0, 0) == PQP_ERR_INVALID_ARGUMENT);
    EXPECT(PQP_Collide(&cres, R, T, &a, R, T2, &b, 7) == PQP_ERR_INVALID_ARGUMENT);
    EXPECT(PQP_Tolerance(&tres, R, T, &a, R, T2, &b, -0.5) == PQP_ERR_INVALID_ARGUMENT);
    PQP_REAL bad[3] = {0, NAN, 0};
    EXPECT(PQP_Distance(&dres, R, T, &a, R, bad, &b, 0, 0) == PQP_ERR_NONFINITE_POSE);
    EXPECT(fabs(dres.Distance() - 2.0) < 1e-12);
    {
        PQP_Model c;
        PQP_REAL p[3] = {0, 0, 0}, q[3] = {1, 0, 0}, r[3] = {0, INFINITY, 0};
        EXPECT(c.BeginModel() == PQP_OK);
        EXPECT(c.AddTri(p, q, r, 0) == PQP_ERR_NONFINITE_COORDINATE);
        EXPECT(c.num_tris == 0);
        EXPECT(c.AddTri(NULL, q, r, 0) == PQP_ERR_NULL_POINTER);
        EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &c, 0, 0) == PQP_ERR_UNPROCESSED_MODEL);
    }

    // Moves: the moved-to object works, the moved-from one is empty but safe.
    PQP_Model moved(std::move(b));
    EXPECT(moved.num_tris == 1 && b.num_tris == 0);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &moved, 0, 0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 2.0) < 1e-12);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &b, 0, 0) == PQP_ERR_UNPROCESSED_MODEL);
    build_triangle(b, 0.5, 3); // a moved-from model can be built again
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T, &b, 0, 0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 0.5) < 1e-12);

    PQP_DistanceResult d2(std::move(dres));
    EXPECT(fabs(d2.Distance() - 0.5) < 1e-12);
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T2, &moved, 0, 0) == PQP_OK); // handle made again
    EXPECT(fabs(dres.Distance() - 2.0) < 1e-12);
    PQP_CollideResult c2;
    c2 = std::move(cres);
    EXPECT(PQP_Collide(&c2, R, T, &a, R, T, &moved) == PQP_OK && c2.Colliding() == 1);
    EXPECT(c2.NumPairs() == 1 && c2.Id1(0) == 1 && c2.Id2(0) == 2);
    EXPECT(c2.Id1(1) == -1);

    // Models in a container (moved as it grows).
    std::vector<PQP_Model> models(3);
    for (int i = 0; i < 3; i++) build_triangle(models[i], 3.0 * i, i);
    models.push_back(PQP_Model());
    build_triangle(models.back(), 10.0, 9);
    EXPECT(PQP_Distance(&dres, R, T, &models[0], R, T, &models[3], 0, 0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 10.0) < 1e-12);

    // The C interface through pqp_handle(): overlap flag and ids.
    EXPECT(PQP_Distance(&dres, R, T, &a, R, T, &moved, 0, 0) == PQP_OK);
    EXPECT(pqp_distance_result_overlap(dres.pqp_handle()) == 1);
    EXPECT(pqp_distance_result_id1(dres.pqp_handle()) == 1);
    EXPECT(pqp_distance_result_id2(dres.pqp_handle()) == 2);
    EXPECT(pqp_model_is_built(a.pqp_handle()) == 1);

    // MemUsage never prints and is clamped to int.
    EXPECT(a.MemUsage(1) > 0);

    if (failures) {
        fprintf(stderr, "pqp_h_extras: %d check(s) failed\n", failures);
        return 1;
    }
    printf("pqp_h_extras: all checks passed\n");
    return 0;
}
