/* Every bad call of the C ABI returns its documented code (or fallback value), never crashes,
 * and leaves results as they were. */
#include <pqp/pqp.h>

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};
static const double FAR3[3] = {5, 0, 0};

static void null_handles_and_getters(void)
{
    double p[3] = {0, 0, 0};

    /* Destroy functions accept NULL. */
    pqp_model_destroy(NULL);
    pqp_collide_result_destroy(NULL);
    pqp_distance_result_destroy(NULL);
    pqp_tolerance_result_destroy(NULL);
    pqp_collide_result_free_pairs(NULL);

    /* Model functions. */
    CHECK_EQ(pqp_model_begin(NULL, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_add_tri(NULL, p, p, p, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_end(NULL), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_num_tris(NULL), 0);
    CHECK_EQ(pqp_model_memory_usage(NULL), 0);
    CHECK_EQ(pqp_model_is_built(NULL), 0);

    /* Collision getters. */
    CHECK_EQ(pqp_collide_result_colliding(NULL), 0);
    CHECK_EQ(pqp_collide_result_num_pairs(NULL), 0);
    CHECK_EQ(pqp_collide_result_id1(NULL, 0), -1);
    CHECK_EQ(pqp_collide_result_id2(NULL, 0), -1);
    CHECK(pqp_collide_result_pairs(NULL) == NULL);
    CHECK_EQ(pqp_collide_result_num_bv_tests(NULL), 0);
    CHECK_EQ(pqp_collide_result_num_tri_tests(NULL), 0);
    CHECK(pqp_collide_result_query_time_secs(NULL) == 0.0);

    /* Distance getters. */
    CHECK(isnan(pqp_distance_result_distance(NULL)));
    CHECK(pqp_distance_result_p1(NULL) == NULL);
    CHECK(pqp_distance_result_p2(NULL) == NULL);
    CHECK_EQ(pqp_distance_result_overlap(NULL), 0);
    CHECK_EQ(pqp_distance_result_id1(NULL), -1);
    CHECK_EQ(pqp_distance_result_id2(NULL), -1);
    CHECK_EQ(pqp_distance_result_num_bv_tests(NULL), 0);
    CHECK_EQ(pqp_distance_result_num_tri_tests(NULL), 0);
    CHECK(pqp_distance_result_query_time_secs(NULL) == 0.0);

    /* Tolerance getters. */
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(NULL), 0);
    CHECK(isnan(pqp_tolerance_result_distance(NULL)));
    CHECK(isnan(pqp_tolerance_result_tolerance(NULL)));
    CHECK(pqp_tolerance_result_p1(NULL) == NULL);
    CHECK(pqp_tolerance_result_p2(NULL) == NULL);
    CHECK_EQ(pqp_tolerance_result_num_bv_tests(NULL), 0);
    CHECK_EQ(pqp_tolerance_result_num_tri_tests(NULL), 0);
    CHECK(pqp_tolerance_result_query_time_secs(NULL) == 0.0);
}

static void null_vertex_pointers(void)
{
    double p[3] = {0, 0, 0}, q[3] = {1, 0, 0}, r[3] = {0, 1, 0};
    pqp_model *m = pqp_model_create();
    CHECK(m != NULL);
    CHECK_EQ(pqp_model_begin(m, 1), PQP_OK);
    CHECK_EQ(pqp_model_add_tri(m, NULL, q, r, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_add_tri(m, p, NULL, r, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_add_tri(m, p, q, NULL, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_num_tris(m), 0);
    CHECK_EQ(pqp_model_add_tri(m, p, q, r, 0), PQP_OK);
    CHECK_EQ(pqp_model_num_tris(m), 1);
    pqp_model_destroy(m);
}

/* Every pointer argument of every query, set to NULL in turn, gives PQP_ERR_NULL_POINTER; the
 * models here need not be built, since pointers are checked first. */
static void null_query_arguments(void)
{
    pqp_model *m = pqp_model_create();
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    int k;
    CHECK(m && cr && dr && tr);
    for (k = 0; k < 7; k++) {
        const double *R1 = k == 1 ? NULL : I3, *T1 = k == 2 ? NULL : ZERO3;
        const double *R2 = k == 4 ? NULL : I3, *T2 = k == 5 ? NULL : FAR3;
        const pqp_model *m1 = k == 3 ? NULL : m, *m2 = k == 6 ? NULL : m;
        CHECK_EQ(pqp_collide(k == 0 ? NULL : cr, R1, T1, m1, R2, T2, m2, PQP_ALL_CONTACTS),
                 PQP_ERR_NULL_POINTER);
        CHECK_EQ(pqp_distance(k == 0 ? NULL : dr, R1, T1, m1, R2, T2, m2, 0.0, 0.0, 2),
                 PQP_ERR_NULL_POINTER);
        CHECK_EQ(pqp_tolerance(k == 0 ? NULL : tr, R1, T1, m1, R2, T2, m2, 0.1, 2),
                 PQP_ERR_NULL_POINTER);
    }
    /* NULL beats any other error (here: unbuilt model and bad arguments). */
    CHECK_EQ(pqp_collide(cr, NULL, ZERO3, m, I3, FAR3, m, 99), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_distance(dr, I3, ZERO3, m, I3, FAR3, NULL, -1.0, -1.0, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, NULL, I3, FAR3, m, -1.0, 0), PQP_ERR_NULL_POINTER);
    pqp_tolerance_result_destroy(tr);
    pqp_distance_result_destroy(dr);
    pqp_collide_result_destroy(cr);
    pqp_model_destroy(m);
}

/* PQP 1.3's build protocol. */
static void build_protocol(void)
{
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    pqp_model *m = pqp_model_create();
    CHECK(m != NULL);

    /* End on a fresh model: an empty model (PQP 1.3's EndModel); nothing built. */
    CHECK_EQ(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
    CHECK_EQ(pqp_model_is_built(m), 0);
    CHECK_EQ(pqp_model_num_tris(m), 0);

    /* Begin, no triangles, end: empty model, stays unbuilt. */
    CHECK_EQ(pqp_model_begin(m, 4), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);
    CHECK_EQ(pqp_model_is_built(m), 0);

    /* Begin on a begun model: cleared, out of sequence, but begun: add and end work. */
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 1), PQP_OK);
    CHECK_EQ(pqp_model_num_tris(m), 1);
    CHECK_EQ(pqp_model_begin(m, 4), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_num_tris(m), 0);
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 2), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    CHECK_EQ(pqp_model_is_built(m), 1);
    CHECK_EQ(pqp_model_num_tris(m), 1);

    /* Add after end: ignored. End twice: out of sequence, the model stays built. */
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 3), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_num_tris(m), 1);
    CHECK_EQ(pqp_model_end(m), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_is_built(m), 1);
    CHECK(pqp_model_memory_usage(m) > 0);

    /* Begin on a built model: cleared and begun. */
    CHECK_EQ(pqp_model_begin(m, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_is_built(m), 0);
    CHECK_EQ(pqp_model_num_tris(m), 0);
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 4), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    pqp_model_destroy(m);

    /* Add before begin: begins implicitly. */
    m = pqp_model_create();
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 5), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    CHECK_EQ(pqp_model_is_built(m), 1);
    pqp_model_destroy(m);

    /* Capacity hints are hints: negative and huge ones are fine. */
    m = pqp_model_create();
    CHECK_EQ(pqp_model_begin(m, -5), PQP_OK);
    CHECK_EQ(pqp_model_begin(m, 2147483647), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 6), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    pqp_model_destroy(m);

    /* Degenerate triangles (a segment, a point) are accepted. */
    m = pqp_model_create();
    CHECK_EQ(pqp_model_begin(m, 2), PQP_OK);
    CHECK_EQ(pqp_model_add_tri(m, a, b, b, 7), PQP_OK);
    CHECK_EQ(pqp_model_add_tri(m, c, c, c, 8), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    CHECK_EQ(pqp_model_num_tris(m), 2);
    pqp_model_destroy(m);
}

