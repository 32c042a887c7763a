/* Swept-sphere primitives as models (pqp_model_set_sphere, pqp_model_set_capsule,
 * pqp_model_set_box): answers by construction against a triangle and each other, in every pair
 * query and batch; every bad input returns its code and changes nothing; every other entry point
 * taking a model answers PQP_ERR_NOT_A_TRIANGLE_MESH or its documented value. */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "check.h"
#include "pqp/pqp.h"

static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double O[3] = {0, 0, 0};

/* A big triangle in the plane z = h, id 7. */
static pqp_model *floor_at(double h)
{
    pqp_model *m = pqp_model_create();
    double a[3] = {-10, -10, 0}, b[3] = {10, -10, 0}, c[3] = {0, 10, 0};
    a[2] = b[2] = c[2] = h;
    CHECK_EQ(pqp_model_add_tri(m, a, b, c, 7), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    return m;
}

static double dist(const pqp_model *a, const double *Ta, const pqp_model *b, const double *Tb)
{
    pqp_distance_result *r = pqp_distance_result_create();
    double d;
    CHECK_EQ(pqp_distance(r, I, Ta, a, I, Tb, b, 0.0, 0.0, 2), PQP_OK);
    d = pqp_distance_result_distance(r);
    pqp_distance_result_destroy(r);
    return d;
}

/* Each primitive above a floor: distances, closest points, ids, collision, tolerance, pairs
 * within a distance, both orders. */
static void answers(void)
{
    pqp_model *fl = floor_at(0.0);
    pqp_model *s = pqp_model_create(), *c = pqp_model_create(), *b = pqp_model_create();
    const double up[3] = {0, 0, 3};
    pqp_distance_result *r = pqp_distance_result_create();
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    int t1, t2;
    CHECK_EQ(pqp_model_set_sphere(s, 1.0), PQP_OK);
    CHECK_EQ(pqp_model_set_capsule(c, 0.5, 2.0), PQP_OK);   /* lowest point z = -1.5 */
    CHECK_EQ(pqp_model_set_box(b, 1.0, 1.0, 4.0), PQP_OK);  /* lowest face z = -2 */
    CHECK_EQ(pqp_model_build_state(s), PQP_BUILD_STATE_PROCESSED);
    CHECK_EQ(pqp_model_is_built(b), 1);
    CHECK_EQ(pqp_model_num_tris(c), 0);
    CHECK_NEAR(dist(s, up, fl, O), 2.0, 1e-15);
    CHECK_NEAR(dist(c, up, fl, O), 1.5, 1e-15);
    CHECK_NEAR(dist(b, up, fl, O), 1.0, 1e-15);
    CHECK_NEAR(dist(fl, O, b, up), 1.0, 1e-15);
    /* Primitives against each other: sphere at 0, box at z = 3 (bottom face z = 1). */
    CHECK_NEAR(dist(s, O, b, up), 0.0, 0.0);
    CHECK_NEAR(dist(c, O, b, up), 0.0, 0.0);       /* capsule top z = 1.5 reaches into it */
    CHECK_NEAR(dist(s, O, c, up), 0.5, 1e-15);     /* capsule bottom z = 1.5 */

    /* Closest points and ids: the sphere's point (0, 0, -1) in its frame, the floor's (0, 0, 0). */
    CHECK_EQ(pqp_distance(r, I, up, s, I, O, fl, 0.0, 0.0, 2), PQP_OK);
    CHECK_NEAR(pqp_distance_result_p1(r)[2], -1.0, 1e-15);
    CHECK_NEAR(pqp_distance_result_p2(r)[2], 0.0, 1e-15);
    CHECK_EQ(pqp_distance_result_id1(r), 0);
    CHECK_EQ(pqp_distance_result_id2(r), 7);
    CHECK_EQ(pqp_distance_result_triangles(r, &t1, &t2), PQP_OK);
    CHECK_EQ(t1, 0);
    CHECK_EQ(t2, 0);
    CHECK_EQ(pqp_distance_result_overlap(r), 0);

    /* Lowered to touch: colliding, pair (0, 7) or (7, 0). */
    {
        const double touch[3] = {0, 0, 1.5};
        CHECK_EQ(pqp_collide(cr, I, touch, c, I, O, fl, PQP_ALL_CONTACTS), PQP_OK);
        CHECK_EQ(pqp_collide_result_num_pairs(cr), 1);
        CHECK_EQ(pqp_collide_result_id1(cr, 0), 0);
        CHECK_EQ(pqp_collide_result_id2(cr, 0), 7);
        CHECK_EQ(pqp_collide(cr, I, O, fl, I, touch, c, PQP_FIRST_CONTACT), PQP_OK);
        CHECK_EQ(pqp_collide_result_id1(cr, 0), 7);
        CHECK_EQ(pqp_collide_result_id2(cr, 0), 0);
        CHECK_EQ(pqp_distance(r, I, touch, c, I, O, fl, 0.0, 0.0, 2), PQP_OK);
        CHECK_EQ(pqp_distance_result_overlap(r), 1);
    }
    CHECK_EQ(pqp_collide(cr, I, up, s, I, O, fl, PQP_ALL_CONTACTS), PQP_OK);
    CHECK_EQ(pqp_collide_result_colliding(cr), 0);
    CHECK_EQ(pqp_tolerance(tr, I, up, b, I, O, fl, 1.0, 2), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 1);
    CHECK_EQ(pqp_tolerance(tr, I, up, b, I, O, fl, 0.99, 2), PQP_OK);
    CHECK_EQ(pqp_tolerance_result_closer_than_tolerance(tr), 0);
    CHECK(pqp_tolerance_result_distance(tr) > 0.99);
    CHECK_EQ(pqp_within_distance(cr, I, up, b, I, O, fl, 1.0), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(cr), 1);
    CHECK_EQ(pqp_within_distance(cr, I, up, b, I, O, s, 1.0), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(cr), 1);
    CHECK_EQ(pqp_collide_result_id1(cr, 0), 0);
    CHECK_EQ(pqp_collide_result_id2(cr, 0), 0);

    /* Batches: as single calls. */
    {
        enum { N = 8 };
        double R1[9 * N], T1[3 * N], R2[9 * N], T2[3 * N], d[N];
        int hit[N], near[N], k;
        for (k = 0; k < N; k++) {
            memcpy(R1 + 9 * k, I, sizeof I);
            memcpy(R2 + 9 * k, I, sizeof I);
            T1[3 * k] = 0.1 * k;
            T1[3 * k + 1] = 0;
            T1[3 * k + 2] = 0.5 * k;
            memcpy(T2 + 3 * k, O, sizeof O);
        }
        CHECK_EQ(pqp_distance_batch(d, N, R1, T1, b, R2, T2, fl, 0.0, 0.0, 0), PQP_OK);
        CHECK_EQ(pqp_collide_batch(hit, N, R1, T1, b, R2, T2, fl, PQP_FIRST_CONTACT, 0), PQP_OK);
        CHECK_EQ(pqp_tolerance_batch(near, N, R1, T1, b, R2, T2, fl, 0.25, 0), PQP_OK);
        for (k = 0; k < N; k++) {
            double want = dist(b, T1 + 3 * k, fl, O);
            CHECK(d[k] == want);
            CHECK_EQ(hit[k], want == 0.0);
            CHECK_EQ(near[k], want <= 0.25);
        }
    }
    pqp_tolerance_result_destroy(tr);
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(r);
    pqp_model_destroy(s);
    pqp_model_destroy(c);
    pqp_model_destroy(b);
    pqp_model_destroy(fl);
}

/* Bad sizes and NULL: the code, and the model unchanged (a sphere stays that sphere, a mesh that
 * mesh). */
static void bad_input(void)
{
    const double bad[] = {-1.0, -1e-300, NAN, INFINITY, -INFINITY, 1e151};
    const double up[3] = {0, 0, 3};
    pqp_model *s = pqp_model_create(), *fl = floor_at(0.0), *mesh = floor_at(1.0);
    size_t k;
    CHECK_EQ(pqp_model_set_sphere(NULL, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_set_capsule(NULL, 1.0, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_set_box(NULL, 1.0, 1.0, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_set_sphere(s, 1.0), PQP_OK);
    for (k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        double v = bad[k];
        CHECK_EQ(pqp_model_set_sphere(s, v), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_capsule(s, v, 1.0), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_capsule(s, 1.0, v), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_box(s, v, 1.0, 1.0), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_box(s, 1.0, v, 1.0), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_box(s, 1.0, 1.0, v), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_model_set_box(mesh, 1.0, 1.0, v), PQP_ERR_INVALID_ARGUMENT);
    }
    CHECK_NEAR(dist(s, up, fl, O), 2.0, 1e-15);
    CHECK_EQ(pqp_model_num_tris(mesh), 1);
    CHECK_NEAR(dist(mesh, O, fl, O), 1.0, 1e-15);
    /* Zero sizes are valid: a point, a sphere, a flat box. */
    CHECK_EQ(pqp_model_set_sphere(s, 0.0), PQP_OK);
    CHECK_NEAR(dist(s, up, fl, O), 3.0, 1e-15);
    CHECK_EQ(pqp_model_set_capsule(s, 1.0, 0.0), PQP_OK);
    CHECK_NEAR(dist(s, up, fl, O), 2.0, 1e-15);
    CHECK_EQ(pqp_model_set_box(s, 2.0, 2.0, 0.0), PQP_OK);
    CHECK_NEAR(dist(s, up, fl, O), 3.0, 1e-15);
    CHECK_EQ(pqp_model_set_box(s, -0.0, 0.0, 0.0), PQP_OK);
    CHECK_NEAR(dist(s, up, fl, O), 3.0, 1e-15);
    pqp_model_destroy(s);
    pqp_model_destroy(fl);
    pqp_model_destroy(mesh);
}

/* The calls that need triangles refuse a primitive; the build calls behave as on a built model. */
static void other_entry_points(void)
{
    pqp_model *s = pqp_model_create(), *fl = floor_at(0.0);
    const double p[3] = {0, 0, 5}, dir[3] = {0, 0, -1};
    pqp_point_result pr;
    pqp_ray_hit hit;
    pqp_contact_time ct;
    double sd = 42.0, coords[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const pqp_tri *tris = NULL;
    const pqp_bv *bvs = NULL;
    int nt = -1, nb = -1;
    size_t size = 0;
    unsigned char buf[64];
    pqp_collide_result *cr = pqp_collide_result_create();
    memset(&pr, 0, sizeof pr);
    CHECK_EQ(pqp_model_set_capsule(s, 1.0, 2.0), PQP_OK);
    CHECK_EQ(pqp_closest_point(&pr, I, O, s, p, INFINITY), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK(pr.distance == 0.0);
    CHECK_EQ(pqp_signed_distance(&sd, I, O, s, p), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK(sd == 42.0);
    CHECK_EQ(pqp_ray_cast(&hit, I, O, s, p, dir, INFINITY), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_ray_cast_batch(&hit, 1, I, O, s, p, dir, INFINITY, 0), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_self_collide(cr, s, PQP_ALL_CONTACTS), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_time_of_contact(&ct, I, O, I, p, s, I, O, I, O, fl, 0.1), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_model_refit(s, coords, 0), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_model_serialize(s, buf, sizeof buf, &size), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_model_bvs(s, &bvs, &nb), PQP_ERR_NOT_A_TRIANGLE_MESH);
    CHECK_EQ(pqp_model_tris(s, &tris, &nt), PQP_OK);
    CHECK_EQ(nt, 0);
    /* add_tri and end: out of sequence, nothing changed; begin clears into a mesh. */
    CHECK_EQ(pqp_model_add_tri(s, coords, coords + 3, coords + 6, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_end(s), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_NEAR(dist(s, p, fl, O), 3.0, 1e-15);
    CHECK_EQ(pqp_model_begin(s, 1), PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    CHECK_EQ(pqp_model_build_state(s), PQP_BUILD_STATE_BEGUN);
    CHECK_EQ(pqp_model_add_tri(s, coords, coords + 3, coords + 6, 1), PQP_OK);
    CHECK_EQ(pqp_model_end(s), PQP_OK);
    CHECK_NEAR(dist(s, p, fl, O), 5.0, 1e-15);
    CHECK_EQ(pqp_model_tris(s, &tris, &nt), PQP_OK);
    CHECK_EQ(nt, 1);
    /* A mesh whose view was read, then made a sphere: its view is gone. */
    CHECK_EQ(pqp_model_set_sphere(s, 1.0), PQP_OK);
    CHECK_EQ(pqp_model_tris(s, &tris, &nt), PQP_OK);
    CHECK_EQ(nt, 0);
    CHECK_NEAR(dist(s, p, fl, O), 4.0, 1e-15);
    /* A clone keeps the primitive. */
    {
        pqp_model *copy = NULL;
        CHECK_EQ(pqp_model_clone(&copy, s), PQP_OK);
        CHECK_NEAR(dist(copy, p, fl, O), 4.0, 1e-15);
        pqp_model_destroy(copy);
    }
    pqp_collide_result_destroy(cr);
    pqp_model_destroy(s);
    pqp_model_destroy(fl);
}

int main(void)
{
    answers();
    bad_input();
    other_entry_points();
    CHECK_DONE("primitives");
}
