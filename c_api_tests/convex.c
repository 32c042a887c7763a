/* The convex-polyhedron C ABI (pqp_convex_*): every bad call returns its documented code or
 * fallback value and never crashes; refused queries leave results and caches as they were;
 * answers on hand-checked geometry; caches used with other models; create/destroy loops. */
#include <pqp/pqp.h>

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};
static const double FAR3[3] = {3, 0, 0};
static const double NEAR3[3] = {0.5, 0.25, 0};

/* The unit cube [0,1]^3 as 8 points, 12 triangles and 6 quads (counter-clockwise from outside). */
static const double CUBE[8 * 3] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                   0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
static const int QUADS[6 * 4] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4,
                                 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
static const int QUAD_COUNTS[6] = {4, 4, 4, 4, 4, 4};

static void cube_triangles(int tris[12 * 3])
{
    int f;
    for (f = 0; f < 6; f++) {
        const int *q = &QUADS[4 * f];
        int *t = &tris[6 * f];
        t[0] = q[0], t[1] = q[1], t[2] = q[2];
        t[3] = q[0], t[4] = q[2], t[5] = q[3];
    }
}

static pqp_convex_model *cube(void)
{
    pqp_convex_model *m = NULL;
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, 8), PQP_OK);
    CHECK(m != NULL);
    return m;
}

static void constants(void)
{
    CHECK_EQ(PQP_ERR_DEGENERATE_POINTS, -11);
    CHECK_EQ(PQP_ERR_INVALID_CONVEX_MESH, -12);
    CHECK_EQ(PQP_CONVEX_VERTEX, 0);
    CHECK_EQ(PQP_CONVEX_EDGE, 1);
    CHECK_EQ(PQP_CONVEX_FACE, 2);
    CHECK(strcmp(pqp_error_string(PQP_ERR_DEGENERATE_POINTS), "unknown error code") != 0);
    CHECK(strcmp(pqp_error_string(PQP_ERR_INVALID_CONVEX_MESH), "unknown error code") != 0);
}

static void null_handles_and_getters(void)
{
    double p[3];
    int a = 7, b = 7;
    int tris[36];
    pqp_convex_model *m = (pqp_convex_model *)&a; /* must be overwritten with NULL on error */
    cube_triangles(tris);

    pqp_convex_model_destroy(NULL);
    pqp_convex_cache_destroy(NULL);
    pqp_convex_result_destroy(NULL);

    CHECK_EQ(pqp_convex_model_from_points(NULL, CUBE, 8), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_points(&m, NULL, 8), PQP_ERR_NULL_POINTER);
    CHECK(m == NULL);
    CHECK_EQ(pqp_convex_model_from_points(&m, NULL, 0), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_triangles(NULL, CUBE, 8, tris, 12), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, NULL, 8, tris, 12), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, NULL, 12), PQP_ERR_NULL_POINTER);
    CHECK(m == NULL);
    CHECK_EQ(pqp_convex_model_from_polygons(NULL, CUBE, 8, QUAD_COUNTS, 6, QUADS, 24),
             PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, NULL, 8, QUAD_COUNTS, 6, QUADS, 24),
             PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, NULL, 6, QUADS, 24), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, NULL, 24),
             PQP_ERR_NULL_POINTER);
    CHECK(m == NULL);

    CHECK_EQ(pqp_convex_model_num_vertices(NULL), 0);
    CHECK_EQ(pqp_convex_model_num_edges(NULL), 0);
    CHECK_EQ(pqp_convex_model_num_faces(NULL), 0);
    CHECK_EQ(pqp_convex_model_vertex(NULL, 0, p), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_vertex_source(NULL, 0), -1);
    CHECK_EQ(pqp_convex_model_edge(NULL, 0, &a, &b), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_face_num_vertices(NULL, 0), 0);
    CHECK_EQ(pqp_convex_model_face(NULL, 0, &a), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_cache_clear(NULL), PQP_ERR_NULL_POINTER);

    CHECK(isnan(pqp_convex_result_distance(NULL)));
    CHECK(pqp_convex_result_p1(NULL) == NULL);
    CHECK(pqp_convex_result_p2(NULL) == NULL);
    CHECK_EQ(pqp_convex_result_intersecting(NULL), 0);
    CHECK_EQ(pqp_convex_result_feature1_kind(NULL), -1);
    CHECK_EQ(pqp_convex_result_feature1_index(NULL), -1);
    CHECK_EQ(pqp_convex_result_feature2_kind(NULL), -1);
    CHECK_EQ(pqp_convex_result_feature2_index(NULL), -1);
    CHECK(isnan(pqp_convex_result_depth(NULL)));
    CHECK(pqp_convex_result_normal(NULL) == NULL);
    CHECK(pqp_convex_result_deepest_p1(NULL) == NULL);
    CHECK(pqp_convex_result_deepest_p2(NULL) == NULL);
    CHECK_EQ(pqp_convex_result_num_iterations(NULL), 0);
    CHECK_EQ(pqp_convex_result_num_local_minima(NULL), 0);
}