/* NaN, infinite and huge coordinates are refused; the model stays usable. */
static void nonfinite_vertices(void)
{
    const double bad[] = {NAN, INFINITY, -INFINITY, 1e151, -1e151, DBL_MAX};
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    unsigned i;
    int v, axis;
    pqp_model *m = pqp_model_create();
    CHECK_EQ(pqp_model_begin(m, 8), PQP_OK);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        for (v = 0; v < 3; v++) {
            for (axis = 0; axis < 3; axis++) {
                double p[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
                p[v][axis] = bad[i];
                CHECK_EQ(pqp_model_add_tri(m, p[0], p[1], p[2], 0), PQP_ERR_NONFINITE_COORDINATE);
            }
        }
    }
    CHECK_EQ(pqp_model_num_tris(m), 0);
    /* The largest accepted magnitude is 1e150. */
    a[0] = 1e150;
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 1), PQP_OK);
    a[0] = 0;
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 2), PQP_OK);
    CHECK_EQ(pqp_model_num_tris(m), 2);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    CHECK_EQ(pqp_model_is_built(m), 1);
    pqp_model_destroy(m);
}

/* Queries with unbuilt or empty models. */
static void unbuilt_models(void)
{
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    pqp_model *fresh = pqp_model_create();
    pqp_model *empty = pqp_model_create();
    pqp_model *building = pqp_model_create();
    pqp_model *built = shapes_unit_box();
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    const pqp_model *bad[3];
    int k;
    CHECK(built != NULL);
    pqp_model_begin(empty, 0);
    CHECK_EQ(pqp_model_end(empty), PQP_ERR_BUILD_EMPTY_MODEL);
    pqp_model_add_tri(building, a, b, c, 0);
    bad[0] = fresh;
    bad[1] = empty;
    bad[2] = building;
    for (k = 0; k < 3; k++) {
        CHECK_EQ(pqp_collide(cr, I3, ZERO3, bad[k], I3, FAR3, built, PQP_ALL_CONTACTS),
                 PQP_ERR_UNPROCESSED_MODEL);
        CHECK_EQ(pqp_collide(cr, I3, ZERO3, built, I3, FAR3, bad[k], PQP_FIRST_CONTACT),
                 PQP_ERR_UNPROCESSED_MODEL);
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, bad[k], I3, FAR3, built, 0.0, 0.0, 2),
                 PQP_ERR_UNPROCESSED_MODEL);
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, built, I3, FAR3, bad[k], 0.0, 0.0, 2),
                 PQP_ERR_UNPROCESSED_MODEL);
        CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, bad[k], I3, FAR3, built, 0.5, 2),
                 PQP_ERR_UNPROCESSED_MODEL);
        CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, built, I3, FAR3, bad[k], 0.5, 2),
                 PQP_ERR_UNPROCESSED_MODEL);
    }
    /* Results untouched by the failures. */
    CHECK_EQ(pqp_collide_result_num_pairs(cr), 0);
    CHECK(isinf(pqp_distance_result_distance(dr)));
    CHECK_EQ(pqp_distance_result_id1(dr), -1);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 0);

    pqp_tolerance_result_destroy(tr);
    pqp_distance_result_destroy(dr);
    pqp_collide_result_destroy(cr);
    pqp_model_destroy(fresh);
    pqp_model_destroy(empty);
    pqp_model_destroy(building);
    pqp_model_destroy(built);
}

