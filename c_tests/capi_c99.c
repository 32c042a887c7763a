/* The C ABI from plain C99: the build protocol, every error path of capi_spec.md, NULL handling,
 * "an error leaves the result as it was", result reuse across models, and create/destroy loops (this
 * program also runs under ASan+UBSan with leak checking). Expected answers come from tiny hand-made
 * configurations whose geometry is obvious (unit triangles at integer offsets). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <pqp/pqp.h>

static long passed, failed;

#define CHECK(cond)                                                                                        \
    do {                                                                                                   \
        if (cond) {                                                                                        \
            ++passed;                                                                                      \
        } else {                                                                                           \
            ++failed;                                                                                      \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);                                         \
        }                                                                                                  \
    } while (0)

#define CHECK_RC(expr, want)                                                                               \
    do {                                                                                                   \
        int rc_ = (expr);                                                                                  \
        if (rc_ == (want)) {                                                                               \
            ++passed;                                                                                      \
        } else {                                                                                           \
            ++failed;                                                                                      \
            printf("FAIL %s:%d: %s returned %d (%s), expected %d\n", __FILE__, __LINE__, #expr, rc_,       \
                   pqp_error_string(rc_), (want));                                                         \
        }                                                                                                  \
    } while (0)

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double Z3[3] = {0, 0, 0};

/* Unit right triangle in the plane z = h, shifted by x along x. */
static int add_unit_tri(pqp_model *m, double x, double h, int id) {
    const double a[3] = {x, 0, h}, b[3] = {x + 1, 0, h}, c[3] = {x, 1, h};
    return pqp_model_add_tri(m, a, b, c, id);
}

/* n unit triangles at z = h, side by side along x. */
static pqp_model *strip(int n, double h) {
    pqp_model *m = pqp_model_create();
    int i;
    if (!m) return NULL;
    CHECK_RC(pqp_model_begin(m, n), PQP_OK);
    for (i = 0; i < n; ++i) CHECK_RC(add_unit_tri(m, 2.0 * i, h, i), PQP_OK);
    CHECK_RC(pqp_model_end(m), PQP_OK);
    return m;
}

static void test_misc(void) {
    static const int codes[] = {PQP_OK,
                                PQP_ERR_MODEL_OUT_OF_MEMORY,
                                PQP_ERR_OUT_OF_MEMORY,
                                PQP_ERR_UNPROCESSED_MODEL,
                                PQP_ERR_BUILD_OUT_OF_SEQUENCE,
                                PQP_ERR_BUILD_EMPTY_MODEL,
                                PQP_ERR_NONFINITE_COORDINATE,
                                PQP_ERR_NONFINITE_POSE,
                                PQP_ERR_INVALID_ARGUMENT,
                                PQP_ERR_NULL_POINTER,
                                PQP_ERR_INTERNAL,
                                PQP_ERR_DEGENERATE_POINTS,
                                PQP_ERR_INVALID_CONVEX_MESH,
                                PQP_ERR_BUFFER_TOO_SMALL,
                                PQP_ERR_INVALID_DATA,
                                PQP_ERR_NOT_A_TRIANGLE_MESH};
    size_t i;
    CHECK(PQP_OK == 0 && PQP_ERR_MODEL_OUT_OF_MEMORY == -1 && PQP_ERR_OUT_OF_MEMORY == -2);
    CHECK(PQP_ERR_UNPROCESSED_MODEL == -3 && PQP_ERR_BUILD_OUT_OF_SEQUENCE == -4 && PQP_ERR_BUILD_EMPTY_MODEL == -5);
    CHECK(PQP_ERR_NONFINITE_COORDINATE == -6 && PQP_ERR_NONFINITE_POSE == -7 && PQP_ERR_INVALID_ARGUMENT == -8);
    CHECK(PQP_ERR_NULL_POINTER == -9 && PQP_ERR_INTERNAL == -10);
    CHECK(PQP_ERR_DEGENERATE_POINTS == -11 && PQP_ERR_INVALID_CONVEX_MESH == -12);
    CHECK(PQP_ERR_BUFFER_TOO_SMALL == -13 && PQP_ERR_INVALID_DATA == -14);
    CHECK(PQP_ERR_NOT_A_TRIANGLE_MESH == -15);
    CHECK(PQP_ALL_CONTACTS == 1 && PQP_FIRST_CONTACT == 2);
    CHECK(strcmp(pqp_version(), "1.0.0") == 0);
    for (i = 0; i < sizeof codes / sizeof codes[0]; ++i) {
        const char *s = pqp_error_string(codes[i]);
        CHECK(s != NULL && s[0] != '\0' && strcmp(s, "unknown error code") != 0);
    }
    CHECK(strcmp(pqp_error_string(12345), "unknown error code") == 0);
    CHECK(strcmp(pqp_error_string(-16), "unknown error code") == 0);
}