static void fresh_result(const pqp_convex_result *r)
{
    CHECK(isinf(pqp_convex_result_distance(r)) && pqp_convex_result_distance(r) > 0);
    CHECK_EQ(pqp_convex_result_intersecting(r), 0);
    CHECK_EQ(pqp_convex_result_feature1_kind(r), -1);
    CHECK_EQ(pqp_convex_result_feature2_index(r), -1);
    CHECK(isnan(pqp_convex_result_depth(r)));
    CHECK(pqp_convex_result_p1(r)[0] == 0.0 && pqp_convex_result_p2(r)[2] == 0.0);
    CHECK_EQ(pqp_convex_result_num_iterations(r), 0);
}

static void bad_point_sets(void)
{
    pqp_convex_model *m = NULL;
    double pts[64 * 3];
    int i;

    /* Empty, one point, duplicates of one point, three points. */
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, 0), PQP_ERR_DEGENERATE_POINTS);
    CHECK(m == NULL);
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, 1), PQP_ERR_DEGENERATE_POINTS);
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, 3), PQP_ERR_DEGENERATE_POINTS);
    for (i = 0; i < 64; i++) pts[3 * i] = 1.5, pts[3 * i + 1] = -2, pts[3 * i + 2] = 0.25;
    CHECK_EQ(pqp_convex_model_from_points(&m, pts, 64), PQP_ERR_DEGENERATE_POINTS);
    /* Two distinct points repeated. */
    for (i = 0; i < 64; i += 2) pts[3 * i] = 7;
    CHECK_EQ(pqp_convex_model_from_points(&m, pts, 64), PQP_ERR_DEGENERATE_POINTS);
    /* Collinear. */
    for (i = 0; i < 64; i++) pts[3 * i] = i, pts[3 * i + 1] = 2.0 * i, pts[3 * i + 2] = -0.5 * i;
    CHECK_EQ(pqp_convex_model_from_points(&m, pts, 64), PQP_ERR_DEGENERATE_POINTS);
    /* Coplanar on a tilted plane (exactly representable), and a flat square (the cube's bottom). */
    for (i = 0; i < 64; i++) {
        double x = i % 8, y = i / 8;
        pts[3 * i] = x, pts[3 * i + 1] = y, pts[3 * i + 2] = 3 * x - 2 * y + 1;
    }
    CHECK_EQ(pqp_convex_model_from_points(&m, pts, 64), PQP_ERR_DEGENERATE_POINTS);
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, 4), PQP_ERR_DEGENERATE_POINTS);
    CHECK(m == NULL);
    /* Negative count. */
    CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, -1), PQP_ERR_INVALID_ARGUMENT);
    /* Non-finite or huge coordinates, in any position. */
    for (i = 0; i < 24; i++) {
        double bad[24];
        double v[3];
        int k;
        v[0] = NAN, v[1] = INFINITY, v[2] = -1e151;
        for (k = 0; k < 3; k++) {
            memcpy(bad, CUBE, sizeof bad);
            bad[i] = v[k];
            m = (pqp_convex_model *)bad;
            CHECK_EQ(pqp_convex_model_from_points(&m, bad, 8), PQP_ERR_NONFINITE_COORDINATE);
            CHECK(m == NULL);
        }
    }
    /* A wide range of magnitudes (1 to 1e60) is fine. */
    memcpy(pts, CUBE, sizeof CUBE);
    pts[3 * 6] = 1e60;
    CHECK_EQ(pqp_convex_model_from_points(&m, pts, 8), PQP_OK);
    pqp_convex_model_destroy(m);
}