/* NaN, infinite and huge pose entries, in every entry of every pose argument. */
static void nonfinite_poses(void)
{
    const double bad[] = {NAN, INFINITY, -INFINITY, 1e151, -DBL_MAX};
    pqp_model *box = shapes_unit_box();
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    unsigned i;
    int which, e;
    CHECK(box != NULL);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        for (which = 0; which < 4; which++) {
            int n = which % 2 == 0 ? 9 : 3;
            for (e = 0; e < n; e++) {
                double R1[9], T1[3], R2[9], T2[3];
                memcpy(R1, I3, sizeof R1);
                memcpy(R2, I3, sizeof R2);
                memcpy(T1, ZERO3, sizeof T1);
                memcpy(T2, FAR3, sizeof T2);
                switch (which) {
                case 0: R1[e] = bad[i]; break;
                case 1: T1[e] = bad[i]; break;
                case 2: R2[e] = bad[i]; break;
                default: T2[e] = bad[i]; break;
                }
                CHECK_EQ(pqp_collide(cr, R1, T1, box, R2, T2, box, PQP_ALL_CONTACTS),
                         PQP_ERR_NONFINITE_POSE);
                CHECK_EQ(pqp_distance(dr, R1, T1, box, R2, T2, box, 0.0, 0.0, 2),
                         PQP_ERR_NONFINITE_POSE);
                CHECK_EQ(pqp_tolerance(tr, R1, T1, box, R2, T2, box, 0.5, 2),
                         PQP_ERR_NONFINITE_POSE);
            }
        }
    }
    /* 1e150 is accepted. */
    {
        double T2[3] = {1e150, 0, 0};
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK(pqp_distance_result_distance(dr) > 1e149);
    }
    pqp_tolerance_result_destroy(tr);
    pqp_distance_result_destroy(dr);
    pqp_collide_result_destroy(cr);
    pqp_model_destroy(box);
}

