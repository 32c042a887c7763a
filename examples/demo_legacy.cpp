// demo_legacy.cpp -- a program written for PQP 1.3, unchanged: it includes "PQP.h", builds two
// models from .tris files, sweeps one through the other, and prints collision, distance and
// tolerance answers with their timings. Built against pqp-rs's PQP.h it runs on pqp-rs.
//
// Usage: demo_legacy [bunny.tris [torus.tris]]
// A .tris file holds the triangle count n, then n triangles as nine numbers x1 y1 z1 ... z3.
#include "PQP.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

// Where the default models are: the build gives the absolute path of examples/models, so the
// program finds them from any working directory.
#ifndef PQP_MODELS_DIR
#define PQP_MODELS_DIR "examples/models"
#endif

static double now_secs()
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Reads a .tris file into m; the triangle ids are their indices. Returns false on failure.
static bool load(PQP_Model &m, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "cannot open %s\n", path);
        return false;
    }
    int n = 0;
    if (fscanf(f, "%d", &n) != 1 || n <= 0) {
        fprintf(stderr, "%s: bad triangle count\n", path);
        fclose(f);
        return false;
    }
    m.BeginModel(n);
    for (int i = 0; i < n; i++) {
        PQP_REAL p[3][3];
        for (int k = 0; k < 9; k++) {
            double v;
            if (fscanf(f, "%lf", &v) != 1) {
                fprintf(stderr, "%s: truncated at triangle %d\n", path, i);
                fclose(f);
                return false;
            }
            p[k / 3][k % 3] = v;
        }
        if (m.AddTri(p[0], p[1], p[2], i) != PQP_OK) {
            fprintf(stderr, "%s: triangle %d refused\n", path, i);
            fclose(f);
            return false;
        }
    }
    fclose(f);
    return m.EndModel() == PQP_OK;
}

// Rotation by angle a about the axis (0, 1, 0).
static void rot_y(PQP_REAL R[3][3], double a)
{
    R[0][0] = cos(a);  R[0][1] = 0; R[0][2] = sin(a);
    R[1][0] = 0;       R[1][1] = 1; R[1][2] = 0;
    R[2][0] = -sin(a); R[2][1] = 0; R[2][2] = cos(a);
}

int main(int argc, char **argv)
{
    const char *bunny_path = argc > 1 ? argv[1] : PQP_MODELS_DIR "/bunny.tris";
    const char *torus_path = argc > 2 ? argv[2] : PQP_MODELS_DIR "/torus.tris";

    PQP_Model bunny, torus;
    double t0 = now_secs();
    if (!load(bunny, bunny_path)) return 1;
    double t1 = now_secs();
    if (!load(torus, torus_path)) return 1;
    double t2 = now_secs();
    printf("bunny: %d triangles, built in %.2f ms, %d bytes\n", bunny.num_tris, 1e3 * (t1 - t0),
           bunny.MemUsage(0));
    printf("torus: %d triangles, built in %.2f ms, %d bytes\n", torus.num_tris, 1e3 * (t2 - t1),
           torus.MemUsage(0));

    PQP_REAL R1[3][3], T1[3] = {0, 0, 0}, R2[3][3], T2[3] = {0, 0, 0};
    rot_y(R1, 0.0);

    // One result object of each kind, reused: the distance and tolerance results keep the last
    // closest triangle pair, which speeds up the next query of a smooth motion.
    PQP_CollideResult cres;
    PQP_DistanceResult dres;
    PQP_ToleranceResult tres;
    const PQP_REAL tolerance = 0.05;

    printf("\nThe torus sweeps through the bunny along x, turning about y.\n");
    printf("%6s | %8s %9s | %12s %9s | %12s %9s | %6s %9s\n", "x", "pairs", "ms", "distance",
           "ms", "approx 5%", "ms", "<0.05?", "ms");
    const int steps = 17;
    double total_c = 0, total_d = 0, total_a = 0, total_t = 0;
    for (int s = 0; s < steps; s++) {
        T2[0] = 2.0 - 4.0 * s / (steps - 1);
        T2[1] = 0.1;
        rot_y(R2, 0.3 * s);

        if (PQP_Collide(&cres, R1, T1, &bunny, R2, T2, &torus) != PQP_OK) return 1;
        int pairs = cres.NumPairs();
        double tc = cres.QueryTimeSecs();

        if (PQP_Distance(&dres, R1, T1, &bunny, R2, T2, &torus, 0.0, 0.0) != PQP_OK) return 1;
        double d = dres.Distance(), td = dres.QueryTimeSecs();

        PQP_DistanceResult approx;
        if (PQP_Distance(&approx, R1, T1, &bunny, R2, T2, &torus, 0.05, 1e30) != PQP_OK) return 1;
        double da = approx.Distance(), ta = approx.QueryTimeSecs();

        if (PQP_Tolerance(&tres, R1, T1, &bunny, R2, T2, &torus, tolerance) != PQP_OK) return 1;
        int closer = tres.CloserThanTolerance();
        double tt = tres.QueryTimeSecs();

        printf("%6.2f | %8d %9.3f | %12.6f %9.3f | %12.6f %9.3f | %6s %9.3f\n", T2[0], pairs,
               1e3 * tc, d, 1e3 * td, da, 1e3 * ta, closer ? "yes" : "no", 1e3 * tt);
        total_c += tc;
        total_d += td;
        total_a += ta;
        total_t += tt;
    }
    printf("\nTotal query time: collide %.2f ms, distance %.2f ms, approximate distance %.2f ms, "
           "tolerance %.2f ms\n",
           1e3 * total_c, 1e3 * total_d, 1e3 * total_a, 1e3 * total_t);
    return 0;
}