static void bad_meshes(void)
{
    pqp_convex_model *m = NULL;
    int tris[36], bad[36];
    int quads[24];
    int counts[6];
    double v[9 * 3];
    int i;
    cube_triangles(tris);

    /* The good ones, then one change at a time. */
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, 12), PQP_OK);
    CHECK_EQ(pqp_convex_model_num_faces(m), 6); /* coplanar triangles merged */
    pqp_convex_model_destroy(m);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, QUADS, 24), PQP_OK);
    CHECK_EQ(pqp_convex_model_num_edges(m), 12);
    pqp_convex_model_destroy(m);
    m = NULL;

    /* Bad indices and counts: PQP_ERR_INVALID_ARGUMENT. */
    memcpy(bad, tris, sizeof bad);
    bad[5] = 8;
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, bad, 12), PQP_ERR_INVALID_ARGUMENT);
    bad[5] = -1;
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, bad, 12), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, -3), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, -8, tris, 12), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, QUADS, 23),
             PQP_ERR_INVALID_ARGUMENT);
    memcpy(counts, QUAD_COUNTS, sizeof counts);
    counts[4] = 6, counts[5] = 2;
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, counts, 6, QUADS, 24), PQP_ERR_INVALID_ARGUMENT);
    counts[4] = 5, counts[5] = -1; /* sums to 24 with a negative count */
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, counts, 6, QUADS, 24), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, -6, QUADS, 24),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK(m == NULL);

    /* Not a closed convex polyhedron: PQP_ERR_INVALID_CONVEX_MESH. */
    /* Open: a triangle missing; empty; fewer than 4 faces. */
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, 11), PQP_ERR_INVALID_CONVEX_MESH);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, 0), PQP_ERR_INVALID_CONVEX_MESH);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 0, tris, 0), PQP_ERR_INVALID_CONVEX_MESH);
    /* Inside out. */
    for (i = 0; i < 12; i++) bad[3 * i] = tris[3 * i + 2], bad[3 * i + 1] = tris[3 * i + 1], bad[3 * i + 2] = tris[3 * i];
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, bad, 12), PQP_ERR_INVALID_CONVEX_MESH);
    /* One triangle flipped. */
    memcpy(bad, tris, sizeof bad);
    bad[0] = tris[1], bad[1] = tris[0];
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, bad, 12), PQP_ERR_INVALID_CONVEX_MESH);
    /* A triangle given twice (non-manifold). */
    memcpy(bad, tris, sizeof bad);
    memcpy(&bad[3], &bad[0], 3 * sizeof(int));
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, bad, 12), PQP_ERR_INVALID_CONVEX_MESH);
    /* Not convex: a corner pushed inside (the triangles stay planar). */
    memcpy(v, CUBE, sizeof CUBE);
    v[3 * 6] = 0.6, v[3 * 6 + 1] = 0.6, v[3 * 6 + 2] = 0.6;
    CHECK_EQ(pqp_convex_model_from_triangles(&m, v, 8, tris, 12), PQP_ERR_INVALID_CONVEX_MESH);
    /* A non-planar quad. */
    memcpy(v, CUBE, sizeof CUBE);
    v[3 * 6 + 2] = 1.1;
    CHECK_EQ(pqp_convex_model_from_polygons(&m, v, 8, QUAD_COUNTS, 6, QUADS, 24), PQP_ERR_INVALID_CONVEX_MESH);
    /* A non-convex (self-crossing) quad. */
    memcpy(quads, QUADS, sizeof quads);
    quads[0] = QUADS[1], quads[1] = QUADS[0];
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, quads, 24), PQP_ERR_INVALID_CONVEX_MESH);
    /* An unused vertex. */
    memcpy(v, CUBE, sizeof CUBE);
    v[24] = 5, v[25] = 5, v[26] = 5;
    CHECK_EQ(pqp_convex_model_from_triangles(&m, v, 9, tris, 12), PQP_ERR_INVALID_CONVEX_MESH);
    /* Flat: a square given twice, back to back (closed and oriented, but no volume). */
    {
        static const int sq[8] = {0, 1, 2, 3, 3, 2, 1, 0};
        static const int c2[2] = {4, 4};
        static const int two[12] = {0, 1, 2, 0, 2, 3, 2, 1, 0, 3, 2, 0};
        CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 4, c2, 2, sq, 8), PQP_ERR_INVALID_CONVEX_MESH);
        CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 4, two, 4), PQP_ERR_INVALID_CONVEX_MESH);
    }
    /* NaN coordinate. */
    memcpy(v, CUBE, sizeof CUBE);
    v[4] = NAN;
    CHECK_EQ(pqp_convex_model_from_triangles(&m, v, 8, tris, 12), PQP_ERR_NONFINITE_COORDINATE);
    CHECK(m == NULL);
}

