/* pqp_ray_cast and pqp_ray_cast_batch through the C ABI: answers known by construction on boxes
 * (axis-aligned rays through faces, edges and vertices, from outside and from inside), batches
 * equal to single calls on every thread count, and every bad input with its code and nothing
 * written. */
#include <pqp/pqp.h>

#include "check.h"
#include "shapes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double T0[3] = {0, 0, 0};

/* The field-by-field equality of two answers (NaN equal to NaN). */
static int same_hit(const pqp_ray_hit *a, const pqp_ray_hit *b)
{
    int k;
    if (a->triangle != b->triangle) return 0;
    if (!(a->t == b->t)) return 0;
    for (k = 0; k < 3; k++) {
        if (!(a->point[k] == b->point[k] || (isnan(a->point[k]) && isnan(b->point[k])))) return 0;
        if (!(a->normal[k] == b->normal[k] || (isnan(a->normal[k]) && isnan(b->normal[k]))))
            return 0;
    }
    return 1;
}

/* A sentinel answer, to see that failed calls write nothing. */
static pqp_ray_hit sentinel(void)
{
    pqp_ray_hit h;
    memset(&h, 0, sizeof h);
    h.t = 12345.0;
    h.triangle = 777;
    return h;
}

/* The unit box: rays along each axis through a grid of face points, edges and vertices (the grid
 * includes 0 and 1), from outside (hit at t = 2 on the near face) and from the centre (t = 1). */
static void box_answers(const pqp_model *box)
{
    int axis, i, j, side;
    for (axis = 0; axis < 3; axis++) {
        for (side = 0; side < 2; side++) {
            for (i = 0; i <= 8; i++) {
                for (j = 0; j <= 8; j++) {
                    double o[3], d[3] = {0, 0, 0};
                    pqp_ray_hit h;
                    o[(axis + 1) % 3] = i / 8.0;
                    o[(axis + 2) % 3] = j / 8.0;
                    o[axis] = side ? 1.5 : -0.5;
                    d[axis] = side ? -0.25 : 0.25;
                    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, d, INFINITY), PQP_OK);
                    CHECK(h.t == 2.0);
                    CHECK(h.triangle >= 0 && h.triangle < 12);
                    CHECK(h.point[axis] == (side ? 1.0 : 0.0));
                    CHECK(fabs(h.normal[0]) + fabs(h.normal[1]) + fabs(h.normal[2]) == 1.0);
                    /* max_t just short of the face: nothing. */
                    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, d, 1.9999999), PQP_OK);
                    CHECK_EQ(h.triangle, -1);
                    CHECK(h.t == INFINITY && isnan(h.point[0]) && isnan(h.normal[2]));
                }
            }
        }
    }
    {
        /* From the centre towards every vertex and edge midpoint: t = 1. */
        const double c[3] = {0.5, 0.5, 0.5};
        int x, y, z;
        for (x = 0; x <= 2; x++)
            for (y = 0; y <= 2; y++)
                for (z = 0; z <= 2; z++) {
                    double d[3];
                    pqp_ray_hit h;
                    d[0] = x * 0.5 - 0.5;
                    d[1] = y * 0.5 - 0.5;
                    d[2] = z * 0.5 - 0.5;
                    if (d[0] == 0 && d[1] == 0 && d[2] == 0) continue;
                    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, c, d, INFINITY), PQP_OK);
                    CHECK(h.t == 1.0);
                    CHECK(h.triangle >= 0);
                }
    }
}

/* A rotated, translated box: the hit point is where the world ray meets the posed face. */
static void posed_box(const pqp_model *box)
{
    /* 90 degrees about z, then up 10: model x -> world y; the box spans x in [-1, 0], y in
     * [0, 1], z in [10, 11]. */
    const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    const double T[3] = {0, 0, 10};
    const double o[3] = {-0.5, -0.25, 10.5}, d[3] = {0, 2, 0};
    pqp_ray_hit h;
    CHECK_EQ(pqp_ray_cast(&h, R, T, box, o, d, INFINITY), PQP_OK);
    CHECK_NEAR(h.t, 0.125, 1e-15);
    CHECK_NEAR(h.point[0], -0.5, 1e-15);
    CHECK_NEAR(h.point[1], 0.0, 1e-15);
    CHECK_NEAR(h.point[2], 10.5, 1e-15);
    CHECK_NEAR(fabs(h.normal[1]), 1.0, 1e-15);
}

/* Whether p lies on the closed triangle t, exactly (every coordinate a multiple of 1/4 and small:
 * integer arithmetic on 4 x the coordinates); never for a triangle without area. */
