// A program written against PQP 1.3's documented interface only (PQP.h: PQP_Model, the result
// classes, PQP_Collide / PQP_Distance / PQP_Tolerance with their default arguments), checking the
// answers on two unit boxes whose distances are known, and on a "fence" of triangles crossed by a
// "rail" whose colliding pairs are known by construction. It must compile unchanged as C++98 to
// C++20 with -Wall -Wextra -pedantic -Werror.
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

// The 12 triangles of the unit box [0,1]^3, ids 0..11, added the way PQP users do.
static void build_box(PQP_Model &m)
{
    PQP_REAL c[8][3];
    for (int k = 0; k < 8; k++) {
        c[k][0] = (k >> 2) & 1;
        c[k][1] = (k >> 1) & 1;
        c[k][2] = k & 1;
    }
    static const int f[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    EXPECT(m.BeginModel() == PQP_OK);
    for (int k = 0; k < 12; k++) EXPECT(m.AddTri(c[f[k][0]], c[f[k][1]], c[f[k][2]], k) == PQP_OK);
    EXPECT(m.EndModel() == PQP_OK);
}

static void identity(PQP_REAL R[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) R[i][j] = i == j ? 1.0 : 0.0;
}

// A model held as a member, as applications do.
struct Body {
    PQP_Model model;
    PQP_REAL R[3][3];
    PQP_REAL T[3];
    Body()
    {
        identity(R);
        T[0] = T[1] = T[2] = 0.0;
    }
};

int main()
{
    // Models: on the stack, with new, and as a member.
    PQP_Model b1;
    PQP_Model *b2 = new PQP_Model;
    Body body;
    build_box(b1);
    build_box(*b2);
    build_box(body.model);
    EXPECT(b1.num_tris == 12);
    EXPECT(b2->num_tris == 12);
    EXPECT(body.model.num_tris == 12);
    EXPECT(b1.MemUsage(0) > 0);
    EXPECT(b1.MemUsage(1) == b1.MemUsage(0));

    PQP_REAL R1[3][3], R2[3][3], T1[3] = {0, 0, 0}, T2[3] = {0, 0, 0};
    identity(R1);
    identity(R2);

    // Distance: box 2 at x + 3 is 2 away; closest points on the faces x = 1 and x = 0 (its own
    // frame).
    PQP_DistanceResult dres;
    T2[0] = 3.0;
    EXPECT(PQP_Distance(&dres, R1, T1, &b1, R2, T2, b2, 0.0, 0.0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 2.0) < 1e-12);
    EXPECT(fabs(dres.P1()[0] - 1.0) < 1e-15);
    EXPECT(fabs(dres.P2()[0] - 0.0) < 1e-15);
    EXPECT(dres.NumBVTests() >= 1);
    EXPECT(dres.NumTriTests() >= 1);
    EXPECT(dres.QueryTimeSecs() >= 0.0);

    // Approximate distance within 10%, with an explicit queue size.
    EXPECT(PQP_Distance(&dres, R1, T1, &b1, R2, T2, b2, 0.1, 0.1, 10) == PQP_OK);
    EXPECT(dres.Distance() >= 2.0 && dres.Distance() <= 2.1 + 1e-12);

    // Box 2 turned 90 degrees about z (x -> y) at x + 3 spans x in [2, 3]: distance 1.
    PQP_REAL Rz[3][3] = {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}};
    EXPECT(PQP_Distance(&dres, R1, T1, &b1, Rz, T2, &body.model, 0.0, 0.0) == PQP_OK);
    EXPECT(fabs(dres.Distance() - 1.0) < 1e-12);

    // Tolerance.
    PQP_ToleranceResult tres;
    EXPECT(PQP_Tolerance(&tres, R1, T1, &b1, R2, T2, b2, 2.5) == PQP_OK);
    EXPECT(tres.CloserThanTolerance() == 1);
    EXPECT(tres.Distance() >= 2.0 - 1e-12 && tres.Distance() <= 2.5);
    {
        // The pair reported lies within the tolerance: its points (P2 in box 2's frame) are
        // Distance() apart in the world.
        const PQP_REAL *p = tres.P1(), *q = tres.P2();
        PQP_REAL dx = q[0] + T2[0] - p[0], dy = q[1] + T2[1] - p[1], dz = q[2] + T2[2] - p[2];
        EXPECT(fabs(sqrt(dx * dx + dy * dy + dz * dz) - tres.Distance()) < 1e-12);
    }
    EXPECT(PQP_Tolerance(&tres, R1, T1, &b1, R2, T2, b2, 1.5) == PQP_OK);
    EXPECT(tres.CloserThanTolerance() == 0);
    EXPECT(tres.Distance() > 1.5 && tres.Distance() <= 2.0 + 1e-12);
    EXPECT(tres.NumBVTests() >= 1 && tres.NumTriTests() >= 0 && tres.QueryTimeSecs() >= 0.0);

    // Collision: apart, overlapping, touching.
    PQP_CollideResult cres;
    EXPECT(PQP_Collide(&cres, R1, T1, &b1, R2, T2, b2) == PQP_OK);
    EXPECT(cres.Colliding() == 0 && cres.NumPairs() == 0);
    T2[0] = 0.5;
    T2[1] = 0.5;
    T2[2] = 0.5;
    EXPECT(PQP_Collide(&cres, R1, T1, &b1, R2, T2, b2) == PQP_OK);
    EXPECT(cres.Colliding() == 1 && cres.NumPairs() > 0);
    EXPECT(cres.NumBVTests() >= 1 && cres.NumTriTests() >= 1 && cres.QueryTimeSecs() >= 0.0);
    EXPECT(PQP_Collide(&cres, R1, T1, &b1, R2, T2, b2, PQP_FIRST_CONTACT) == PQP_OK);
    EXPECT(cres.NumPairs() == 1);
    cres.FreePairsList();
    EXPECT(cres.NumPairs() == 0);
    EXPECT(PQP_Distance(&dres, R1, T1, &b1, R2, T2, b2, 0.0, 0.0) == PQP_OK);
    EXPECT(dres.Distance() == 0.0);

    // Fence: triangle k in the plane x = k; the rail crosses planes x in [2.5, 6]: pairs (3..6, 7).
    PQP_Model fence, rail;
    EXPECT(fence.BeginModel(10) == PQP_OK);
    for (int k = 0; k < 10; k++) {
        PQP_REAL a[3] = {0, 0, 0}, b[3] = {0, 1, 0}, c[3] = {0, 0, 1};
        a[0] = b[0] = c[0] = k;
        EXPECT(fence.AddTri(a, b, c, k) == PQP_OK);
    }
    EXPECT(fence.EndModel() == PQP_OK);
    PQP_REAL ra[3] = {0, 0.2, 0.2}, rb[3] = {3.5, 0.2, 0.2}, rc[3] = {3.5, 0.3, 0.2};
    EXPECT(rail.BeginModel(1) == PQP_OK);
    EXPECT(rail.AddTri(ra, rb, rc, 7) == PQP_OK);
    EXPECT(rail.EndModel() == PQP_OK);
    T2[0] = 2.5;
    T2[1] = T2[2] = 0.0;
    EXPECT(PQP_Collide(&cres, R1, T1, &fence, R2, T2, &rail) == PQP_OK);
    EXPECT(cres.NumPairs() == 4);
    int seen = 0;
    for (int k = 0; k < cres.NumPairs(); k++) {
        EXPECT(cres.Id2(k) == 7);
        if (cres.Id1(k) >= 3 && cres.Id1(k) <= 6) seen |= 1 << cres.Id1(k);
    }
    EXPECT(seen == ((1 << 3) | (1 << 4) | (1 << 5) | (1 << 6)));

    // PQP 1.3's error codes.
    PQP_Model unbuilt;
    EXPECT(PQP_Distance(&dres, R1, T1, &b1, R2, T2, &unbuilt, 0.0, 0.0) == PQP_ERR_UNPROCESSED_MODEL);
    EXPECT(b1.AddTri(ra, rb, rc, 1) == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    EXPECT(b1.num_tris == 12);
    EXPECT(unbuilt.BeginModel() == PQP_OK);
    EXPECT(unbuilt.EndModel() == PQP_ERR_BUILD_EMPTY_MODEL);
    EXPECT(b1.BeginModel() == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    EXPECT(b1.num_tris == 0);

    delete b2;
    if (failures) {
        fprintf(stderr, "legacy_boxes: %d check(s) failed\n", failures);
        return 1;
    }
    printf("legacy_boxes: all checks passed\n");
    return 0;
}
