/* Test geometry with answers known by construction, for the C and C++ test programs. */
#ifndef PQP_TEST_SHAPES_H
#define PQP_TEST_SHAPES_H

#include <pqp/pqp.h>

#include <math.h>

/* Triangle k (0..11) of the axis-aligned box [lo, lo + size]: two per face, faces in the order
 * x = lo, x = hi, y = lo, y = hi, z = lo, z = hi. */
static inline void shapes_box_triangle(const double lo[3], const double size[3], int k,
                                       double out[3][3])
{
    /* Corner c has coordinate lo + size on axis a when bit (2 - a) of c is set. */
    static const int faces[12][3] = {
        {0, 2, 3}, {0, 3, 1}, /* x = lo */
        {4, 5, 7}, {4, 7, 6}, /* x = hi */
        {0, 1, 5}, {0, 5, 4}, /* y = lo */
        {2, 6, 7}, {2, 7, 3}, /* y = hi */
        {0, 4, 6}, {0, 6, 2}, /* z = lo */
        {1, 3, 7}, {1, 7, 5}, /* z = hi */
    };
    int v, a;
    for (v = 0; v < 3; v++)
        for (a = 0; a < 3; a++)
            out[v][a] = lo[a] + (((faces[k][v] >> (2 - a)) & 1) ? size[a] : 0.0);
}

/* Adds the 12 triangles of the axis-aligned box [lo, lo + size] (ids first_id .. first_id + 11). */
static inline int shapes_add_box(pqp_model *m, const double lo[3], const double size[3],
                                 int first_id)
{
    int k, rc = PQP_OK;
    for (k = 0; k < 12 && rc == PQP_OK; k++) {
        double t[3][3];
        shapes_box_triangle(lo, size, k, t);
        rc = pqp_model_add_tri(m, t[0], t[1], t[2], first_id + k);
    }
    return rc;
}

/* Distance from point p to triangle t, by brute force: the nearest of the plane projection (when
 * inside) and the three edges. Independent of the library. */
static inline double shapes_point_triangle_distance(const double p[3], double t[3][3])
{
    double best = 1e300;
    double e0[3], e1[3], n[3], w[3], nn, s, u, v, q[3];
    int i, a;
    for (a = 0; a < 3; a++) {
        e0[a] = t[1][a] - t[0][a];
        e1[a] = t[2][a] - t[0][a];
        w[a] = p[a] - t[0][a];
    }
    n[0] = e0[1] * e1[2] - e0[2] * e1[1];
    n[1] = e0[2] * e1[0] - e0[0] * e1[2];
    n[2] = e0[0] * e1[1] - e0[1] * e1[0];
    nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (nn > 0) {
        /* Barycentric coordinates of the projection. */
        double d00 = 0, d01 = 0, d11 = 0, d20 = 0, d21 = 0, den;
        for (a = 0; a < 3; a++) {
            d00 += e0[a] * e0[a];
            d01 += e0[a] * e1[a];
            d11 += e1[a] * e1[a];
            d20 += w[a] * e0[a];
            d21 += w[a] * e1[a];
        }
        den = d00 * d11 - d01 * d01;
        u = (d11 * d20 - d01 * d21) / den;
        v = (d00 * d21 - d01 * d20) / den;
        if (u >= 0 && v >= 0 && u + v <= 1) {
            s = (n[0] * w[0] + n[1] * w[1] + n[2] * w[2]) / sqrt(nn);
            best = fabs(s);
        }
    }
    for (i = 0; i < 3; i++) {
        const double *a0 = t[i], *a1 = t[(i + 1) % 3];
        double d[3], dd = 0, pd = 0, dist2 = 0;
        for (a = 0; a < 3; a++) {
            d[a] = a1[a] - a0[a];
            dd += d[a] * d[a];
            pd += (p[a] - a0[a]) * d[a];
        }
        s = dd > 0 ? pd / dd : 0;
        if (s < 0) s = 0;
        if (s > 1) s = 1;
        for (a = 0; a < 3; a++) {
            q[a] = a0[a] + s * d[a] - p[a];
            dist2 += q[a] * q[a];
        }
        if (sqrt(dist2) < best) best = sqrt(dist2);
    }
    return best;
}

/* A built unit box [0,1]^3 (ids 0..11), or NULL if building failed. */
static inline pqp_model *shapes_unit_box(void)
{
    static const double lo[3] = {0, 0, 0}, size[3] = {1, 1, 1};
    pqp_model *m = pqp_model_create();
    if (m == NULL) return NULL;
    if (pqp_model_begin(m, 12) != PQP_OK || shapes_add_box(m, lo, size, 0) != PQP_OK ||
        pqp_model_end(m) != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

/* A "fence": n triangles, triangle k in the plane x = k with vertices (k,0,0), (k,1,0), (k,0,1),
 * id k. */
static inline pqp_model *shapes_fence(int n)
{
    int k;
    pqp_model *m = pqp_model_create();
    if (m == NULL) return NULL;
    pqp_model_begin(m, n);
    for (k = 0; k < n; k++) {
        double a[3], b[3], c[3];
        a[0] = b[0] = c[0] = k;
        a[1] = 0; a[2] = 0;
        b[1] = 1; b[2] = 0;
        c[1] = 0; c[2] = 1;
        pqp_model_add_tri(m, a, b, c, k);
    }
    if (pqp_model_end(m) != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

/* A "rail": one thin triangle in the plane z = 0.2 from x = 0 to x = len, along y = 0.2:
 * (0,0.2,0.2), (len,0.2,0.2), (len,0.3,0.2), id `id`. Translated by t along x it crosses fence
 * triangle k exactly when t <= k <= t + len (the point (k, 0.2, 0.2) lies in both). */
static inline pqp_model *shapes_rail(double len, int id)
{
    double a[3] = {0, 0.2, 0.2}, b[3] = {0, 0.2, 0.2}, c[3] = {0, 0.3, 0.2};
    pqp_model *m = pqp_model_create();
    if (m == NULL) return NULL;
    b[0] = len;
    c[0] = len;
    pqp_model_begin(m, 1);
    pqp_model_add_tri(m, a, b, c, id);
    if (pqp_model_end(m) != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

#endif