static void test_null_handling(void) {
    const double p[3] = {0, 0, 0};
    pqp_model *m = strip(1, 0);
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();

    pqp_model_destroy(NULL);
    pqp_collide_result_destroy(NULL);
    pqp_distance_result_destroy(NULL);
    pqp_tolerance_result_destroy(NULL);
    pqp_collide_result_free_pairs(NULL);
    CHECK_RC(pqp_model_begin(NULL, 4), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_model_add_tri(NULL, p, p, p, 0), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_model_end(NULL), PQP_ERR_NULL_POINTER);
    CHECK(pqp_model_num_tris(NULL) == 0 && pqp_model_memory_usage(NULL) == 0 && pqp_model_is_built(NULL) == 0);
    {
        pqp_model *n = pqp_model_create();
        CHECK_RC(pqp_model_begin(n, 1), PQP_OK);
        CHECK_RC(pqp_model_add_tri(n, NULL, p, p, 0), PQP_ERR_NULL_POINTER);
        CHECK_RC(pqp_model_add_tri(n, p, NULL, p, 0), PQP_ERR_NULL_POINTER);
        CHECK_RC(pqp_model_add_tri(n, p, p, NULL, 0), PQP_ERR_NULL_POINTER);
        CHECK(pqp_model_num_tris(n) == 0);
        pqp_model_destroy(n);
    }

    CHECK(pqp_collide_result_colliding(NULL) == 0 && pqp_collide_result_num_pairs(NULL) == 0);
    CHECK(pqp_collide_result_id1(NULL, 0) == -1 && pqp_collide_result_id2(NULL, 0) == -1);
    CHECK(pqp_collide_result_pairs(NULL) == NULL);
    CHECK(isnan(pqp_distance_result_distance(NULL)));
    CHECK(pqp_distance_result_p1(NULL) == NULL && pqp_distance_result_p2(NULL) == NULL);
    CHECK(pqp_distance_result_id1(NULL) == -1 && pqp_distance_result_id2(NULL) == -1);
    CHECK(pqp_distance_result_overlap(NULL) == 0);
    CHECK(pqp_tolerance_result_closer_than_tolerance(NULL) == 0);
    CHECK(pqp_tolerance_result_p1(NULL) == NULL && pqp_tolerance_result_p2(NULL) == NULL);

    /* Every required pointer of every query. */
    CHECK_RC(pqp_collide(NULL, I3, Z3, m, I3, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, NULL, Z3, m, I3, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, I3, NULL, m, I3, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, I3, Z3, NULL, I3, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, I3, Z3, m, NULL, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, NULL, m, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, Z3, NULL, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(NULL, I3, Z3, m, I3, Z3, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, NULL, Z3, m, I3, Z3, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, I3, NULL, m, I3, Z3, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, I3, Z3, NULL, I3, Z3, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, I3, Z3, m, NULL, Z3, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, I3, Z3, m, I3, NULL, m, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_distance(dr, I3, Z3, m, I3, Z3, NULL, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(NULL, I3, Z3, m, I3, Z3, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, NULL, Z3, m, I3, Z3, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, I3, NULL, m, I3, Z3, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, NULL, I3, Z3, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, m, NULL, Z3, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, m, I3, NULL, m, 1, 2), PQP_ERR_NULL_POINTER);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, m, I3, Z3, NULL, 1, 2), PQP_ERR_NULL_POINTER);

    pqp_model_destroy(m);
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(dr);
    pqp_tolerance_result_destroy(tr);
}

static void test_build_protocol(void) {
    pqp_model *m = pqp_model_create();
    pqp_model *ok = strip(2, 0);
    pqp_collide_result *cr = pqp_collide_result_create();
    CHECK(m != NULL && pqp_model_is_built(m) == 0 && pqp_model_num_tris(m) == 0);

    /* end before begin/add: an empty model, as PQP 1.3 says */
    CHECK_RC(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
    /* add before begin begins implicitly */
    CHECK_RC(add_unit_tri(m, 0, 0, 7), PQP_OK);
    CHECK(pqp_model_num_tris(m) == 1 && pqp_model_is_built(m) == 0);
    /* not built yet: queries refuse */
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, Z3, ok, PQP_ALL_CONTACTS), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_RC(pqp_collide(cr, I3, Z3, ok, I3, Z3, m, PQP_ALL_CONTACTS), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_RC(pqp_model_end(m), PQP_OK);
    CHECK(pqp_model_is_built(m) == 1 && pqp_model_num_tris(m) == 1 && pqp_model_memory_usage(m) > 0);
    /* add after end: refused and ignored */
    CHECK_RC(add_unit_tri(m, 5, 0, 8), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK(pqp_model_num_tris(m) == 1 && pqp_model_is_built(m) == 1);
    /* end twice */
    CHECK_RC(pqp_model_end(m), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK(pqp_model_is_built(m) == 1);
    /* the model still answers, with the caller's id */
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, Z3, ok, PQP_ALL_CONTACTS), PQP_OK);
    CHECK(pqp_collide_result_num_pairs(cr) == 1 && pqp_collide_result_id1(cr, 0) == 7 &&
          pqp_collide_result_id2(cr, 0) == 0);
    /* begin on a built model clears it, reports the sequence error, and accepts a new build */
    CHECK_RC(pqp_model_begin(m, 3), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK(pqp_model_num_tris(m) == 0 && pqp_model_is_built(m) == 0);
    CHECK_RC(add_unit_tri(m, 2, 0, 11), PQP_OK);
    CHECK_RC(add_unit_tri(m, 40, 0, 12), PQP_OK);
    CHECK_RC(pqp_model_end(m), PQP_OK);
    CHECK(pqp_model_num_tris(m) == 2 && pqp_model_is_built(m) == 1);
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, Z3, ok, PQP_ALL_CONTACTS), PQP_OK);
    CHECK(pqp_collide_result_num_pairs(cr) == 1 && pqp_collide_result_id1(cr, 0) == 11 &&
          pqp_collide_result_id2(cr, 0) == 1);
    /* begin on a model in the middle of a build also clears it */
    CHECK_RC(pqp_model_begin(m, 0), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_RC(add_unit_tri(m, 0, 0, 1), PQP_OK);
    CHECK_RC(pqp_model_begin(m, -5), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK(pqp_model_num_tris(m) == 0);
    /* begin then end with no triangles: empty model, unusable */
    CHECK_RC(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
    CHECK(pqp_model_is_built(m) == 0);
    CHECK_RC(pqp_collide(cr, I3, Z3, m, I3, Z3, ok, PQP_ALL_CONTACTS), PQP_ERR_UNPROCESSED_MODEL);
    {
        pqp_distance_result *dr = pqp_distance_result_create();
        pqp_tolerance_result *tr = pqp_tolerance_result_create();
        CHECK_RC(pqp_distance(dr, I3, Z3, ok, I3, Z3, m, 0, 0, 2), PQP_ERR_UNPROCESSED_MODEL);
        CHECK_RC(pqp_tolerance(tr, I3, Z3, m, I3, Z3, ok, 1, 2), PQP_ERR_UNPROCESSED_MODEL);
        pqp_distance_result_destroy(dr);
        pqp_tolerance_result_destroy(tr);
    }
    /* a fresh model ended right away */
    {
        pqp_model *e = pqp_model_create();
        CHECK_RC(pqp_model_begin(e, 10), PQP_OK);
        CHECK_RC(pqp_model_end(e), PQP_ERR_BUILD_EMPTY_MODEL);
        pqp_model_destroy(e);
    }
    pqp_model_destroy(m);
    pqp_model_destroy(ok);
    pqp_collide_result_destroy(cr);
}

static void test_coordinates(void) {
    const double inf = HUGE_VAL, nan_ = nan("");
    const double big = 1e151, edge = 1e150;
    const double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    double bad[3] = {0, 0, 0};
    const double *vals[3];
    double v[3];
    int k, which;
    pqp_model *m = pqp_model_create();
    CHECK_RC(pqp_model_begin(m, 4), PQP_OK);
    v[0] = nan_;
    v[1] = inf;
    v[2] = big;
    for (k = 0; k < 3; ++k)
        for (which = 0; which < 3; ++which) {
            bad[0] = 0;
            bad[1] = 0;
            bad[2] = 0;
            bad[which] = v[k];
            vals[0] = o;
            vals[1] = x;
            vals[2] = y;
            vals[k] = bad;
            CHECK_RC(pqp_model_add_tri(m, vals[0], vals[1], vals[2], 100 + k), PQP_ERR_NONFINITE_COORDINATE);
        }
    bad[0] = -inf;
    bad[1] = 0;
    bad[2] = 0;
    CHECK_RC(pqp_model_add_tri(m, o, x, bad, 1), PQP_ERR_NONFINITE_COORDINATE);
    CHECK(pqp_model_num_tris(m) == 0);
    /* degenerate triangles are accepted */
    CHECK_RC(pqp_model_add_tri(m, o, o, o, 2), PQP_OK);
    CHECK_RC(pqp_model_add_tri(m, o, x, x, 3), PQP_OK);
    CHECK_RC(pqp_model_add_tri(m, o, x, y, 4), PQP_OK);
    CHECK(pqp_model_num_tris(m) == 3);
    CHECK_RC(pqp_model_end(m), PQP_OK);
    {
        /* the refusals left the model usable: a unit triangle 0.5 above the plane z = 0 of the point,
         * the segment and the triangle is 0.5 away */
        pqp_model *u = strip(1, 0.5);
        pqp_distance_result *dr = pqp_distance_result_create();
        CHECK_RC(pqp_distance(dr, I3, Z3, m, I3, Z3, u, 0, 0, 2), PQP_OK);
        CHECK(fabs(pqp_distance_result_distance(dr) - 0.5) < 1e-12);
        /* |x| = 1e150 is still accepted (no accuracy is asked of such a model, only an answer) */
        {
            pqp_model *h = pqp_model_create();
            bad[0] = edge;
            bad[1] = 0;
            bad[2] = 0;
            CHECK_RC(pqp_model_add_tri(h, bad, o, y, 1), PQP_OK);
            CHECK_RC(pqp_model_add_tri(h, o, x, y, 2), PQP_OK);
            CHECK_RC(pqp_model_end(h), PQP_OK);
            CHECK(pqp_model_num_tris(h) == 2);
            CHECK_RC(pqp_distance(dr, I3, Z3, h, I3, Z3, u, 0, 0, 2), PQP_OK);
            CHECK(pqp_distance_result_distance(dr) >= 0);
            pqp_model_destroy(h);
        }
        pqp_distance_result_destroy(dr);
        pqp_model_destroy(u);
    }
    pqp_model_destroy(m);
}

static void test_poses_and_arguments(void) {
    pqp_model *a = strip(3, 0), *b = strip(3, 0.25);
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    double R[9], T[3];
    const double bads[4] = {nan(""), HUGE_VAL, -HUGE_VAL, 1e151};
    int i, k;

    CHECK(isinf(pqp_distance_result_distance(dr)) && pqp_distance_result_distance(dr) > 0);
    for (k = 0; k < 4; ++k) {
        for (i = 0; i < 9; ++i) {
            memcpy(R, I3, sizeof R);
            R[i] = bads[k];
            CHECK_RC(pqp_collide(cr, R, Z3, a, I3, Z3, b, PQP_ALL_CONTACTS), PQP_ERR_NONFINITE_POSE);
            CHECK_RC(pqp_distance(dr, I3, Z3, a, R, Z3, b, 0, 0, 2), PQP_ERR_NONFINITE_POSE);
            CHECK_RC(pqp_tolerance(tr, R, Z3, a, I3, Z3, b, 1, 2), PQP_ERR_NONFINITE_POSE);
        }
        for (i = 0; i < 3; ++i) {
            memcpy(T, Z3, sizeof T);
            T[i] = bads[k];
            CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, T, b, PQP_FIRST_CONTACT), PQP_ERR_NONFINITE_POSE);
            CHECK_RC(pqp_distance(dr, I3, T, a, I3, Z3, b, 0, 0, 2), PQP_ERR_NONFINITE_POSE);
            CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, T, b, 1, 2), PQP_ERR_NONFINITE_POSE);
        }
    }
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, Z3, b, 0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, Z3, b, 3), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, Z3, b, -1), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, -0.1, 0, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, nan(""), 0, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, -1e-9, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, nan(""), 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, 0, 0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, 0, -3), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, -1, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, nan(""), 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, 1, 0), PQP_ERR_INVALID_ARGUMENT);
    /* still untouched after all those errors */
    CHECK(isinf(pqp_distance_result_distance(dr)));
    CHECK(pqp_collide_result_num_pairs(cr) == 0 && pqp_collide_result_colliding(cr) == 0);

    /* Errors leave a result as it was: answer, then fail, then compare. Strips 0.25 apart. */
    T[0] = 0;
    T[1] = 0;
    T[2] = -0.25; /* b moved onto a's plane: every aligned pair overlaps (coplanar, identical) */
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, T, b, PQP_ALL_CONTACTS), PQP_OK);
    CHECK(pqp_collide_result_colliding(cr) == 1 && pqp_collide_result_num_pairs(cr) == 3);
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, T, b, 7), PQP_ERR_INVALID_ARGUMENT);
    CHECK(pqp_collide_result_colliding(cr) == 1 && pqp_collide_result_num_pairs(cr) == 3);
    CHECK(pqp_collide_result_pairs(cr) != NULL);
    for (k = 0; k < 3; ++k)
        CHECK(pqp_collide_result_id1(cr, k) == pqp_collide_result_id2(cr, k) && pqp_collide_result_pairs(cr)[k].id1 ==
                                                                                   pqp_collide_result_id1(cr, k));
    CHECK(pqp_collide_result_id1(cr, 3) == -1 && pqp_collide_result_id2(cr, -1) == -1);
    CHECK(pqp_collide_result_num_bv_tests(cr) >= 0 && pqp_collide_result_num_tri_tests(cr) >= 3);
    CHECK(pqp_collide_result_query_time_secs(cr) >= 0);
    pqp_collide_result_free_pairs(cr);
    CHECK(pqp_collide_result_num_pairs(cr) == 0 && pqp_collide_result_pairs(cr) == NULL);
    CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, Z3, b, PQP_FIRST_CONTACT), PQP_OK);
    CHECK(pqp_collide_result_colliding(cr) == 0 && pqp_collide_result_pairs(cr) == NULL);

    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, 0, 2), PQP_OK);
    CHECK(fabs(pqp_distance_result_distance(dr) - 0.25) < 1e-12 && pqp_distance_result_overlap(dr) == 0);
    {
        const double d0 = pqp_distance_result_distance(dr);
        const int i1 = pqp_distance_result_id1(dr), i2 = pqp_distance_result_id2(dr);
        double p1[3], p2[3];
        memcpy(p1, pqp_distance_result_p1(dr), sizeof p1);
        memcpy(p2, pqp_distance_result_p2(dr), sizeof p2);
        CHECK(i1 >= 0 && i1 < 3 && i2 == i1); /* only aligned triangles are 0.25 apart */
        CHECK(fabs(p2[2] - 0.25) < 1e-12 && fabs(p1[2]) < 1e-12);
        CHECK(fabs(p1[0] - p2[0]) < 1e-12 && fabs(p1[1] - p2[1]) < 1e-12);
        CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, Z3, b, 0, 0, 0), PQP_ERR_INVALID_ARGUMENT);
        CHECK(pqp_distance_result_distance(dr) == d0 && pqp_distance_result_id1(dr) == i1 &&
              pqp_distance_result_id2(dr) == i2);
        CHECK(memcmp(p1, pqp_distance_result_p1(dr), sizeof p1) == 0 &&
              memcmp(p2, pqp_distance_result_p2(dr), sizeof p2) == 0);
        CHECK(pqp_distance_result_num_tri_tests(dr) >= 1 && pqp_distance_result_num_bv_tests(dr) >= 0);
        CHECK(pqp_distance_result_query_time_secs(dr) >= 0);
    }
    CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, T, b, 0, 0, 2), PQP_OK);
    CHECK(pqp_distance_result_distance(dr) == 0 && pqp_distance_result_overlap(dr) == 1);

    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, 0.3, 2), PQP_OK);
    CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 1 && pqp_tolerance_result_tolerance(tr) == 0.3);
    CHECK(fabs(pqp_tolerance_result_distance(tr) - 0.25) < 1e-12);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, -2, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 1 && pqp_tolerance_result_tolerance(tr) == 0.3);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, 0.2, 1), PQP_OK);
    CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 0 && pqp_tolerance_result_distance(tr) > 0.2 &&
          pqp_tolerance_result_distance(tr) <= 0.25 + 1e-12);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, Z3, b, 0.25 + 1e-9, 3), PQP_OK);
    CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 1);
    CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, T, b, 0, 2), PQP_OK); /* overlapping: closer than 0 */
    CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 1 && pqp_tolerance_result_distance(tr) == 0);
    CHECK(pqp_tolerance_result_num_bv_tests(tr) >= 0 && pqp_tolerance_result_num_tri_tests(tr) >= 0 &&
          pqp_tolerance_result_query_time_secs(tr) >= 0);

    pqp_model_destroy(a);
    pqp_model_destroy(b);
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(dr);
    pqp_tolerance_result_destroy(tr);
}

