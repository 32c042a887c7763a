// PQP 1.3 users could make PQP_REAL float by editing PQP_Compile.h. pqp-rs supports client code
// built that way (here with -DPQP_USE_FLOAT, which PQP_Compile.h honours): every PQP_REAL the
// program passes is widened to double, the library computes in double, and every PQP_REAL it reads
// back (result members, tris, b) is the double answer rounded to float. Checked against brute
// force on the float coordinates widened to long double. C++11 and later (bf.hpp).
#include "PQP.h"

#include <math.h>
#include <stdio.h>

#include <vector>

#include "bf.hpp"

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

typedef bf::V<long double> V;

static unsigned long long state = 12345;
static float uniform()
{
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (float)((double)(state >> 11) * (1.0 / 9007199254740992.0));
}

int main()
{
    EXPECT(sizeof(PQP_REAL) == sizeof(float));
    const int n = 80;
    std::vector<float> va(9 * n), vb(9 * n);
    for (int k = 0; k < 9 * n; k++) {
        va[k] = 2.0f * uniform() - 1.0f;
        vb[k] = 2.0f * uniform() - 1.0f;
    }
    PQP_Model a, b;
    EXPECT(a.BeginModel() == PQP_OK && b.BeginModel() == PQP_OK);
    for (int k = 0; k < n; k++) {
        EXPECT(a.AddTri(&va[9 * k], &va[9 * k + 3], &va[9 * k + 6], k) == PQP_OK);
        EXPECT(b.AddTri(&vb[9 * k], &vb[9 * k + 3], &vb[9 * k + 6], 100 + k) == PQP_OK);
    }
    EXPECT(a.EndModel() == PQP_OK && b.EndModel() == PQP_OK);

    // The view reads back the float coordinates exactly, and a float hierarchy.
    // (Found by id: PQP 1.3 reorders tris as it builds, pqp-rs keeps the order added.)
    int seventh = -1;
    for (int k = 0; k < n; k++)
        if (a.tris[k].id == 7) seventh = k;
    EXPECT(seventh >= 0 && a.tris[seventh].p2[1] == va[9 * 7 + 4]);
    EXPECT(a.num_bvs == 2 * n - 1 && a.b[0].first_child > 0);
    EXPECT(a.child(0)->GetSize() > 0.0f);

    PQP_REAL R1[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, T1[3] = {0, 0, 0};
    for (int pose = 0; pose < 20; pose++) {
        // Model b turned by an angle about z and shifted along x: overlapping to far apart.
        float angle = 0.3f * (float)pose, shift = 0.25f * (float)pose;
        PQP_REAL R2[3][3] = {{cosf(angle), -sinf(angle), 0}, {sinf(angle), cosf(angle), 0}, {0, 0, 1}};
        PQP_REAL T2[3] = {shift, 0.1f, 0};

        // Brute force on the same float inputs, widened.
        long double best = INFINITY;
        int crossing = 0;
        for (int i = 0; i < n; i++) {
            V s[3], t[3];
            for (int v = 0; v < 3; v++) {
                const float *p = &va[9 * i + 3 * v];
                s[v] = V{p[0], p[1], p[2]};
            }
            for (int j = 0; j < n; j++) {
                for (int v = 0; v < 3; v++) {
                    const float *q = &vb[9 * j + 3 * v];
                    long double x = q[0], y = q[1], z = q[2];
                    t[v] = V{(long double)R2[0][0] * x + (long double)R2[0][1] * y + T2[0],
                             (long double)R2[1][0] * x + (long double)R2[1][1] * y + T2[1], z + T2[2]};
                }
                bf::TriTri<long double> r = bf::triangle_triangle(s, t);
                if (r.dist < best) best = r.dist;
                if (r.crossing) crossing++;
            }
        }

        PQP_DistanceResult d;
        EXPECT(PQP_Distance(&d, R1, T1, &a, R2, T2, &b, 0, 0) == PQP_OK);
        EXPECT(fabsl((long double)d.distance - best) <= 1e-6L * (1 + best));
        EXPECT(d.Distance() == d.distance && d.P1() == d.p1);

        PQP_CollideResult c;
        EXPECT(PQP_Collide(&c, R1, T1, &a, R2, T2, &b) == PQP_OK);
        // Crossing pairs are a subset of the colliding pairs (touching ones collide too).
        EXPECT(c.NumPairs() >= crossing);
        EXPECT((c.NumPairs() > 0) == (best == 0));

        PQP_ToleranceResult t;
        float tol = 0.2f;
        if (fabsl(best - tol) > 1e-5L) {
            EXPECT(PQP_Tolerance(&t, R1, T1, &a, R2, T2, &b, tol) == PQP_OK);
            EXPECT(t.closer_than_tolerance == (best <= tol ? 1 : 0));
            EXPECT(t.tolerance == tol);
        }
    }

    if (failures != 0) return 1;
    printf("all checks passed\n");
    return 0;
}
