/* Self-collision of a closed mesh with no self-intersection (BENCHMARKS.md): a torus of
 * n x n/2 quads (2 triangles each; n = 1000 gives 1,000,000 triangles) through pqp_self_collide,
 * all contacts. Prints each round's wall-clock and thread CPU time, and their medians. The CPU time
 * is what the query costs on a machine shared with other work.
 *
 *   self_collide_bench [n] [rounds]        (defaults 1000 and 7)
 */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <pqp/pqp.h>

static double seconds(clockid_t clock) {
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Vertex (i, j) of the torus (big radius 1, small 0.3), indices taken modulo the grid so that the
 * seam's vertices are bit-identical to the first row's. */
static void vertex(int i, int j, int n, int k, double out[3]) {
    const double tau = 6.283185307179586;
    const double u = tau * (double)(i % n) / (double)n, v = tau * (double)(j % k) / (double)k;
    const double w = 1.0 + 0.3 * cos(v);
    out[0] = w * cos(u);
    out[1] = w * sin(u);
    out[2] = 0.3 * sin(v);
}

static int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    const int n = argc > 1 ? atoi(argv[1]) : 1000, rounds = argc > 2 ? atoi(argv[2]) : 7;
    const int k = n / 2;
    if (n < 4 || rounds < 1 || rounds > 100) {
        fprintf(stderr, "usage: %s [n >= 4] [rounds 1..100]\n", argv[0]);
        return 2;
    }
    pqp_model *m = pqp_model_create();
    int rc = m ? pqp_model_begin(m, 2 * n * k) : PQP_ERR_INTERNAL;
    for (int i = 0; i < n && rc == PQP_OK; ++i)
        for (int j = 0; j < k && rc == PQP_OK; ++j) {
            double a[3], b[3], c[3], d[3];
            vertex(i, j, n, k, a);
            vertex(i + 1, j, n, k, b);
            vertex(i + 1, j + 1, n, k, c);
            vertex(i, j + 1, n, k, d);
            rc = pqp_model_add_tri(m, a, b, c, 2 * (i * k + j));
            if (rc == PQP_OK) rc = pqp_model_add_tri(m, a, c, d, 2 * (i * k + j) + 1);
        }
    const double b0 = seconds(CLOCK_MONOTONIC);
    if (rc == PQP_OK) rc = pqp_model_end(m);
    const double built = seconds(CLOCK_MONOTONIC) - b0;
    pqp_collide_result *r = pqp_collide_result_create();
    if (rc != PQP_OK || !r) {
        fprintf(stderr, "model: rc %d\n", rc);
        return 1;
    }
    printf("closed torus, %d triangles (built in %.0f ms)\n", 2 * n * k, built * 1e3);
    double wall[100], cpu[100];
    for (int round = 0; round < rounds; ++round) {
        const double w0 = seconds(CLOCK_MONOTONIC), c0 = seconds(CLOCK_THREAD_CPUTIME_ID);
        rc = pqp_self_collide(r, m, PQP_ALL_CONTACTS);
        cpu[round] = seconds(CLOCK_THREAD_CPUTIME_ID) - c0;
        wall[round] = seconds(CLOCK_MONOTONIC) - w0;
        if (rc != PQP_OK) {
            fprintf(stderr, "pqp_self_collide: rc %d\n", rc);
            return 1;
        }
        printf("  round %d: %.1f ms wall, %.1f ms CPU, %d pairs\n", round, wall[round] * 1e3, cpu[round] * 1e3,
               pqp_collide_result_num_pairs(r));
    }
    qsort(wall, (size_t)rounds, sizeof wall[0], by_value);
    qsort(cpu, (size_t)rounds, sizeof cpu[0], by_value);
    printf("median of %d: %.1f ms wall, %.1f ms CPU\n", rounds, wall[rounds / 2] * 1e3, cpu[rounds / 2] * 1e3);
    pqp_collide_result_destroy(r);
    pqp_model_destroy(m);
    return 0;
}
