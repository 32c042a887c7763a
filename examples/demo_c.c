/* demo_c.c -- the C interface of pqp-rs: builds two models from .tris files, places them, and asks
 * the three questions, printing the answers with the details PQP never gave (overlap flag, the ids
 * of the closest triangles, closest points while overlapping) and error codes for bad input.
 *
 * Usage: demo_c [bunny.tris [torus.tris]]
 * A .tris file holds the triangle count n, then n triangles as nine numbers x1 y1 z1 ... z3. */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Where the default models are: the build gives the absolute path of examples/models, so the
 * program finds them from any working directory. */
#ifndef PQP_MODELS_DIR
#define PQP_MODELS_DIR "examples/models"
#endif

/* Reads a .tris file into a new built model (triangle ids are indices), or returns NULL. */
static pqp_model *load(const char *path)
{
    FILE *f = fopen(path, "r");
    pqp_model *m;
    int n = 0, i, k, rc;
    if (!f) {
        fprintf(stderr, "cannot open %s\n", path);
        return NULL;
    }
    if (fscanf(f, "%d", &n) != 1 || n <= 0) {
        fprintf(stderr, "%s: bad triangle count\n", path);
        fclose(f);
        return NULL;
    }
    m = pqp_model_create();
    if (!m) {
        fclose(f);
        return NULL;
    }
    pqp_model_begin(m, n);
    for (i = 0; i < n; i++) {
        double p[9];
        for (k = 0; k < 9; k++) {
            if (fscanf(f, "%lf", &p[k]) != 1) {
                fprintf(stderr, "%s: truncated at triangle %d\n", path, i);
                fclose(f);
                pqp_model_destroy(m);
                return NULL;
            }
        }
        rc = pqp_model_add_tri(m, p, p + 3, p + 6, i);
        if (rc != PQP_OK) {
            fprintf(stderr, "%s: triangle %d: %s\n", path, i, pqp_error_string(rc));
            fclose(f);
            pqp_model_destroy(m);
            return NULL;
        }
    }
    fclose(f);
    rc = pqp_model_end(m);
    if (rc != PQP_OK) {
        fprintf(stderr, "%s: %s\n", path, pqp_error_string(rc));
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

static void print_distance(const char *what, const pqp_distance_result *r)
{
    const double *p1 = pqp_distance_result_p1(r), *p2 = pqp_distance_result_p2(r);
    printf("%s: distance %.9f%s, triangles %d and %d, p1 (%.4f %.4f %.4f), p2 (%.4f %.4f %.4f),"
           " %lld volume and %lld triangle tests, %.3f ms\n",
           what, pqp_distance_result_distance(r),
           pqp_distance_result_overlap(r) ? " (overlap)" : "", pqp_distance_result_id1(r),
           pqp_distance_result_id2(r), p1[0], p1[1], p1[2], p2[0], p2[1], p2[2],
           (long long)pqp_distance_result_num_bv_tests(r),
           (long long)pqp_distance_result_num_tri_tests(r),
           1e3 * pqp_distance_result_query_time_secs(r));
}

int main(int argc, char **argv)
{
    const char *bunny_path = argc > 1 ? argv[1] : PQP_MODELS_DIR "/bunny.tris";
    const char *torus_path = argc > 2 ? argv[2] : PQP_MODELS_DIR "/torus.tris";
    /* Poses: R row by row (columns are the model's axes in the world), T a translation. */
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double origin[3] = {0, 0, 0};
    double R2[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0}; /* the torus stood up: +90 degrees about x */
    double T2[3] = {1.2, 0.0, 0.0};
    pqp_model *bunny, *torus;
    pqp_collide_result *c;
    pqp_distance_result *d;
    pqp_tolerance_result *t;
    int rc, k;

    printf("pqp-rs %s\n", pqp_version());
    bunny = load(bunny_path);
    torus = load(torus_path);
    if (!bunny || !torus) return 1;
    printf("bunny: %d triangles, %llu bytes; torus: %d triangles, %llu bytes\n",
           pqp_model_num_tris(bunny), (unsigned long long)pqp_model_memory_usage(bunny),
           pqp_model_num_tris(torus), (unsigned long long)pqp_model_memory_usage(torus));

    c = pqp_collide_result_create();
    d = pqp_distance_result_create();
    t = pqp_tolerance_result_create();
    if (!c || !d || !t) return 1;

    /* Apart. */
    rc = pqp_distance(d, I, origin, bunny, R2, T2, torus, 0.0, 0.0, 2);
    if (rc != PQP_OK) return 1;
    print_distance("torus at x = 1.2", d);
    rc = pqp_tolerance(t, I, origin, bunny, R2, T2, torus, 0.1, 2);
    if (rc != PQP_OK) return 1;
    printf("  within 0.1? %s (distance bound %.6f)\n",
           pqp_tolerance_result_closer_than_tolerance(t) ? "yes" : "no",
           pqp_tolerance_result_distance(t));

    /* Moved into the bunny: collision, and the distance result reports the overlap with a point
     * common to both models. */
    T2[0] = 0.3;
    rc = pqp_collide(c, I, origin, bunny, R2, T2, torus, PQP_ALL_CONTACTS);
    if (rc != PQP_OK) return 1;
    printf("torus at x = 0.3: %d colliding triangle pairs (%.3f ms); the first ones:",
           pqp_collide_result_num_pairs(c), 1e3 * pqp_collide_result_query_time_secs(c));
    for (k = 0; k < pqp_collide_result_num_pairs(c) && k < 5; k++)
        printf(" (%d, %d)", pqp_collide_result_id1(c, k), pqp_collide_result_id2(c, k));
    printf("\n");
    rc = pqp_distance(d, I, origin, bunny, R2, T2, torus, 0.0, 0.0, 2);
    if (rc != PQP_OK) return 1;
    print_distance("torus at x = 0.3", d);

    /* Bad input is refused with a code, never a crash or a wrong answer. */
    T2[1] = NAN;
    rc = pqp_distance(d, I, origin, bunny, R2, T2, torus, 0.0, 0.0, 2);
    printf("NaN in a pose: %d (%s)\n", rc, pqp_error_string(rc));
    rc = pqp_distance(d, I, origin, bunny, R2, origin, torus, -1.0, 0.0, 2);
    printf("negative rel_err: %d (%s)\n", rc, pqp_error_string(rc));
    rc = pqp_collide(c, I, origin, NULL, R2, origin, torus, PQP_ALL_CONTACTS);
    printf("NULL model: %d (%s)\n", rc, pqp_error_string(rc));

    pqp_tolerance_result_destroy(t);
    pqp_distance_result_destroy(d);
    pqp_collide_result_destroy(c);
    pqp_model_destroy(torus);
    pqp_model_destroy(bunny);
    return 0;
}