/* Counts past their documented limits are refused with PQP_ERR_INVALID_ARGUMENT before anything
 * is allocated or read: the arrays given are small and real, so reading by the count would run
 * past them (AddressSanitizer in the CMake build) or allocating by it fail. */
static void counts_past_their_limits(void)
{
    static const int past[4] = {(1 << 30) + 1, (1 << 30) + 2, INT_MAX - 1, INT_MAX};
    int tris[12 * 3], more[16 * 3], k;
    pqp_convex_model *m = NULL;
    cube_triangles(tris);
    for (k = 0; k < 4; k++) {
        CHECK_EQ(pqp_convex_model_from_points(&m, CUBE, past[k]), PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, past[k], tris, 12),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, past[k], QUAD_COUNTS, 6, QUADS, 24),
                 PQP_ERR_INVALID_ARGUMENT);
        /* More triangles, faces or indices than any closed mesh on the 8 vertices has. */
        CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, past[k]),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, past[k], QUADS, 24),
                 PQP_ERR_INVALID_ARGUMENT);
        CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, QUADS, past[k]),
                 PQP_ERR_INVALID_ARGUMENT);
    }
    /* Just past the mesh limits: 2 V + 1 triangles or faces, 6 V + 1 indices. */
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, tris, 17), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 4, tris, 9), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 17, QUADS, 24),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_from_polygons(&m, CUBE, 8, QUAD_COUNTS, 6, QUADS, 49),
             PQP_ERR_INVALID_ARGUMENT);
    /* At the limit the arrays are read: 16 triangles (the cube's and four repeated) are no
     * convex mesh. */
    memcpy(more, tris, sizeof tris);
    memcpy(more + 12 * 3, tris, 4 * 3 * sizeof(int));
    CHECK_EQ(pqp_convex_model_from_triangles(&m, CUBE, 8, more, 16), PQP_ERR_INVALID_CONVEX_MESH);
    CHECK(m == NULL);
}

