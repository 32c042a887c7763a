/* batch_bench.c -- batch queries (pqp_collide_batch, pqp_distance_batch, pqp_tolerance_batch)
 * against the same n single calls, in one run (BENCHMARKS.md, "Batch queries"). Run by hand; never
 * a test.
 *
 * For each workload and query it times, in each round and in turn: n single calls in a loop (one
 * result object reused, as a planner's loop would), the batch on 1 thread, the batch on 2 threads;
 * it prints the median time over the rounds and the median over the rounds of each round's ratio
 * single / batch (a round's three runs follow one another, so that the ratio is of times measured
 * at nearly the same moment on this shared host), and checks that the batch
 * answers what the single calls answer (approximate distance: single calls searching afresh, as a
 * fresh result does; a last row shows single calls reusing their result, which answer otherwise).
 *
 * Usage: batch_bench [models_dir [rounds]]
 *   models_dir holds torus1.tris, torus2.tris, torus1.path, torus2.path (the tumbling tori) and
 *   bunny.tris, torus.tris; default PQP_BENCH_MODELS_DIR (/work/shared/models).
 * Build: cargo build --release, then
 *   cc -O2 -Iinclude bench/batch_bench.c target/release/libpqp.a -lpthread -ldl -lm -o batch_bench
 * or with the other benchmarks (bench/CMakeLists.txt, target batch_bench). */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */
#include <pqp/pqp.h>

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef PQP_BENCH_MODELS_DIR
#define PQP_BENCH_MODELS_DIR "/work/shared/models"
#endif

#define MAX_ROUNDS 15

/* APPROX: single calls searching afresh (triangle_cache 0), which answer what the batch answers;
 * APPROX_REUSED: single calls reusing their result (other answers, within the same bounds). */
enum query { COLLIDE, DISTANCE, APPROX, APPROX_REUSED, TOLERANCE, NUM_QUERIES };
static const char *const query_name[NUM_QUERIES] = {
    "collide (first contact)", "distance (exact)", "distance (rel 0.1, abs 0.01)",
    "distance (rel 0.1, abs 0.01), single calls reusing the result", "tolerance"};

/* A workload: two models and n pose pairs, as the batch takes them. */
struct workload {
    const char *name;
    pqp_model *m1, *m2;
    size_t n;
    double *R1, *T1, *R2, *T2;
    double tolerance;
};