/* Invalid flags, error bounds, tolerances and queue sizes; results keep their last answer. */
static void invalid_arguments(void)
{
    const int bad_flags[] = {0, 3, -1, 4, 2147483647, -2147483647 - 1};
    const double bad_reals[] = {-1.0, -1e-300, -INFINITY, NAN};
    const int bad_qsizes[] = {0, -1, -2147483647 - 1};
    pqp_model *box = shapes_unit_box();
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    unsigned i;
    double d;
    const double *p1;
    double p1_copy[3];
    CHECK(box != NULL);

    /* A valid answer first (boxes 4 apart along x), to see that failures keep it. */
    CHECK_EQ(pqp_collide(cr, I3, ZERO3, box, I3, ZERO3, box, PQP_ALL_CONTACTS), PQP_OK);
    CHECK(pqp_collide_result_num_pairs(cr) > 0);
    CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, FAR3, box, 0.0, 0.0, 2), PQP_OK);
    d = pqp_distance_result_distance(dr);
    CHECK_NEAR(d, 4.0, 1e-12);
    p1 = pqp_distance_result_p1(dr);
    CHECK(p1 != NULL);
    memcpy(p1_copy, p1, sizeof p1_copy);
    CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, box, I3, FAR3, box, 4.5, 2), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 1);

    for (i = 0; i < sizeof bad_flags / sizeof bad_flags[0]; i++) {
        int pairs = pqp_collide_result_num_pairs(cr);
        CHECK_EQ(pqp_collide(cr, I3, ZERO3, box, I3, FAR3, box, bad_flags[i]),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_collide_result_num_pairs(cr), pairs);
    }
    for (i = 0; i < sizeof bad_reals / sizeof bad_reals[0]; i++) {
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, ZERO3, box, bad_reals[i], 0.0, 2),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, ZERO3, box, 0.0, bad_reals[i], 2),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, box, I3, ZERO3, box, bad_reals[i], 2),
                 PQP_ERR_INVALID_ARGUMENT);
    }
    for (i = 0; i < sizeof bad_qsizes / sizeof bad_qsizes[0]; i++) {
        CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, ZERO3, box, 0.0, 0.0, bad_qsizes[i]),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, box, I3, ZERO3, box, 0.5, bad_qsizes[i]),
                 PQP_ERR_INVALID_ARGUMENT);
    }
    /* The results still hold the valid answers. */
    CHECK(pqp_distance_result_distance(dr) == d);
    CHECK(pqp_distance_result_p1(dr)[0] == p1_copy[0] && pqp_distance_result_p1(dr)[1] == p1_copy[1]
          && pqp_distance_result_p1(dr)[2] == p1_copy[2]);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 1);
    CHECK(pqp_tolerance_result_tolerance(tr) == 4.5);

    /* Valid edge values are accepted: both flags, qsize 1, large qsize, infinite abs_err,
     * zero tolerance, infinite tolerance. */
    CHECK_EQ(pqp_collide(cr, I3, ZERO3, box, I3, FAR3, box, PQP_FIRST_CONTACT), PQP_OK);
    CHECK_EQ(pqp_collide_result_colliding(cr), 0);
    CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, FAR3, box, 0.0, 0.0, 1), PQP_OK);
    CHECK_NEAR(pqp_distance_result_distance(dr), 4.0, 1e-12);
    CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, FAR3, box, 0.0, 0.0, 1000), PQP_OK);
    CHECK_NEAR(pqp_distance_result_distance(dr), 4.0, 1e-12);
    CHECK_EQ(pqp_distance(dr, I3, ZERO3, box, I3, FAR3, box, 0.5, INFINITY, 2), PQP_OK);
    CHECK(pqp_distance_result_distance(dr) >= 4.0 - 1e-12);
    CHECK(pqp_distance_result_distance(dr) <= 6.0 + 1e-12);
    CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, box, I3, FAR3, box, 0.0, 2), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 0);
    CHECK_EQ(pqp_tolerance(tr, I3, ZERO3, box, I3, FAR3, box, INFINITY, 2), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 1);

    pqp_tolerance_result_destroy(tr);
    pqp_distance_result_destroy(dr);
    pqp_collide_result_destroy(cr);
    pqp_model_destroy(box);
}