static void accessors(void)
{
    pqp_convex_model *m = NULL;
    double pts[9 * 3];
    double p[3] = {-1, -1, -1};
    int t = -5, h = -5, f, face[8], seen[8] = {0};
    int nv, ne, nf;
    /* The cube with its centre and a repeated corner: still 8 vertices, 12 edges, 6 faces. */
    memcpy(pts, CUBE, sizeof CUBE);
    pts[24] = 0.5, pts[25] = 0.5, pts[26] = 0.5;
    {
        double more[10 * 3];
        memcpy(more, pts, sizeof pts);
        more[27] = 1, more[28] = 1, more[29] = 1;
        CHECK_EQ(pqp_convex_model_from_points(&m, more, 10), PQP_OK);
    }
    nv = pqp_convex_model_num_vertices(m), ne = pqp_convex_model_num_edges(m), nf = pqp_convex_model_num_faces(m);
    CHECK_EQ(nv, 8);
    CHECK_EQ(ne, 12);
    CHECK_EQ(nf, 6);
    for (f = 0; f < nv; f++) {
        int src = pqp_convex_model_vertex_source(m, f);
        CHECK(src >= 0 && src < 8);
        CHECK_EQ(pqp_convex_model_vertex(m, f, p), PQP_OK);
        CHECK(src >= 0 && src < 8 && memcmp(p, &CUBE[3 * src], sizeof p) == 0);
    }
    CHECK_EQ(pqp_convex_model_vertex(m, nv, p), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_vertex(m, -1, p), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_convex_model_vertex(m, 0, NULL), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_vertex_source(m, nv), -1);
    CHECK_EQ(pqp_convex_model_vertex_source(m, -1), -1);
    CHECK_EQ(pqp_convex_model_edge(m, 0, &t, &h), PQP_OK);
    CHECK(t >= 0 && t < 8 && h >= 0 && h < 8 && t != h);
    t = h = -5;
    CHECK_EQ(pqp_convex_model_edge(m, ne, &t, &h), PQP_ERR_INVALID_ARGUMENT);
    CHECK(t == -5 && h == -5);
    CHECK_EQ(pqp_convex_model_edge(m, 0, NULL, &h), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_model_edge(m, 0, &t, NULL), PQP_ERR_NULL_POINTER);
    for (f = 0; f < nf; f++) {
        int k;
        CHECK_EQ(pqp_convex_model_face_num_vertices(m, f), 4);
        CHECK_EQ(pqp_convex_model_face(m, f, face), PQP_OK);
        for (k = 0; k < 4; k++) {
            CHECK(face[k] >= 0 && face[k] < 8);
            if (face[k] >= 0 && face[k] < 8) seen[face[k]]++;
        }
    }
    for (f = 0; f < 8; f++) CHECK_EQ(seen[f], 3);
    CHECK_EQ(pqp_convex_model_face_num_vertices(m, nf), 0);
    CHECK_EQ(pqp_convex_model_face_num_vertices(m, -1), 0);
    face[0] = -7;
    CHECK_EQ(pqp_convex_model_face(m, nf, face), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(face[0], -7);
    CHECK_EQ(pqp_convex_model_face(m, 0, NULL), PQP_ERR_NULL_POINTER);
    pqp_convex_model_destroy(m);
}

/* Copies what a result holds, to check that refused queries leave it unchanged. */
struct snap {
    double d, depth, p1[3], p2[3], n[3];
    int inter, k1, i1, k2, i2;
    int64_t it;
};

static struct snap snap_of(const pqp_convex_result *r)
{
    struct snap s;
    s.d = pqp_convex_result_distance(r);
    s.depth = pqp_convex_result_depth(r);
    memcpy(s.p1, pqp_convex_result_p1(r), sizeof s.p1);
    memcpy(s.p2, pqp_convex_result_p2(r), sizeof s.p2);
    memcpy(s.n, pqp_convex_result_normal(r), sizeof s.n);
    s.inter = pqp_convex_result_intersecting(r);
    s.k1 = pqp_convex_result_feature1_kind(r), s.i1 = pqp_convex_result_feature1_index(r);
    s.k2 = pqp_convex_result_feature2_kind(r), s.i2 = pqp_convex_result_feature2_index(r);
    s.it = pqp_convex_result_num_iterations(r);
    return s;
}

static int same(struct snap a, struct snap b)
{
    /* Bitwise for the doubles (depth may be NaN). */
    return memcmp(&a.d, &b.d, sizeof a.d) == 0 && memcmp(&a.depth, &b.depth, sizeof a.depth) == 0 &&
           memcmp(a.p1, b.p1, sizeof a.p1) == 0 && memcmp(a.p2, b.p2, sizeof a.p2) == 0 &&
           memcmp(a.n, b.n, sizeof a.n) == 0 && a.inter == b.inter && a.k1 == b.k1 && a.i1 == b.i1 &&
           a.k2 == b.k2 && a.i2 == b.i2 && a.it == b.it;
}

static void bad_queries(void)
{
    pqp_convex_model *a = cube(), *b = cube();
    pqp_convex_result *r = pqp_convex_result_create();
    pqp_convex_cache *c = pqp_convex_cache_create();
    double R[9], T[3];
    int flag = 9, i, k;
    struct snap before;
    double bad[4];
    bad[0] = NAN, bad[1] = INFINITY, bad[2] = -INFINITY, bad[3] = 2e150;
    CHECK(r != NULL && c != NULL);
    fresh_result(r);

    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, FAR3, b, c), PQP_OK);
    before = snap_of(r);
    CHECK_NEAR(before.d, 2.0, 1e-12);

    /* NULLs, in each position; the cache is optional. */
    CHECK_EQ(pqp_convex_distance(NULL, I3, ZERO3, a, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, NULL, ZERO3, a, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, I3, NULL, a, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, NULL, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, NULL, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, NULL, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, FAR3, NULL, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_penetration(NULL, I3, ZERO3, a, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, NULL, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, a, I3, FAR3, b, NULL), PQP_OK);
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, FAR3, b, c), PQP_OK);
    CHECK(same(before, snap_of(r)));
    CHECK_EQ(pqp_convex_intersect(NULL, I3, ZERO3, a, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_intersect(&flag, I3, ZERO3, NULL, I3, FAR3, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_convex_intersect(&flag, I3, ZERO3, a, I3, NULL, b, c), PQP_ERR_NULL_POINTER);
    CHECK_EQ(flag, 9);

    /* NaN, infinite, huge pose entries, in every position of both poses. */
    for (k = 0; k < 4; k++) {
        for (i = 0; i < 12; i++) {
            memcpy(R, I3, sizeof R);
            memcpy(T, FAR3, sizeof T);
            if (i < 9) R[i] = bad[k];
            else T[i - 9] = bad[k];
            CHECK_EQ(pqp_convex_distance(r, R, T, a, I3, FAR3, b, c), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, R, T, b, c), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, a, R, T, b, NULL), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(pqp_convex_intersect(&flag, R, T, a, I3, ZERO3, b, c), PQP_ERR_NONFINITE_POSE);
            CHECK_EQ(flag, 9);
        }
    }
    CHECK(same(before, snap_of(r)));

    /* The intersect verdicts. */
    CHECK_EQ(pqp_convex_intersect(&flag, I3, ZERO3, a, I3, FAR3, b, c), PQP_OK);
    CHECK_EQ(flag, 0);
    CHECK_EQ(pqp_convex_intersect(&flag, I3, ZERO3, a, I3, NEAR3, b, NULL), PQP_OK);
    CHECK_EQ(flag, 1);

    pqp_convex_result_destroy(r);
    pqp_convex_cache_destroy(c);
    pqp_convex_model_destroy(a);
    pqp_convex_model_destroy(b);
}

