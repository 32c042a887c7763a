/* Answers of the C ABI on geometry whose answers are known by construction: unit boxes at known
 * poses (distances, closest points, overlap), a fence of triangles crossed by a rail (colliding
 * pairs), and result reuse. */
#include <pqp/pqp.h>

#include <math.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
/* Rotation by +90 degrees about z, row by row: (x, y, z) -> (-y, x, z). */
static const double RZ90[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};
static const double UNIT_LO[3] = {0, 0, 0}, UNIT_SIZE[3] = {1, 1, 1};

static void apply(const double R[9], const double T[3], const double p[3], double out[3])
{
    int i;
    for (i = 0; i < 3; i++) out[i] = R[3 * i] * p[0] + R[3 * i + 1] * p[1] + R[3 * i + 2] * p[2] + T[i];
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* The closest points of r lie on the triangles it names, and are `distance` apart in the world. */
static void check_witnesses(const pqp_distance_result *r, const double R1[9], const double T1[3],
                            const double R2[9], const double T2[3])
{
    const double *p1 = pqp_distance_result_p1(r), *p2 = pqp_distance_result_p2(r);
    double w1[3], w2[3], t[3][3];
    int id1 = pqp_distance_result_id1(r), id2 = pqp_distance_result_id2(r);
    CHECK(p1 != NULL && p2 != NULL);
    CHECK(id1 >= 0 && id1 < 12 && id2 >= 0 && id2 < 12);
    if (!p1 || !p2 || id1 < 0 || id1 >= 12 || id2 < 0 || id2 >= 12) return;
    apply(R1, T1, p1, w1);
    apply(R2, T2, p2, w2);
    CHECK_NEAR(dist3(w1, w2), pqp_distance_result_distance(r), 1e-12);
    shapes_box_triangle(UNIT_LO, UNIT_SIZE, id1, t);
    CHECK_NEAR(shapes_point_triangle_distance(p1, t), 0.0, 1e-12);
    shapes_box_triangle(UNIT_LO, UNIT_SIZE, id2, t);
    CHECK_NEAR(shapes_point_triangle_distance(p2, t), 0.0, 1e-12);
}

static void box_distances(void)
{
    pqp_model *box = shapes_unit_box();
    pqp_distance_result *r = pqp_distance_result_create();
    const double *p1, *p2;
    CHECK(box != NULL && r != NULL);
    if (!box || !r) return;

    /* Before any query: +infinity, no ids, zero points. */
    CHECK(isinf(pqp_distance_result_distance(r)) && pqp_distance_result_distance(r) > 0);
    CHECK_EQ(pqp_distance_result_id1(r), -1);
    CHECK_EQ(pqp_distance_result_overlap(r), 0);
    CHECK(pqp_distance_result_p1(r)[0] == 0.0);

    /* Box 2 at x + 1.5: the gap is 0.5 between the faces x = 1 and x = 1.5. */
    {
        double T2[3] = {1.5, 0, 0};
        CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK_NEAR(pqp_distance_result_distance(r), 0.5, 1e-15);
        CHECK_EQ(pqp_distance_result_overlap(r), 0);
        p1 = pqp_distance_result_p1(r);
        p2 = pqp_distance_result_p2(r);
        CHECK_NEAR(p1[0], 1.0, 1e-15);
        CHECK_NEAR(p2[0], 0.0, 1e-15); /* model 2's frame */
        CHECK_NEAR(p1[1], p2[1], 1e-12);
        CHECK_NEAR(p1[2], p2[2], 1e-12);
        CHECK(pqp_distance_result_num_bv_tests(r) >= 1);
        CHECK(pqp_distance_result_num_tri_tests(r) >= 1);
        CHECK(pqp_distance_result_query_time_secs(r) >= 0.0);
        check_witnesses(r, I3, ZERO3, I3, T2);
    }

    /* Box 2 turned +90 degrees about z and put at x + 3: it spans x in [2, 3] (y in [0, 1]), so
     * the distance is 1. With the rotation read transposed it would span x in [3, 4] and the
     * distance would be 2: this checks the row-major convention. The closest point of box 2 is on
     * its world face x = 2, which is its own face y = 1. */
    {
        double T2[3] = {3, 0, 0};
        CHECK_EQ(pqp_distance(r, I3, ZERO3, box, RZ90, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK_NEAR(pqp_distance_result_distance(r), 1.0, 1e-12);
        p1 = pqp_distance_result_p1(r);
        p2 = pqp_distance_result_p2(r);
        CHECK_NEAR(p1[0], 1.0, 1e-12);
        CHECK_NEAR(p2[1], 1.0, 1e-12);
        check_witnesses(r, I3, ZERO3, RZ90, T2);
    }

    /* Both boxes turned the same way, box 2 at R1 * (1.5, 0, 0) = (0, 1.5, 0): the same relative
     * placement as the first case; points are reported in each model's own frame. */
    {
        double T2[3] = {0, 1.5, 0};
        CHECK_EQ(pqp_distance(r, RZ90, ZERO3, box, RZ90, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK_NEAR(pqp_distance_result_distance(r), 0.5, 1e-12);
        CHECK_NEAR(pqp_distance_result_p1(r)[0], 1.0, 1e-12);
        CHECK_NEAR(pqp_distance_result_p2(r)[0], 0.0, 1e-12);
        check_witnesses(r, RZ90, ZERO3, RZ90, T2);
    }

    /* Overlapping boxes: distance 0, overlap flag, and p1, p2 the same world point, on the
     * triangles named by the ids. */
    {
        double T2[3] = {0.5, 0.25, 0.75};
        CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK(pqp_distance_result_distance(r) == 0.0);
        CHECK_EQ(pqp_distance_result_overlap(r), 1);
        check_witnesses(r, I3, ZERO3, I3, T2);
    }

    /* Touching boxes (face to face): distance 0, overlap. */
    {
        double T2[3] = {1, 0, 0};
        CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 0.0, 0.0, 2), PQP_OK);
        CHECK(pqp_distance_result_distance(r) == 0.0);
        CHECK_EQ(pqp_distance_result_overlap(r), 1);
    }

    /* Error bounds: true <= d <= min(true * (1 + rel), true + abs). */
    {
        double T2[3] = {1.5, 0.3, -0.2};
        int q;
        for (q = 1; q <= 8; q *= 2) {
            double d;
            CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 0.1, INFINITY, q), PQP_OK);
            d = pqp_distance_result_distance(r);
            CHECK(d >= 0.5 - 1e-12 && d <= 0.55 + 1e-12);
            CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 10.0, 0.01, q), PQP_OK);
            d = pqp_distance_result_distance(r);
            CHECK(d >= 0.5 - 1e-12 && d <= 0.51 + 1e-12);
            CHECK_EQ(pqp_distance(r, I3, ZERO3, box, I3, T2, box, 10.0, 0.0, q), PQP_OK);
            CHECK_NEAR(pqp_distance_result_distance(r), 0.5, 1e-12);
        }
    }

    /* Reusing the result while box 2 moves (triangle cache) gives the same answers as a fresh
     * result each time. */
    {
        pqp_distance_result *fresh = pqp_distance_result_create();
        int step;
        for (step = 0; step < 50; step++) {
            double T2[3];
            T2[0] = 1.2 + 0.05 * step;
            T2[1] = 0.3 * sin(0.2 * step);
            T2[2] = 0.3 * cos(0.3 * step);
            CHECK_EQ(pqp_distance(r, I3, ZERO3, box, RZ90, T2, box, 0.0, 0.0, 2), PQP_OK);
            CHECK_EQ(pqp_distance(fresh, I3, ZERO3, box, RZ90, T2, box, 0.0, 0.0, 2), PQP_OK);
            CHECK_NEAR(pqp_distance_result_distance(r), pqp_distance_result_distance(fresh),
                       1e-12);
            /* Box 2 spans world x in [T2x - 1, T2x]: the gap to x = 1 is known. */
            {
                double gap = T2[0] - 2.0;
                CHECK_NEAR(pqp_distance_result_distance(r), gap > 0 ? gap : 0.0, 1e-12);
            }
            pqp_distance_result_destroy(fresh);
            fresh = pqp_distance_result_create();
        }
        pqp_distance_result_destroy(fresh);
    }

    pqp_distance_result_destroy(r);
    pqp_model_destroy(box);
}

