/* Create/destroy loops (run under AddressSanitizer with leak detection to find leaks and double
 * frees), results outliving the models they answered about, and results reused across models. */
#include <pqp/pqp.h>

#include <math.h>

#include "check.h"
#include "shapes.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};

static void empty_create_destroy(void)
{
    int i;
    for (i = 0; i < 1000; i++) {
        pqp_model *m = pqp_model_create();
        pqp_collide_result *c = pqp_collide_result_create();
        pqp_distance_result *d = pqp_distance_result_create();
        pqp_tolerance_result *t = pqp_tolerance_result_create();
        CHECK(m && c && d && t);
        pqp_tolerance_result_destroy(t);
        pqp_distance_result_destroy(d);
        pqp_collide_result_destroy(c);
        pqp_model_destroy(m);
    }
}

/* Models destroyed in every build state. */
static void destroy_in_every_state(void)
{
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    int i;
    for (i = 0; i < 200; i++) {
        pqp_model *m = pqp_model_create();
        int k, n = i % 7;
        if (i % 4 >= 1) pqp_model_begin(m, n);
        for (k = 0; k < n; k++) pqp_model_add_tri(m, a, b, c, k);
        if (i % 4 >= 2) pqp_model_end(m);
        if (i % 4 == 3) pqp_model_begin(m, 3); /* cleared again */
        pqp_model_destroy(m);
    }
}

static void build_query_destroy_loop(void)
{
    int i;
    for (i = 0; i < 200; i++) {
        pqp_model *a = shapes_unit_box();
        pqp_model *b = shapes_fence(1 + i % 9);
        pqp_collide_result *c = pqp_collide_result_create();
        pqp_distance_result *d = pqp_distance_result_create();
        pqp_tolerance_result *t = pqp_tolerance_result_create();
        double T2[3];
        CHECK(a && b && c && d && t);
        if (!a || !b || !c || !d || !t) return;
        T2[0] = -0.5 + 0.01 * i;
        T2[1] = 0.1;
        T2[2] = 0.1;
        CHECK_EQ(pqp_collide(c, I3, ZERO3, a, I3, T2, b, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_distance(d, I3, ZERO3, a, I3, T2, b, 0.0, 0.0, 2 + i % 3), PQP_OK);
        CHECK_EQ(pqp_tolerance(t, I3, ZERO3, a, I3, T2, b, 0.05, 2), PQP_OK);
        if (i % 2) pqp_collide_result_free_pairs(c);
        /* Results are destroyed after the models they answered about, half of the time. */
        if (i % 2) {
            pqp_model_destroy(a);
            pqp_model_destroy(b);
        }
        pqp_tolerance_result_destroy(t);
        pqp_distance_result_destroy(d);
        pqp_collide_result_destroy(c);
        if (!(i % 2)) {
            pqp_model_destroy(a);
            pqp_model_destroy(b);
        }
    }
}

/* A distance result keeps its answer after its models are gone, and can then be used with other
 * models: its triangle cache is not applied to models it did not come from. */
static void result_outlives_models(void)
{
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_model *small = shapes_fence(3);
    pqp_model *box = shapes_unit_box();
    double T2[3] = {0.0, 0.0, 3.0}, dist;
    int i;
    CHECK(d && small && box);
    if (!d || !small || !box) return;
    CHECK_EQ(pqp_distance(d, I3, ZERO3, small, I3, T2, box, 0.0, 0.0, 2), PQP_OK);
    dist = pqp_distance_result_distance(d);
    CHECK_NEAR(dist, 2.0, 1e-12); /* fence tops out at z = 1; the box starts at z = 3 */
    pqp_model_destroy(small);
    pqp_model_destroy(box);
    CHECK(pqp_distance_result_distance(d) == dist);
    CHECK(pqp_distance_result_p1(d) != NULL);
    for (i = 0; i < 20; i++) {
        pqp_model *a = shapes_unit_box();
        pqp_model *b = shapes_fence(1 + i);
        double T[3] = {0.0, 0.0, 2.5};
        CHECK_EQ(pqp_distance(d, I3, ZERO3, b, I3, T, a, 0.0, 0.0, 2), PQP_OK);
        CHECK_NEAR(pqp_distance_result_distance(d), 1.5, 1e-12);
        pqp_model_destroy(a);
        pqp_model_destroy(b);
    }
    pqp_distance_result_destroy(d);
}

int main(void)
{
    empty_create_destroy();
    destroy_in_every_state();
    build_query_destroy_loop();
    result_outlives_models();
    CHECK_DONE("lifecycle");
}