static void answers(void)
{
    pqp_convex_model *a = cube(), *b = NULL;
    pqp_convex_result *r = pqp_convex_result_create();
    int tris[36];
    /* b: the cube as a mesh, i.e. a different model with the same shape. */
    cube_triangles(tris);
    CHECK_EQ(pqp_convex_model_from_triangles(&b, CUBE, 8, tris, 12), PQP_OK);

    /* Face to face, 2 apart along x: p1 on x = 1, p2 on x = 0 of b's frame. */
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, FAR3, b, NULL), PQP_OK);
    CHECK_NEAR(pqp_convex_result_distance(r), 2.0, 1e-12);
    CHECK_EQ(pqp_convex_result_intersecting(r), 0);
    CHECK_NEAR(pqp_convex_result_p1(r)[0], 1.0, 1e-12);
    CHECK_NEAR(pqp_convex_result_p2(r)[0], 0.0, 1e-12);
    CHECK(pqp_convex_result_feature1_kind(r) >= 0 && pqp_convex_result_feature1_kind(r) <= 2);
    CHECK(pqp_convex_result_feature2_index(r) >= 0);
    CHECK(pqp_convex_result_num_iterations(r) > 0);
    CHECK(isnan(pqp_convex_result_depth(r)));

    /* Overlapping by 0.5 along x, 0.875 along y, 0.9375 along z: depth 0.5, normal +x. */
    {
        static const double T[3] = {0.5, 0.125, 0.0625};
        const double *n;
        CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, a, I3, T, b, NULL), PQP_OK);
        CHECK_EQ(pqp_convex_result_intersecting(r), 1);
        CHECK(pqp_convex_result_distance(r) == 0.0);
        CHECK_NEAR(pqp_convex_result_depth(r), 0.5, 1e-12);
        n = pqp_convex_result_normal(r);
        CHECK_NEAR(n[0], 1.0, 1e-12);
    }
    /* Apart: depth 0, normal from a to b. */
    CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, a, I3, FAR3, b, NULL), PQP_OK);
    CHECK(pqp_convex_result_depth(r) == 0.0);
    CHECK_NEAR(pqp_convex_result_normal(r)[0], 1.0, 1e-12);
    CHECK_NEAR(pqp_convex_result_distance(r), 2.0, 1e-12);

    /* A model against itself at the identity: touching. */
    CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, a, I3, ZERO3, a, NULL), PQP_OK);
    CHECK_EQ(pqp_convex_result_intersecting(r), 1);
    CHECK(pqp_convex_result_distance(r) == 0.0);

    pqp_convex_result_destroy(r);
    pqp_convex_model_destroy(a);
    pqp_convex_model_destroy(b);
}

/* One cache used with other models, in the other order, cleared, and after a model it saw is
 * destroyed: answers always equal the cold ones. */
