/* Point queries from C: pqp_closest_point and pqp_signed_distance against brute force on two
 * boxes at random poses and points, max_distance pruning, and every bad input (an error code, and
 * nothing written). */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

/* The model: the unit box [0,1]^3 (ids 0..11) and the box [2,3]x[0,1]x[0,2] (ids 100..111). */
static const double lo_a[3] = {0, 0, 0}, size_a[3] = {1, 1, 1};
static const double lo_b[3] = {2, 0, 0}, size_b[3] = {1, 1, 2};

static pqp_model *two_boxes(void)
{
    pqp_model *m = pqp_model_create();
    if (m == NULL) return NULL;
    if (pqp_model_begin(m, 24) != PQP_OK || shapes_add_box(m, lo_a, size_a, 0) != PQP_OK ||
        shapes_add_box(m, lo_b, size_b, 100) != PQP_OK || pqp_model_end(m) != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

/* Triangle `id` of the model, posed: world coordinates. */
static void posed_triangle(int id, const double R[9], const double T[3], double out[3][3])
{
    double t[3][3];
    int v, r;
    if (id < 100)
        shapes_box_triangle(lo_a, size_a, id, t);
    else
        shapes_box_triangle(lo_b, size_b, id - 100, t);
    for (v = 0; v < 3; v++)
        for (r = 0; r < 3; r++)
            out[v][r] = R[3 * r] * t[v][0] + R[3 * r + 1] * t[v][1] + R[3 * r + 2] * t[v][2] + T[r];
}

/* A rotation from a random unit quaternion. */
static void random_rotation(uint64_t *s, double R[9])
{
    double q[4], n = 0, w, x, y, z;
    int k;
    for (k = 0; k < 4; k++) {
        q[k] = 2 * check_unit(s) - 1;
        n += q[k] * q[k];
    }
    n = sqrt(n);
    w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

/* Whether the model-frame point is inside a box, and how far from its faces. */
static double inside_depth(const double p[3], const double lo[3], const double size[3])
{
    double depth = 1e300;
    int a;
    for (a = 0; a < 3; a++) {
        double d = fmin(p[a] - lo[a], lo[a] + size[a] - p[a]);
        depth = fmin(depth, d);
    }
    return depth; /* > 0 inside */
}

static void against_brute_force(pqp_model *m)
{
    uint64_t s = 22;
    int i, k, r;
    for (i = 0; i < 2000; i++) {
        double R[9], T[3], local[3], p[3], best = 1e300, t[3][3], sd, depth;
        int ids[24];
        pqp_point_result res;
        random_rotation(&s, R);
        for (r = 0; r < 3; r++) {
            T[r] = 4 * check_unit(&s) - 2;
            local[r] = 5 * check_unit(&s) - 1.5; /* around both boxes */
        }
        if (i % 10 == 0) local[0] = 1.0, local[1] = 0.25; /* on an edge of the unit box */
        for (r = 0; r < 3; r++)
            p[r] = R[3 * r] * local[0] + R[3 * r + 1] * local[1] + R[3 * r + 2] * local[2] + T[r];
        for (k = 0; k < 24; k++) {
            ids[k] = k < 12 ? k : 100 + k - 12;
            posed_triangle(ids[k], R, T, t);
            best = fmin(best, shapes_point_triangle_distance(p, t));
        }
        CHECK_EQ(pqp_closest_point(&res, R, T, m, p, INFINITY), PQP_OK);
        CHECK_NEAR(res.distance, best, 1e-12);
        CHECK(res.triangle >= 0 && (res.triangle < 12 || (res.triangle >= 100 && res.triangle < 112)));
        posed_triangle(res.triangle, R, T, t);
        CHECK_NEAR(shapes_point_triangle_distance(p, t), best, 1e-12);
        CHECK(shapes_point_triangle_distance(res.point, t) <= 1e-12);
        CHECK_NEAR(sqrt((res.point[0] - p[0]) * (res.point[0] - p[0]) +
                        (res.point[1] - p[1]) * (res.point[1] - p[1]) +
                        (res.point[2] - p[2]) * (res.point[2] - p[2])),
                   best, 1e-12);

        CHECK_EQ(pqp_signed_distance(&sd, R, T, m, p), PQP_OK);
        CHECK_NEAR(fabs(sd), best, 1e-12);
        depth = fmax(inside_depth(local, lo_a, size_a), inside_depth(local, lo_b, size_b));
        if (depth > 1e-9) CHECK(sd < 0);
        if (depth < -1e-9) CHECK(sd > 0);

        /* max_distance: at the distance (kept), above (the same answer), below (beyond). */
        {
            pqp_point_result at, above, below;
            CHECK_EQ(pqp_closest_point(&at, R, T, m, p, res.distance), PQP_OK);
            CHECK(at.distance == res.distance && at.triangle == res.triangle);
            CHECK_EQ(pqp_closest_point(&above, R, T, m, p, 2 * res.distance + 1), PQP_OK);
            CHECK(above.distance == res.distance && above.triangle == res.triangle);
            CHECK(memcmp(above.point, res.point, sizeof res.point) == 0);
            if (res.distance > 0) {
                CHECK_EQ(pqp_closest_point(&below, R, T, m, p, 0.5 * res.distance), PQP_OK);
                CHECK(isinf(below.distance) && below.triangle == -1);
                CHECK(isnan(below.point[0]) && isnan(below.point[1]) && isnan(below.point[2]));
                CHECK_EQ(pqp_closest_point(&below, R, T, m, p, 0.0), PQP_OK);
                CHECK(below.triangle == -1);
            }
        }
    }
}

/* Every bad input returns its code and writes nothing. */
static void bad_inputs(pqp_model *m)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T0[3] = {0, 0, 0};
    const double p[3] = {0.5, 0.5, 3};
    const double nan = NAN, inf = INFINITY;
    pqp_point_result res, sentinel;
    double sd = 12345.0;
    pqp_model *unbuilt = pqp_model_create();
    int k;
    memset(&sentinel, 0x5a, sizeof sentinel);
    res = sentinel;

#define UNTOUCHED() CHECK(memcmp(&res, &sentinel, sizeof res) == 0 && sd == 12345.0)
    /* (res is never written on these paths, so its padding stays the sentinel's too.) */
    CHECK_EQ(pqp_closest_point(NULL, I, T0, m, p, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_closest_point(&res, NULL, T0, m, p, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_closest_point(&res, I, NULL, m, p, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_closest_point(&res, I, T0, NULL, p, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_closest_point(&res, I, T0, m, NULL, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_signed_distance(NULL, I, T0, m, p), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_signed_distance(&sd, NULL, T0, m, p), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_signed_distance(&sd, I, NULL, m, p), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_signed_distance(&sd, I, T0, NULL, p), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_signed_distance(&sd, I, T0, m, NULL), PQP_ERR_NULL_POINTER);
    UNTOUCHED();

    CHECK_EQ(pqp_closest_point(&res, I, T0, unbuilt, p, 1.0), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_signed_distance(&sd, I, T0, unbuilt, p), PQP_ERR_UNPROCESSED_MODEL);
    UNTOUCHED();

    CHECK_EQ(pqp_closest_point(&res, I, T0, m, p, -1.0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_closest_point(&res, I, T0, m, p, nan), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_closest_point(&res, I, T0, m, p, -inf), PQP_ERR_INVALID_ARGUMENT);
    UNTOUCHED();

    for (k = 0; k < 3; k++) {
        double q[3], R[9], T[3];
        const double bad[3] = {nan, inf, 1e151};
        int j;
        for (j = 0; j < 3; j++) {
            memcpy(q, p, sizeof q);
            q[k] = bad[j];
            CHECK_EQ(pqp_closest_point(&res, I, T0, m, q, 1.0), PQP_ERR_NONFINITE_COORDINATE);
            CHECK_EQ(pqp_signed_distance(&sd, I, T0, m, q), PQP_ERR_NONFINITE_COORDINATE);
            memcpy(R, I, sizeof R);
            R[3 * k + j] = bad[j];
            CHECK_EQ(pqp_closest_point(&res, R, T0, m, p, 1.0), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(pqp_signed_distance(&sd, R, T0, m, p), PQP_ERR_NONFINITE_POSE);
            memcpy(T, T0, sizeof T);
            T[k] = bad[j];
            CHECK_EQ(pqp_closest_point(&res, I, T, m, p, 1.0), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(pqp_signed_distance(&sd, I, T, m, p), PQP_ERR_NONFINITE_POSE);
        }
    }
    UNTOUCHED();
#undef UNTOUCHED
    pqp_model_destroy(unbuilt);

    /* The answer may be written over its own inputs. */
    {
        double q[3] = {0.5, 0.5, -2};
        CHECK_EQ(pqp_signed_distance(&q[0], I, T0, m, q), PQP_OK);
        CHECK_NEAR(q[0], 2.0, 1e-15);
    }
}

int main(void)
{
    pqp_model *m = two_boxes();
    CHECK(m != NULL);
    if (m == NULL) CHECK_DONE("point");
    against_brute_force(m);
    bad_inputs(m);
    pqp_model_destroy(m);
    CHECK_DONE("point");
}