/* One distance result reused across different model pairs (its triangle cache then names triangles
 * of other models): answers must match fresh results. */
static void test_result_reuse_across_models(void) {
    pqp_model *ms[4];
    pqp_distance_result *shared = pqp_distance_result_create();
    pqp_tolerance_result *tshared = pqp_tolerance_result_create();
    int i, j, round;
    ms[0] = strip(1, 0);
    ms[1] = strip(40, 3);
    ms[2] = strip(7, -1);
    ms[3] = strip(200, 0.5);
    for (round = 0; round < 3; ++round)
        for (i = 0; i < 4; ++i)
            for (j = 0; j < 4; ++j) {
                pqp_distance_result *fresh = pqp_distance_result_create();
                const double T[3] = {0.5 * round, 0, 0};
                CHECK_RC(pqp_distance(shared, I3, Z3, ms[i], I3, T, ms[j], 0, 0, 2), PQP_OK);
                CHECK_RC(pqp_distance(fresh, I3, Z3, ms[i], I3, T, ms[j], 0, 0, 2), PQP_OK);
                CHECK(fabs(pqp_distance_result_distance(shared) - pqp_distance_result_distance(fresh)) < 1e-12);
                CHECK_RC(pqp_tolerance(tshared, I3, Z3, ms[i], I3, T, ms[j], 0.6, 2), PQP_OK);
                CHECK(pqp_tolerance_result_closer_than_tolerance(tshared) ==
                      (pqp_distance_result_distance(fresh) <= 0.6));
                pqp_distance_result_destroy(fresh);
            }
    for (i = 0; i < 4; ++i) pqp_model_destroy(ms[i]);
    pqp_distance_result_destroy(shared);
    pqp_tolerance_result_destroy(tshared);
}