static int on_triangle(double t[3][3], const double p[3])
{
    long long a[3], u[3], v[3], w[3], n[3], k;
    int i, e;
    for (i = 0; i < 3; i++) {
        a[i] = (long long)(4 * t[0][i]);
        u[i] = (long long)(4 * t[1][i]) - a[i];
        v[i] = (long long)(4 * t[2][i]) - a[i];
        w[i] = (long long)(4 * p[i]) - a[i];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    if ((n[0] == 0 && n[1] == 0 && n[2] == 0) || n[0] * w[0] + n[1] * w[1] + n[2] * w[2] != 0)
        return 0;
    /* In the plane: on the inner side of (or on) every edge, measured along the normal. */
    for (e = 0; e < 3; e++) {
        long long x[3], f[3], g[3], m[3];
        for (i = 0; i < 3; i++) {
            x[i] = (long long)(4 * t[e][i]);
            f[i] = (long long)(4 * t[(e + 1) % 3][i]) - x[i];
            g[i] = (long long)(4 * p[i]) - x[i];
        }
        m[0] = f[1] * g[2] - f[2] * g[1];
        m[1] = f[2] * g[0] - f[0] * g[2];
        m[2] = f[0] * g[1] - f[1] * g[0];
        k = m[0] * n[0] + m[1] * n[1] + m[2] * n[2];
        if (k < 0) return 0;
    }
    return 1;
}

/* Rays starting on a triangle hit it at t = 0, max_t = 0 included: the single triangle of issue 38,
 * and every point on the 1/4 grid of the surface of the box [0, 4]^3 whose faces are cut into 4 x 4
 * squares of two triangles, in 17 directions (along and across the faces), at the identity and at
 * an exact pose; the triangle reported is the first added that the origin lies on. */
static void from_the_surface(void)
{
    enum { N = 4, TRIS = 6 * N * N * 2 };
    static double tris[TRIS][3][3];
    /* A rotation of the cube (x -> y -> z -> x) and an integer translation: exact. */
    static const double P[9] = {0, 0, 1, 1, 0, 0, 0, 1, 0}, TP[3] = {-3, 7, 2};
    static const double D[17][3] = {
        {1, 0, 0},   {-1, 0, 0},   {0, 1, 0},        {0, -1, 0},      {0, 0, 1},  {0, 0, -1},
        {1, 1, 1},   {1, 1, -1},   {1, -1, 1},       {1, -1, -1},     {-1, 1, 1}, {-1, 1, -1},
        {-1, -1, 1}, {-1, -1, -1}, {0.3, -1.7, 0.9}, {-2.5, 0.1, 0.6}, {1, 0.5, 0}};
    pqp_model *one = pqp_model_create(), *box = pqp_model_create();
    int axis, side, i, j, k, x, y, z, pose, count = 0, misses = 0;
    {
        const double a[3] = {-2, -2, -1}, b[3] = {-2, -1, 0}, c[3] = {-2, -1, -1};
        const double o[3] = {-2, -1.5, -0.75}, d[3] = {-1.5, -1.75, -0.625};
        const double max_t[2] = {0.0, INFINITY};
        CHECK(one != NULL && box != NULL);
        if (one == NULL || box == NULL) return;
        CHECK_EQ(pqp_model_begin(one, 1), PQP_OK);
        CHECK_EQ(pqp_model_add_tri(one, a, b, c, 0), PQP_OK);
        CHECK_EQ(pqp_model_end(one), PQP_OK);
        for (k = 0; k < 2; k++) {
            pqp_ray_hit h;
            CHECK_EQ(pqp_ray_cast(&h, I, T0, one, o, d, max_t[k]), PQP_OK);
            CHECK(h.t == 0.0 && h.triangle == 0);
            CHECK(h.point[0] == o[0] && h.point[1] == o[1] && h.point[2] == o[2]);
        }
    }
    k = 0;
    for (axis = 0; axis < 3; axis++)
        for (side = 0; side <= N; side += N)
            for (i = 0; i < N; i++)
                for (j = 0; j < N; j++) {
                    double c[4][3];
                    int q, order[6];
                    for (q = 0; q < 4; q++) {
                        c[q][axis] = side;
                        c[q][(axis + 1) % 3] = i + (q == 1 || q == 2);
                        c[q][(axis + 2) % 3] = j + (q >= 2);
                    }
                    if ((i + j) % 2 == 0) {
                        order[0] = 0, order[1] = 1, order[2] = 2;
                        order[3] = 0, order[4] = 2, order[5] = 3;
                    } else {
                        order[0] = 0, order[1] = 1, order[2] = 3;
                        order[3] = 1, order[4] = 2, order[5] = 3;
                    }
                    for (q = 0; q < 6; q++)
                        memcpy(tris[k + q / 3][q % 3], c[order[q]], sizeof c[0]);
                    k += 2;
                }
    CHECK_EQ(pqp_model_begin(box, TRIS), PQP_OK);
    for (k = 0; k < TRIS; k++)
        CHECK_EQ(pqp_model_add_tri(box, tris[k][0], tris[k][1], tris[k][2], k), PQP_OK);
    CHECK_EQ(pqp_model_end(box), PQP_OK);
    for (x = 0; x <= 4 * N; x++)
        for (y = 0; y <= 4 * N; y++)
            for (z = 0; z <= 4 * N; z++) {
                double o[3];
                int first = -1;
                if (x % (4 * N) && y % (4 * N) && z % (4 * N)) continue; /* not on the surface */
                o[0] = x / 4.0, o[1] = y / 4.0, o[2] = z / 4.0;
                for (k = 0; k < TRIS && first < 0; k++)
                    if (on_triangle(tris[k], o)) first = k;
                CHECK(first >= 0);
                for (pose = 0; pose < 2; pose++) {
                    const double *R = pose ? P : I, *T = pose ? TP : T0;
                    double wo[3];
                    for (i = 0; i < 3; i++)
                        wo[i] = R[3 * i] * o[0] + R[3 * i + 1] * o[1] + R[3 * i + 2] * o[2] + T[i];
                    for (j = 0; j < 17; j++) {
                        double wd[3];
                        for (i = 0; i < 3; i++)
                            wd[i] = R[3 * i] * D[j][0] + R[3 * i + 1] * D[j][1] +
                                    R[3 * i + 2] * D[j][2];
                        for (k = 0; k < 2; k++) {
                            pqp_ray_hit h;
                            count++;
                            CHECK_EQ(pqp_ray_cast(&h, R, T, box, wo, wd, k ? INFINITY : 0.0),
                                     PQP_OK);
                            if (!(h.t == 0.0 && h.triangle == first && h.point[0] == wo[0] &&
                                  h.point[1] == wo[1] && h.point[2] == wo[2]))
                                misses++;
                        }
                    }
                }
            }
    CHECK(count == (17 * 17 * 17 - 15 * 15 * 15) * 2 * 17 * 2);
    CHECK_EQ(misses, 0);
    pqp_model_destroy(one);
    pqp_model_destroy(box);
}

/* Batches: the same answers as single calls, on 0, 1, 2 and 64 threads. */
static void batches(const pqp_model *box)
{
    enum { N = 500 };
    static double origins[3 * N], directions[3 * N];
    static pqp_ray_hit single[N], hits[N];
    static const unsigned threads[4] = {0, 1, 2, 64};
    uint64_t seed = 22;
    int i, k, hit_count = 0;
    for (i = 0; i < 3 * N; i++) {
        origins[i] = 3.0 * check_unit(&seed) - 1.0;
        directions[i] = check_unit(&seed) - 0.5;
    }
    for (i = 0; i < N; i++) {
        CHECK_EQ(pqp_ray_cast(&single[i], I, T0, box, origins + 3 * i, directions + 3 * i, 4.0),
                 PQP_OK);
        hit_count += single[i].triangle >= 0;
    }
    CHECK(hit_count > N / 10);
    for (k = 0; k < 4; k++) {
        for (i = 0; i < N; i++) hits[i] = sentinel();
        CHECK_EQ(pqp_ray_cast_batch(hits, N, I, T0, box, origins, directions, 4.0, threads[k]),
                 PQP_OK);
        for (i = 0; i < N; i++) CHECK(same_hit(&hits[i], &single[i]));
    }
    /* n = 0, with or without arrays. */
    CHECK_EQ(pqp_ray_cast_batch(NULL, 0, I, T0, box, NULL, NULL, 1.0, 0), PQP_OK);
    CHECK_EQ(pqp_ray_cast_batch(hits, 0, I, T0, box, origins, directions, 1.0, 3), PQP_OK);

    /* One bad ray fails the whole batch, and nothing is written. */
    for (k = 0; k < 3; k++) {
        pqp_ray_hit s = sentinel();
        double keep;
        int rc;
        double *where = k == 2 ? directions + 3 * 321 : origins + 3 * 321 + 1;
        keep = *where;
        *where = k == 0 ? NAN : INFINITY;
        for (i = 0; i < N; i++) hits[i] = s;
        rc = pqp_ray_cast_batch(hits, N, I, T0, box, origins, directions, 4.0, 2);
        CHECK_EQ(rc, PQP_ERR_NONFINITE_COORDINATE);
        for (i = 0; i < N; i++) CHECK(same_hit(&hits[i], &s));
        *where = keep;
    }
    {
        pqp_ray_hit s = sentinel();
        double keep[3];
        memcpy(keep, directions + 3 * 499, sizeof keep);
        directions[3 * 499] = directions[3 * 499 + 1] = directions[3 * 499 + 2] = 0.0;
        for (i = 0; i < N; i++) hits[i] = s;
        CHECK_EQ(pqp_ray_cast_batch(hits, N, I, T0, box, origins, directions, 4.0, 0),
                 PQP_ERR_INVALID_ARGUMENT);
        for (i = 0; i < N; i++) CHECK(same_hit(&hits[i], &s));
        memcpy(directions + 3 * 499, keep, sizeof keep);
    }
}

/* Every bad input of pqp_ray_cast and pqp_ray_cast_batch: its code, nothing written. */
static void errors(const pqp_model *box)
{
    const double o[3] = {0.5, 0.5, -1}, d[3] = {0, 0, 1};
    const double zero[3] = {0, 0, 0};
    double bad[3] = {0, 0, 0}, badR[9], badT[3] = {0, 0, 0};
    pqp_ray_hit h = sentinel(), s = sentinel(), many[4];
    pqp_model *empty = pqp_model_create(), *begun = pqp_model_create();
    int i;
    pqp_model_begin(begun, 1);

    CHECK_EQ(pqp_ray_cast(NULL, I, T0, box, o, d, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, NULL, T0, box, o, d, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, I, NULL, box, o, d, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, NULL, o, d, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, NULL, d, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, NULL, 1.0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, empty, o, d, 1.0), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, begun, o, d, 1.0), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, zero, 1.0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, d, -1.0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, d, NAN), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, d, -INFINITY), PQP_ERR_INVALID_ARGUMENT);
    for (i = 0; i < 3; i++) {
        bad[0] = bad[1] = bad[2] = 0.25;
        bad[i] = NAN;
        CHECK_EQ(pqp_ray_cast(&h, I, T0, box, bad, d, 1.0), PQP_ERR_NONFINITE_COORDINATE);
        CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, bad, 1.0), PQP_ERR_NONFINITE_COORDINATE);
        bad[i] = -INFINITY;
        CHECK_EQ(pqp_ray_cast(&h, I, T0, box, bad, d, 1.0), PQP_ERR_NONFINITE_COORDINATE);
        CHECK_EQ(pqp_ray_cast(&h, I, T0, box, o, bad, 1.0), PQP_ERR_NONFINITE_COORDINATE);
        bad[i] = 2e150;
        CHECK_EQ(pqp_ray_cast(&h, I, T0, box, bad, d, 1.0), PQP_ERR_NONFINITE_COORDINATE);
    }
    for (i = 0; i < 9; i++) {
        memcpy(badR, I, sizeof badR);
        badR[i] = NAN;
        CHECK_EQ(pqp_ray_cast(&h, badR, T0, box, o, d, 1.0), PQP_ERR_NONFINITE_POSE);
    }
    badT[1] = INFINITY;
    CHECK_EQ(pqp_ray_cast(&h, I, badT, box, o, d, 1.0), PQP_ERR_NONFINITE_POSE);
    CHECK(same_hit(&h, &s));

    /* The batch: NULLs, unbuilt model, max_t, huge n. */
    for (i = 0; i < 4; i++) many[i] = s;
    CHECK_EQ(pqp_ray_cast_batch(NULL, 1, I, T0, box, o, d, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, NULL, T0, box, o, d, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, NULL, box, o, d, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, T0, NULL, o, d, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, T0, box, NULL, d, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, T0, box, o, NULL, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(NULL, 0, I, T0, NULL, NULL, NULL, 1.0, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, T0, empty, o, d, 1.0, 1), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_ray_cast_batch(many, 0, I, T0, empty, o, d, 1.0, 1), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, I, T0, box, o, d, -2.0, 1), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_ray_cast_batch(many, 1, badR, T0, box, o, d, 1.0, 1), PQP_ERR_NONFINITE_POSE);
    CHECK_EQ(pqp_ray_cast_batch(many, (size_t)-1, I, T0, box, o, d, 1.0, 1),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_ray_cast_batch(many, (size_t)-1 / 8, I, T0, box, o, d, 1.0, 1),
             PQP_ERR_INVALID_ARGUMENT);
    for (i = 0; i < 4; i++) CHECK(same_hit(&many[i], &s));

    pqp_model_destroy(empty);
    pqp_model_destroy(begun);
}

int main(void)
{
    pqp_model *box = shapes_unit_box();
    CHECK(box != NULL);
    if (box == NULL) CHECK_DONE("ray");
    box_answers(box);
    posed_box(box);
    from_the_surface();
    batches(box);
    errors(box);
    pqp_model_destroy(box);
    CHECK_DONE("ray");
}