static int has_pair(const pqp_contact_pair *pairs, int n, int id1, int id2)
{
    int k;
    for (k = 0; k < n; k++)
        if (pairs[k].id1 == id1 && pairs[k].id2 == id2) return 1;
    return 0;
}

/* A fence of 10 triangles (x = 0..9) crossed by a rail of length 3.5 placed at x = 2.5 collides
 * exactly with fence triangles 3, 4, 5 and 6. */
static void fence_pairs(void)
{
    pqp_model *fence = shapes_fence(10);
    pqp_model *rail = shapes_rail(3.5, 99);
    pqp_collide_result *r = pqp_collide_result_create();
    const pqp_contact_pair *pairs;
    int k, n;
    CHECK(fence != NULL && rail != NULL && r != NULL);
    if (!fence || !rail || !r) return;

    CHECK_EQ(pqp_collide_result_colliding(r), 0);
    CHECK(pqp_collide_result_pairs(r) == NULL);

    {
        double T2[3] = {2.5, 0, 0};
        CHECK_EQ(pqp_collide(r, I3, ZERO3, fence, I3, T2, rail, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 1);
        n = pqp_collide_result_num_pairs(r);
        CHECK_EQ(n, 4);
        pairs = pqp_collide_result_pairs(r);
        CHECK(pairs != NULL);
        if (pairs != NULL) {
            for (k = 3; k <= 6; k++) CHECK(has_pair(pairs, n, k, 99));
            for (k = 0; k < n; k++) {
                CHECK_EQ(pqp_collide_result_id1(r, k), pairs[k].id1);
                CHECK_EQ(pqp_collide_result_id2(r, k), pairs[k].id2);
            }
        }
        CHECK_EQ(pqp_collide_result_id1(r, n), -1);
        CHECK_EQ(pqp_collide_result_id2(r, -1), -1);
        CHECK(pqp_collide_result_num_bv_tests(r) >= 1);
        CHECK(pqp_collide_result_num_tri_tests(r) >= 4);
        CHECK(pqp_collide_result_query_time_secs(r) >= 0.0);

        /* First contact: one of them. */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, fence, I3, T2, rail, PQP_FIRST_CONTACT), PQP_OK);
        CHECK_EQ(pqp_collide_result_num_pairs(r), 1);
        CHECK(pqp_collide_result_id1(r, 0) >= 3 && pqp_collide_result_id1(r, 0) <= 6);
        CHECK_EQ(pqp_collide_result_id2(r, 0), 99);

        /* Freeing the list empties it. */
        pqp_collide_result_free_pairs(r);
        CHECK_EQ(pqp_collide_result_num_pairs(r), 0);
        CHECK_EQ(pqp_collide_result_colliding(r), 0);
        CHECK(pqp_collide_result_pairs(r) == NULL);
    }

    /* Models swapped: the ids swap. */
    {
        double T1[3] = {2.5, 0, 0};
        CHECK_EQ(pqp_collide(r, I3, T1, rail, I3, ZERO3, fence, PQP_ALL_CONTACTS), PQP_OK);
        n = pqp_collide_result_num_pairs(r);
        CHECK_EQ(n, 4);
        pairs = pqp_collide_result_pairs(r);
        if (pairs != NULL)
            for (k = 3; k <= 6; k++) CHECK(has_pair(pairs, n, 99, k));
    }

    /* Both models turned the same way: the same relative placement, the same pairs. */
    {
        double T2[3];
        double shift[3] = {5.25, 0, 0};
        apply(RZ90, ZERO3, shift, T2);
        CHECK_EQ(pqp_collide(r, RZ90, ZERO3, fence, RZ90, T2, rail, PQP_ALL_CONTACTS), PQP_OK);
        n = pqp_collide_result_num_pairs(r); /* x in [5.25, 8.75]: 6, 7, 8 */
        CHECK_EQ(n, 3);
        pairs = pqp_collide_result_pairs(r);
        if (pairs != NULL)
            for (k = 6; k <= 8; k++) CHECK(has_pair(pairs, n, k, 99));
    }

    /* Far away: nothing. */
    {
        double T2[3] = {20.5, 0, 0};
        CHECK_EQ(pqp_collide(r, I3, ZERO3, fence, I3, T2, rail, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 0);
        CHECK_EQ(pqp_collide_result_num_pairs(r), 0);
        CHECK(pqp_collide_result_pairs(r) == NULL);
    }

    pqp_collide_result_destroy(r);
    pqp_model_destroy(rail);
    pqp_model_destroy(fence);
}