static void texts(void)
{
    int c;
    for (c = -20; c <= 5; c++) {
        const char *s = pqp_error_string(c);
        CHECK(s != NULL && s[0] != '\0');
    }
    CHECK(strcmp(pqp_error_string(PQP_OK), "no error") == 0);
    CHECK(strcmp(pqp_error_string(PQP_ERR_NULL_POINTER), "null pointer") == 0);
    CHECK(strcmp(pqp_error_string(1), "unknown error code") == 0);
    CHECK(strcmp(pqp_error_string(-16), "unknown error code") == 0);
    CHECK(strcmp(pqp_error_string(-2147483647 - 1), "unknown error code") == 0);
    CHECK(strcmp(pqp_version(), "1.0.0") == 0);
    /* Every code has its own text. */
    for (c = PQP_ERR_NOT_A_TRIANGLE_MESH; c <= PQP_OK; c++) {
        int d;
        for (d = c + 1; d <= PQP_OK; d++) CHECK(strcmp(pqp_error_string(c), pqp_error_string(d)) != 0);
    }
}

/* The constants have the documented values (PQP 1.3's first five included). */
static void constants(void)
{
    CHECK_EQ(PQP_OK, 0);
    CHECK_EQ(PQP_ERR_MODEL_OUT_OF_MEMORY, -1);
    CHECK_EQ(PQP_ERR_OUT_OF_MEMORY, -2);
    CHECK_EQ(PQP_ERR_UNPROCESSED_MODEL, -3);
    CHECK_EQ(PQP_ERR_BUILD_OUT_OF_SEQUENCE, -4);
    CHECK_EQ(PQP_ERR_BUILD_EMPTY_MODEL, -5);
    CHECK_EQ(PQP_ERR_NONFINITE_COORDINATE, -6);
    CHECK_EQ(PQP_ERR_NONFINITE_POSE, -7);
    CHECK_EQ(PQP_ERR_INVALID_ARGUMENT, -8);
    CHECK_EQ(PQP_ERR_NULL_POINTER, -9);
    CHECK_EQ(PQP_ERR_INTERNAL, -10);
    CHECK_EQ(PQP_ALL_CONTACTS, 1);
    CHECK_EQ(PQP_FIRST_CONTACT, 2);
    CHECK_EQ(sizeof(pqp_contact_pair), 2 * sizeof(int));
}

int main(void)
{
    constants();
    texts();
    null_handles_and_getters();
    null_vertex_pointers();
    null_query_arguments();
    build_protocol();
    nonfinite_vertices();
    unbuilt_models();
    nonfinite_poses();
    invalid_arguments();
    CHECK_DONE("errors");
}