static void caches(void)
{
    pqp_convex_model *a = cube(), *b = NULL, *c = NULL;
    pqp_convex_result *warm = pqp_convex_result_create(), *cold = pqp_convex_result_create();
    pqp_convex_cache *k = pqp_convex_cache_create();
    double pts[40 * 3];
    int i, step;
    uint32_t s = 12345u;
    for (i = 0; i < 40 * 3; i++) {
        s = s * 1664525u + 1013904223u;
        pts[i] = (double)(s >> 8) / 16777216.0 - 0.5;
    }
    CHECK_EQ(pqp_convex_model_from_points(&b, pts, 40), PQP_OK);
    CHECK_EQ(pqp_convex_model_from_points(&c, pts, 20), PQP_OK);
    for (step = 0; step < 300; step++) {
        double T[3], R[9];
        double t = 0.05 * step, ca = cos(t), sa = sin(t);
        const pqp_convex_model *m1 = (step % 3 == 0) ? a : b, *m2 = (step % 5 == 0) ? c : a;
        R[0] = ca, R[1] = -sa, R[2] = 0, R[3] = sa, R[4] = ca, R[5] = 0, R[6] = 0, R[7] = 0, R[8] = 1;
        T[0] = 2.0 * cos(0.3 * t), T[1] = 0.3, T[2] = 0.1;
        if (step % 7 == 0) CHECK_EQ(pqp_convex_cache_clear(k), PQP_OK);
        if (step % 11 == 0) {
            const pqp_convex_model *x = m1;
            m1 = m2, m2 = x;
        }
        CHECK_EQ(pqp_convex_distance(warm, I3, ZERO3, m1, R, T, m2, k), PQP_OK);
        CHECK_EQ(pqp_convex_distance(cold, I3, ZERO3, m1, R, T, m2, NULL), PQP_OK);
        CHECK_NEAR(pqp_convex_result_distance(warm), pqp_convex_result_distance(cold), 1e-12);
        CHECK_EQ(pqp_convex_result_intersecting(warm), pqp_convex_result_intersecting(cold));
        CHECK_EQ(pqp_convex_intersect(&i, I3, ZERO3, m1, R, T, m2, k), PQP_OK);
        CHECK_EQ(i, pqp_convex_result_intersecting(cold));
        i = 0;
    }
    /* A model the cache saw is destroyed and another may take its address: still right. */
    pqp_convex_model_destroy(c);
    c = NULL;
    CHECK_EQ(pqp_convex_model_from_points(&c, pts, 30), PQP_OK);
    CHECK_EQ(pqp_convex_distance(warm, I3, ZERO3, c, I3, FAR3, a, k), PQP_OK);
    CHECK_EQ(pqp_convex_distance(cold, I3, ZERO3, c, I3, FAR3, a, NULL), PQP_OK);
    CHECK_NEAR(pqp_convex_result_distance(warm), pqp_convex_result_distance(cold), 1e-12);

    pqp_convex_result_destroy(warm);
    pqp_convex_result_destroy(cold);
    pqp_convex_cache_destroy(k);
    pqp_convex_model_destroy(a);
    pqp_convex_model_destroy(b);
    pqp_convex_model_destroy(c);
}

static void create_destroy_loops(void)
{
    int i;
    for (i = 0; i < 2000; i++) {
        pqp_convex_model *m = NULL;
        pqp_convex_result *r = pqp_convex_result_create();
        pqp_convex_cache *c = pqp_convex_cache_create();
        int rc = pqp_convex_model_from_points(&m, CUBE, (i % 3 == 0) ? 3 : 8);
        CHECK_EQ(rc, (i % 3 == 0) ? PQP_ERR_DEGENERATE_POINTS : PQP_OK);
        if (m) {
            CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, m, I3, FAR3, m, c), PQP_OK);
            CHECK_EQ(pqp_convex_penetration(r, I3, ZERO3, m, I3, NEAR3, m, c), PQP_OK);
        } else {
            CHECK_EQ(pqp_convex_distance(r, I3, ZERO3, m, I3, FAR3, m, c), PQP_ERR_NULL_POINTER);
        }
        if (i % 2) pqp_convex_cache_destroy(c), pqp_convex_result_destroy(r);
        else pqp_convex_result_destroy(r), pqp_convex_cache_destroy(c);
        pqp_convex_model_destroy(m);
    }
}

int main(void)
{
    constants();
    null_handles_and_getters();
    bad_point_sets();
    bad_meshes();
    counts_past_their_limits();
    accessors();
    bad_queries();
    answers();
    caches();
    create_destroy_loops();
    CHECK_DONE("convex");
}