static void box_collisions(void)
{
    pqp_model *box = shapes_unit_box();
    pqp_collide_result *r = pqp_collide_result_create();
    CHECK(box != NULL && r != NULL);
    if (!box || !r) return;
    {
        double T2[3] = {0.5, 0.5, 0.5}; /* overlapping */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, box, I3, T2, box, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 1);
    }
    {
        double T2[3] = {1.0, 0.0, 0.0}; /* touching face to face: counts as colliding */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, box, I3, T2, box, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 1);
    }
    {
        double T2[3] = {1.0 + 1e-9, 0.0, 0.0}; /* apart */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, box, I3, T2, box, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 0);
    }
    {
        double T2[3] = {2.5, 0.5, 0.0}; /* turned box spans x in [1.5, 2.5]: apart */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, box, RZ90, T2, box, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 0);
        T2[0] = 1.5; /* spans x in [0.5, 1.5]: overlapping */
        CHECK_EQ(pqp_collide(r, I3, ZERO3, box, RZ90, T2, box, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_colliding(r), 1);
    }
    pqp_collide_result_destroy(r);
    pqp_model_destroy(box);
}

static void box_tolerances(void)
{
    pqp_model *box = shapes_unit_box();
    pqp_tolerance_result *r = pqp_tolerance_result_create();
    double T2[3] = {1.5, 0.2, 0.1}; /* gap 0.5 */
    int q;
    CHECK(box != NULL && r != NULL);
    if (!box || !r) return;
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(r), 0);
    for (q = 1; q <= 4; q++) {
        double d, w1[3], w2[3];
        CHECK_EQ(pqp_tolerance(r, I3, ZERO3, box, I3, T2, box, 0.6, q), PQP_OK);
        CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(r), 1);
        CHECK(pqp_tolerance_result_tolerance(r) == 0.6);
        d = pqp_tolerance_result_distance(r);
        CHECK(d >= 0.5 - 1e-12 && d <= 0.6);
        apply(I3, ZERO3, pqp_tolerance_result_p1(r), w1);
        apply(I3, T2, pqp_tolerance_result_p2(r), w2);
        CHECK_NEAR(dist3(w1, w2), d, 1e-12);
        CHECK(pqp_tolerance_result_num_tri_tests(r) >= 1);

        CHECK_EQ(pqp_tolerance(r, I3, ZERO3, box, I3, T2, box, 0.4, q), PQP_OK);
        CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(r), 0);
        CHECK(pqp_tolerance_result_tolerance(r) == 0.4);
        d = pqp_tolerance_result_distance(r);
        CHECK(d > 0.4 && d <= 0.5 + 1e-12);
        CHECK(pqp_tolerance_result_query_time_secs(r) >= 0.0);
    }
    /* Overlapping: closer than 0. */
    {
        double T3[3] = {0.5, 0.5, 0.5};
        CHECK_EQ(pqp_tolerance(r, I3, ZERO3, box, I3, T3, box, 0.0, 2), PQP_OK);
        CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(r), 1);
        CHECK(pqp_tolerance_result_distance(r) == 0.0);
    }
    pqp_tolerance_result_destroy(r);
    pqp_model_destroy(box);
}