/* Create/destroy in loops, with error paths mixed in (leaks show under LeakSanitizer). */
static void test_loops(void) {
    int it, k;
    for (it = 0; it < 300; ++it) {
        pqp_model *a = pqp_model_create(), *b = pqp_model_create();
        pqp_collide_result *cr = pqp_collide_result_create();
        pqp_distance_result *dr = pqp_distance_result_create();
        pqp_tolerance_result *tr = pqp_tolerance_result_create();
        const int n = 1 + it % 37;
        const double nanv[3] = {nan(""), 0, 0};
        CHECK(a && b && cr && dr && tr);
        CHECK_RC(pqp_model_begin(a, n), PQP_OK);
        for (k = 0; k < n; ++k) CHECK_RC(add_unit_tri(a, 1.5 * k, 0.01 * (k % 3), k), PQP_OK);
        if (it % 3 == 0) CHECK_RC(pqp_model_add_tri(a, nanv, nanv, nanv, -1), PQP_ERR_NONFINITE_COORDINATE);
        if (it % 5 == 0) { /* abandoned build: destroyed while begun */
            pqp_model_destroy(a);
            a = pqp_model_create();
            CHECK_RC(add_unit_tri(a, 0, 0, 0), PQP_OK);
        }
        CHECK_RC(pqp_model_end(a), PQP_OK);
        for (k = 0; k < 1 + it % 4; ++k) CHECK_RC(add_unit_tri(b, 0.3 * k, 0.2, k), PQP_OK);
        if (it % 7 == 0) { /* an unbuilt model in a query */
            CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, Z3, b, PQP_ALL_CONTACTS), PQP_ERR_UNPROCESSED_MODEL);
        }
        CHECK_RC(pqp_model_end(b), PQP_OK);
        {
            /* b's triangles lie at height h above a's first triangle (which is at z = 0 and overlaps
             * them in x, y); a's other triangles are at 0.01 and 0.02; so the distance is h. */
            const double h = 0.001 * (it % 5), rel = 0.1 * (it % 3), abs_err = 0.01 * (it % 2);
            const double T[3] = {0, 0, h - 0.2};
            const double d_hi = (rel == 0 || abs_err == 0) ? h : fmin(h * (1 + rel), h + abs_err);
            CHECK_RC(pqp_collide(cr, I3, Z3, a, I3, T, b, it % 2 ? PQP_ALL_CONTACTS : PQP_FIRST_CONTACT), PQP_OK);
            CHECK(pqp_collide_result_colliding(cr) == (h == 0));
            CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, T, b, rel, abs_err, 1 + it % 3), PQP_OK);
            CHECK(pqp_distance_result_distance(dr) >= h - 1e-12 && pqp_distance_result_distance(dr) <= d_hi + 1e-12);
            CHECK_RC(pqp_tolerance(tr, I3, Z3, a, I3, T, b, 0.01, 1 + it % 2), PQP_OK);
            CHECK(pqp_tolerance_result_closer_than_tolerance(tr) == 1);
            CHECK_RC(pqp_distance(dr, I3, Z3, a, I3, T, b, -1, 0, 2), PQP_ERR_INVALID_ARGUMENT);
        }
        if (it % 2) pqp_collide_result_free_pairs(cr);
        pqp_model_destroy(a);
        pqp_model_destroy(b);
        pqp_collide_result_destroy(cr);
        pqp_distance_result_destroy(dr);
        pqp_tolerance_result_destroy(tr);
    }
}

int main(void) {
    test_misc();
    test_null_handling();
    test_build_protocol();
    test_coordinates();
    test_poses_and_arguments();
    test_result_reuse_across_models();
    test_loops();
    printf("capi_c99: %ld passed, %ld failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