static double clock_seconds(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Wall-clock seconds. */
static double now(void) { return clock_seconds(CLOCK_MONOTONIC); }

/* CPU seconds of the whole process (every thread). */
static double cpu_now(void) { return clock_seconds(CLOCK_PROCESS_CPUTIME_ID); }

static FILE *open_in(const char *dir, const char *file)
{
    char path[4096];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s", dir, file);
    f = fopen(path, "r");
    if (!f) fprintf(stderr, "cannot open %s\n", path);
    return f;
}

/* A built model from a .tris file (ids are indices), or NULL. */
static pqp_model *load_tris(const char *dir, const char *file)
{
    FILE *f = open_in(dir, file);
    pqp_model *m;
    int n, i, k;
    if (!f) return NULL;
    if (fscanf(f, "%d", &n) != 1 || n <= 0) {
        fclose(f);
        return NULL;
    }
    m = pqp_model_create();
    pqp_model_begin(m, n);
    for (i = 0; i < n; i++) {
        double p[9];
        for (k = 0; k < 9; k++)
            if (fscanf(f, "%lf", &p[k]) != 1) p[k] = NAN;
        if (pqp_model_add_tri(m, p, p + 3, p + 6, i) != PQP_OK) {
            fprintf(stderr, "%s: bad triangle %d\n", file, i);
            fclose(f);
            pqp_model_destroy(m);
            return NULL;
        }
    }
    fclose(f);
    if (pqp_model_end(m) != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

/* The poses of a .path file into R (9 per pose) and T (3 per pose); returns the count, 0 on error. */
static size_t load_path(const char *dir, const char *file, double **R, double **T)
{
    FILE *f = open_in(dir, file);
    int n, i, k;
    if (!f) return 0;
    if (fscanf(f, "%d", &n) != 1 || n <= 0) {
        fclose(f);
        return 0;
    }
    *R = (double *)malloc(9 * (size_t)n * sizeof(double));
    *T = (double *)malloc(3 * (size_t)n * sizeof(double));
    for (i = 0; i < n; i++) {
        for (k = 0; k < 9; k++)
            if (fscanf(f, "%lf", &(*R)[9 * i + k]) != 1) n = 0;
        for (k = 0; k < 3; k++)
            if (fscanf(f, "%lf", &(*T)[3 * i + k]) != 1) n = 0;
    }
    fclose(f);
    return (size_t)n;
}

/* SplitMix64, uniform in [0, 1). */
static double uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}

/* A random rotation from a random unit quaternion, row by row. */
static void random_rotation(uint64_t *s, double *R)
{
    double q[4], len = 0;
    int k;
    do {
        len = 0;
        for (k = 0; k < 4; k++) {
            q[k] = 2 * uniform(s) - 1;
            len += q[k] * q[k];
        }
    } while (len > 1 || len < 1e-6);
    len = sqrt(len);
    for (k = 0; k < 4; k++) q[k] /= len;
    R[0] = 1 - 2 * (q[2] * q[2] + q[3] * q[3]);
    R[1] = 2 * (q[1] * q[2] - q[3] * q[0]);
    R[2] = 2 * (q[1] * q[3] + q[2] * q[0]);
    R[3] = 2 * (q[1] * q[2] + q[3] * q[0]);
    R[4] = 1 - 2 * (q[1] * q[1] + q[3] * q[3]);
    R[5] = 2 * (q[2] * q[3] - q[1] * q[0]);
    R[6] = 2 * (q[1] * q[3] - q[2] * q[0]);
    R[7] = 2 * (q[2] * q[3] + q[1] * q[0]);
    R[8] = 1 - 2 * (q[1] * q[1] + q[2] * q[2]);
}

/* The single calls of query q over the workload, one result reused; answers to ans (as doubles). */
static void run_single(const struct workload *w, enum query q, double *ans)
{
    pqp_collide_result *c = pqp_collide_result_create();
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_tolerance_result *t = pqp_tolerance_result_create();
    pqp_search_options fresh = pqp_search_options_default();
    size_t i;
    fresh.triangle_cache = 0;
    for (i = 0; i < w->n; i++) {
        const double *R1 = w->R1 + 9 * i, *T1 = w->T1 + 3 * i;
        const double *R2 = w->R2 + 9 * i, *T2 = w->T2 + 3 * i;
        switch (q) {
        case COLLIDE:
            pqp_collide(c, R1, T1, w->m1, R2, T2, w->m2, PQP_FIRST_CONTACT);
            ans[i] = pqp_collide_result_colliding(c);
            break;
        case DISTANCE:
            pqp_distance(d, R1, T1, w->m1, R2, T2, w->m2, 0.0, 0.0, 2);
            ans[i] = pqp_distance_result_distance(d);
            break;
        case APPROX:
            pqp_distance_search(d, R1, T1, w->m1, R2, T2, w->m2, 0.1, 0.01, &fresh);
            ans[i] = pqp_distance_result_distance(d);
            break;
        case APPROX_REUSED:
            pqp_distance(d, R1, T1, w->m1, R2, T2, w->m2, 0.1, 0.01, 2);
            ans[i] = pqp_distance_result_distance(d);
            break;
        default:
            pqp_tolerance(t, R1, T1, w->m1, R2, T2, w->m2, w->tolerance, 2);
            ans[i] = pqp_tolerance_result_closer_than_tolerance(t);
            break;
        }
    }
    pqp_collide_result_destroy(c);
    pqp_distance_result_destroy(d);
    pqp_tolerance_result_destroy(t);
}

/* The batch of query q on `threads` threads; answers to ans (as doubles). */
static int run_batch(const struct workload *w, enum query q, unsigned threads, double *ans,
                     int *ints)
{
    int rc;
    size_t i;
    switch (q) {
    case COLLIDE:
        rc = pqp_collide_batch(ints, w->n, w->R1, w->T1, w->m1, w->R2, w->T2, w->m2,
                               PQP_FIRST_CONTACT, threads);
        break;
    case DISTANCE:
        return pqp_distance_batch(ans, w->n, w->R1, w->T1, w->m1, w->R2, w->T2, w->m2, 0.0, 0.0,
                                  threads);
    case APPROX:
    case APPROX_REUSED:
        return pqp_distance_batch(ans, w->n, w->R1, w->T1, w->m1, w->R2, w->T2, w->m2, 0.1, 0.01,
                                  threads);
    default:
        rc = pqp_tolerance_batch(ints, w->n, w->R1, w->T1, w->m1, w->R2, w->T2, w->m2,
                                 w->tolerance, threads);
        break;
    }
    for (i = 0; i < w->n; i++) ans[i] = ints[i];
    return rc;
}

static double median(double *v, int n);

/* Where the spin loops leave their results, so that the compiler keeps them. */
static volatile uint64_t spin_sink;

/* A CPU-bound loop with no memory traffic: what two threads can gain on this machine right now. */
static void *spin(void *arg)
{
    uint64_t x = 1, i, n = *(const uint64_t *)arg;
    for (i = 0; i < n; i++) x = x * 6364136223846793005ull + i;
    *(uint64_t *)arg = x;
    return NULL;
}

/* The speed-up of the spin loop split on 2 threads over 1 thread (median of 3): a control for the
 * batches' speed-up, since other processes share the cores. */
static double machine_scaling(void)
{
    double r[3];
    int k;
    for (k = 0; k < 3; k++) {
        uint64_t whole = 100000000, half1 = whole / 2, half2 = whole / 2;
        pthread_t t;
        double start = now(), one, two;
        spin(&whole);
        one = now() - start;
        start = now();
        if (pthread_create(&t, NULL, spin, &half1) != 0) return 0;
        spin(&half2);
        pthread_join(t, NULL);
        two = now() - start;
        spin_sink = whole ^ half1 ^ half2;
        r[k] = one / two;
    }
    return median(r, 3);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof v[0], cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Times one query on one workload and prints its table row; returns the mismatches found. */
static size_t bench_query(const struct workload *w, enum query q, int rounds)
{
    double *single = (double *)malloc(w->n * sizeof(double));
    double *batch = (double *)malloc(w->n * sizeof(double));
    int *ints = (int *)malloc(w->n * sizeof(int));
    double t[3][MAX_ROUNDS], cpu[3][MAX_ROUNDS], med[3], cpu_med[3], speedup[3][MAX_ROUNDS];
    const unsigned threads[3] = {0, 1, 2}; /* index 0: single calls */
    size_t i, mismatches = 0, positive = 0;
    int r, k;
    for (r = 0; r < rounds; r++) {
        for (k = 0; k < 3; k++) {
            /* Alternate the order between rounds, so that no variant always runs first. */
            int v = (r % 2) ? 2 - k : k;
            double start = now(), cpu_start = cpu_now();
            if (v == 0) {
                run_single(w, q, single);
            } else if (run_batch(w, q, threads[v], batch, ints) != PQP_OK) {
                fprintf(stderr, "batch failed\n");
                exit(1);
            }
            t[v][r] = now() - start;
            cpu[v][r] = cpu_now() - cpu_start;
            /* Reused results answer approximate queries otherwise (within the same bounds). */
            if (v != 0 && q != APPROX_REUSED)
                for (i = 0; i < w->n; i++) mismatches += batch[i] != single[i];
        }
    }
    /* The single calls ran first in round 0: `single` holds their answers from then on. */
    for (i = 0; i < w->n; i++) positive += single[i] > 0;
    for (r = 0; r < rounds; r++)
        for (k = 1; k < 3; k++) speedup[k][r] = t[0][r] / t[k][r];
    for (k = 0; k < 3; k++) {
        med[k] = median(t[k], rounds);
        cpu_med[k] = median(cpu[k], rounds);
    }
    printf("| %s | %s | %zu | %.2f | %.2f | %.2f | %.2fx | %.2fx | %.3f | %.3f |\n", w->name,
           query_name[q], positive, 1e6 * med[0] / (double)w->n, 1e6 * med[1] / (double)w->n,
           1e6 * med[2] / (double)w->n, median(speedup[1], rounds), median(speedup[2], rounds),
           cpu_med[1] / cpu_med[0], cpu_med[2] / cpu_med[0]);
    free(single);
    free(batch);
    free(ints);
    return mismatches;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : PQP_BENCH_MODELS_DIR;
    int rounds = argc > 2 ? atoi(argv[2]) : 5;
    struct workload w[2];
    double *R1 = NULL, *T1 = NULL;
    size_t n1, i, mismatches = 0;
    uint64_t seed = 21;
    int k, q;
    if (rounds < 1 || rounds > MAX_ROUNDS) rounds = 5;

    /* The tumbling tori: 2398 frames of coherent motion. */
    w[0].name = "tumbling tori (path)";
    w[0].m1 = load_tris(dir, "torus1.tris");
    w[0].m2 = load_tris(dir, "torus2.tris");
    n1 = load_path(dir, "torus1.path", &R1, &T1);
    w[0].n = load_path(dir, "torus2.path", &w[0].R2, &w[0].T2);
    w[0].R1 = R1;
    w[0].T1 = T1;
    w[0].tolerance = 0.02;
    /* The bunny and the torus at 4000 random poses, the torus within reach of the bunny. */
    w[1].name = "bunny-torus (random)";
    w[1].m1 = load_tris(dir, "bunny.tris");
    w[1].m2 = load_tris(dir, "torus.tris");
    w[1].n = 4000;
    w[1].R1 = (double *)malloc(9 * w[1].n * sizeof(double));
    w[1].T1 = (double *)calloc(3 * w[1].n, sizeof(double));
    w[1].R2 = (double *)malloc(9 * w[1].n * sizeof(double));
    w[1].T2 = (double *)malloc(3 * w[1].n * sizeof(double));
    w[1].tolerance = 0.02;
    for (i = 0; i < w[1].n; i++) {
        static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(w[1].R1 + 9 * i, I3, sizeof I3);
        random_rotation(&seed, w[1].R2 + 9 * i);
        for (k = 0; k < 3; k++) w[1].T2[3 * i + k] = 2.4 * uniform(&seed) - 1.2;
    }
    if (!w[0].m1 || !w[0].m2 || !w[1].m1 || !w[1].m2 || n1 != w[0].n || n1 == 0) {
        fprintf(stderr, "cannot load the models of %s\n", dir);
        return 1;
    }

    printf("control before: a CPU-bound loop on 2 threads runs %.2fx faster than on 1\n",
           machine_scaling());
    printf("%d rounds, median; wall-clock us per query; speed-up: time of the n single calls / "
           "time of the batch in the same round; CPU: the process's CPU time for the batch / for "
           "the single calls\n\n",
           rounds);
    printf("| workload | query | answers > 0 | single us | batch 1 thread us | batch 2 threads us "
           "| speed-up 1 thread | speed-up 2 threads | CPU 1 thread | CPU 2 threads |\n");
    printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (k = 0; k < 2; k++)
        for (q = 0; q < NUM_QUERIES; q++) mismatches += bench_query(&w[k], (enum query)q, rounds);
    printf("\nanswers differing between the batches and single calls: %zu\n", mismatches);
    printf("control after: a CPU-bound loop on 2 threads runs %.2fx faster than on 1\n",
           machine_scaling());
    for (k = 0; k < 2; k++) {
        pqp_model_destroy(w[k].m1);
        pqp_model_destroy(w[k].m2);
        free(w[k].R1);
        free(w[k].T1);
        free(w[k].R2);
        free(w[k].T2);
    }
    return mismatches != 0;
}