/* Every search strategy, with and without triangle caching, gives the same exact distance and the
 * same tolerance verdicts; bad options are refused and leave the result as it was. */
static void search_strategies(void)
{
    static const int strategies[4] = {PQP_SEARCH_AUTO, PQP_SEARCH_DEPTH_FIRST, PQP_SEARCH_BREADTH_FIRST,
                                      PQP_SEARCH_PRIORITY};
    pqp_model *box = shapes_unit_box();
    pqp_distance_result *r = pqp_distance_result_create();
    pqp_tolerance_result *t = pqp_tolerance_result_create();
    pqp_search_options o = pqp_search_options_default();
    const double T2[3] = {2.75, 0.25, -0.5}; /* box 2 spans x in [1.75, 2.75] */
    int s, cache, q;
    CHECK(box != NULL && r != NULL && t != NULL);
    if (!box || !r || !t) return;
    CHECK_EQ(o.strategy, PQP_SEARCH_AUTO);
    CHECK_EQ(o.qsize, 1024);
    CHECK_EQ(o.triangle_cache, 1);
    for (s = 0; s < 4; s++)
        for (cache = 0; cache < 2; cache++)
            for (q = 0; q < 3; q++) {
                o.strategy = strategies[s];
                o.triangle_cache = cache;
                o.qsize = q; /* 0: unbounded */
                CHECK_EQ(pqp_distance_search(r, I3, ZERO3, box, RZ90, T2, box, 0.0, 0.0, &o), PQP_OK);
                CHECK_NEAR(pqp_distance_result_distance(r), 0.75, 1e-12);
                check_witnesses(r, I3, ZERO3, RZ90, T2);
                CHECK_EQ(pqp_tolerance_search(t, I3, ZERO3, box, RZ90, T2, box, 0.8, &o), PQP_OK);
                CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(t), 1);
                CHECK_EQ(pqp_tolerance_search(t, I3, ZERO3, box, RZ90, T2, box, 0.7, &o), PQP_OK);
                CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(t), 0);
                CHECK(pqp_tolerance_result_distance(t) > 0.7);
            }
    /* NULL options: the default search. */
    CHECK_EQ(pqp_distance_search(r, I3, ZERO3, box, RZ90, T2, box, 0.0, 0.0, NULL), PQP_OK);
    CHECK_NEAR(pqp_distance_result_distance(r), 0.75, 1e-12);
    CHECK_EQ(pqp_tolerance_search(t, I3, ZERO3, box, RZ90, T2, box, 0.8, NULL), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(t), 1);
    /* Refused options leave the results as they were. */
    o = pqp_search_options_default();
    o.strategy = 4;
    CHECK_EQ(pqp_distance_search(r, I3, ZERO3, box, I3, ZERO3, box, 0.0, 0.0, &o), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_tolerance_search(t, I3, ZERO3, box, I3, ZERO3, box, 0.8, &o), PQP_ERR_INVALID_ARGUMENT);
    o = pqp_search_options_default();
    o.qsize = -1;
    CHECK_EQ(pqp_distance_search(r, I3, ZERO3, box, I3, ZERO3, box, 0.0, 0.0, &o), PQP_ERR_INVALID_ARGUMENT);
    o = pqp_search_options_default();
    o.triangle_cache = 2;
    CHECK_EQ(pqp_tolerance_search(t, I3, ZERO3, box, I3, ZERO3, box, 0.8, &o), PQP_ERR_INVALID_ARGUMENT);
    CHECK_NEAR(pqp_distance_result_distance(r), 0.75, 1e-12);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(t), 1);
    CHECK_EQ(pqp_distance_search(NULL, I3, ZERO3, box, I3, ZERO3, box, 0.0, 0.0, NULL), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_tolerance_search(t, I3, NULL, box, I3, ZERO3, box, 0.8, NULL), PQP_ERR_NULL_POINTER);
    pqp_tolerance_result_destroy(t);
    pqp_distance_result_destroy(r);
    pqp_model_destroy(box);
}

int main(void)
{
    box_distances();
    fence_pairs();
    box_collisions();
    box_tolerances();
    search_strategies();
    CHECK_DONE("answers");
}
