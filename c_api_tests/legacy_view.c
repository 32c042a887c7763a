/* PQP 1.3's view of a model as a C program reads it: the structs' layout, the triangles in the
 * order added, the volumes in PQP's layout with parent-relative frames (walked and composed here,
 * every vertex checked against every volume above it), the float view, build states, copies,
 * the closest triangles of a query, and BV.h's functions. Under AddressSanitizer (ctest) every
 * array read is checked against its allocation. */
#include <pqp/pqp.h>

#include <stddef.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

#define N 300

/* A deterministic scatter of triangles, some degenerate. */
static void make_tris(double tris[N][3][3])
{
    unsigned s = 12345u;
    int k, v, a;
    for (k = 0; k < N; k++) {
        double c[3];
        for (a = 0; a < 3; a++) {
            s = s * 1103515245u + 12345u;
            c[a] = (double)((s >> 8) % 10000) / 1000.0;
        }
        for (v = 0; v < 3; v++)
            for (a = 0; a < 3; a++) {
                s = s * 1103515245u + 12345u;
                tris[k][v][a] = c[a] + (double)((s >> 8) % 1000) / 2000.0;
            }
        if (k % 10 == 0) memcpy(tris[k][2], tris[k][0], sizeof tris[k][0]); /* a segment */
        if (k % 10 == 1) { memcpy(tris[k][1], tris[k][0], sizeof tris[k][0]);
                           memcpy(tris[k][2], tris[k][0], sizeof tris[k][0]); } /* a point */
    }
}

/* out = a * b (3x3). */
static void mul(const double a[3][3], const double b[3][3], double out[3][3])
{
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            out[i][j] = 0;
            for (k = 0; k < 3; k++) out[i][j] += a[i][k] * b[k][j];
        }
}

/* out = a * v + t. */
static void place(const double a[3][3], const double v[3], const double t[3], double out[3])
{
    int i;
    for (i = 0; i < 3; i++) out[i] = a[i][0] * v[0] + a[i][1] * v[1] + a[i][2] * v[2] + t[i];
}

/* A volume in model coordinates, with its slot. */
typedef struct {
    double R[3][3], Tr[3], To[3];
    int slot;
} placed;

/* Whether p lies in the volume's rectangle swept sphere and box (model coordinates), within tol. */
static int contains(const placed *w, const pqp_bv *b, const double p[3], double tol)
{
    double q[3], o[3], dx, dy;
    int i, k;
    for (i = 0; i < 3; i++) {
        q[i] = 0;
        o[i] = 0;
        for (k = 0; k < 3; k++) {
            q[i] += w->R[k][i] * (p[k] - w->Tr[k]);
            o[i] += w->R[k][i] * (p[k] - w->To[k]);
        }
    }
    dx = q[0] < 0 ? -q[0] : q[0] > b->l[0] ? q[0] - b->l[0] : 0;
    dy = q[1] < 0 ? -q[1] : q[1] > b->l[1] ? q[1] - b->l[1] : 0;
    if (sqrt(dx * dx + dy * dy + q[2] * q[2]) > b->r + tol) return 0;
    for (i = 0; i < 3; i++)
        if (fabs(o[i]) > b->d[i] + tol) return 0;
    return 1;
}

static double tris_in[N][3][3];
static int leaf_seen[N];

/* Walks the hierarchy from slot k, composing frames, and checks every vertex against every
 * volume on its path (path[0..depth]). Returns the number of leaves below. */
static int walk(const pqp_bv *b, int nb, const pqp_tri *t, int k, placed *path, int depth)
{
    placed *w = &path[depth];
    int a, leaves = 0;
    CHECK(k >= 0 && k < nb && depth < 200);
    if (k < 0 || k >= nb || depth >= 200) return 0;
    w->slot = k;
    if (depth == 0) {
        memcpy(w->R, b[k].R, sizeof w->R);
        memcpy(w->Tr, b[k].Tr, sizeof w->Tr);
        memcpy(w->To, b[k].To, sizeof w->To);
    } else {
        const placed *p = &path[depth - 1];
        mul(p->R, b[k].R, w->R);
        place(p->R, b[k].Tr, p->Tr, w->Tr);
        place(p->R, b[k].To, p->To, w->To);
    }
    if (b[k].first_child >= 0) {
        CHECK(b[k].first_child > k && b[k].first_child + 1 < nb);
        leaves += walk(b, nb, t, b[k].first_child, path, depth + 1);
        leaves += walk(b, nb, t, b[k].first_child + 1, path, depth + 1);
    } else {
        int tri = -b[k].first_child - 1;
        CHECK(tri >= 0 && tri < N);
        if (tri < 0 || tri >= N) return 0;
        CHECK(!leaf_seen[tri]);
        leaf_seen[tri] = 1;
        for (a = 0; a <= depth; a++) {
            const pqp_bv *v = &b[path[a].slot];
            CHECK(contains(&path[a], v, t[tri].p1, 1e-9));
            CHECK(contains(&path[a], v, t[tri].p2, 1e-9));
            CHECK(contains(&path[a], v, t[tri].p3, 1e-9));
        }
        leaves = 1;
    }
    return leaves;
}

int main(void)
{
    static placed path[200];
    pqp_model *m = pqp_model_create(), *copy = NULL;
    const pqp_tri *t = NULL;
    const pqp_bv *b = NULL;
    const pqp_tri_float *tf = NULL;
    const pqp_bv_float *bf = NULL;
    int nt = -1, nb = -1, k, a;

    /* The layout C sees is PQP's: doubles first, the int last. */
    CHECK_EQ(offsetof(pqp_tri, p2), 3 * sizeof(double));
    CHECK_EQ(offsetof(pqp_tri, id), 9 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, Tr), 9 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, l), 12 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, r), 14 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, To), 15 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, d), 18 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv, first_child), 21 * sizeof(double));
    CHECK_EQ(offsetof(pqp_bv_float, first_child), 21 * sizeof(float));

    /* Fresh: empty, no triangles, no volumes. */
    CHECK_EQ(pqp_model_build_state(m), PQP_BUILD_STATE_EMPTY);
    CHECK_EQ(pqp_model_tris(m, &t, &nt), PQP_OK);
    CHECK(t == NULL && nt == 0);
    CHECK_EQ(pqp_model_bvs(m, &b, &nb), PQP_ERR_UNPROCESSED_MODEL);
    CHECK(b == NULL && nb == 0);
    CHECK_EQ(pqp_model_end(m), PQP_ERR_BUILD_EMPTY_MODEL);

    make_tris(tris_in);
    for (k = 0; k < N; k++) {
        CHECK_EQ(pqp_model_add_tri(m, tris_in[k][0], tris_in[k][1], tris_in[k][2], 1000 + k),
                 PQP_OK);
        if (k % 50 == 0) {
            /* While building: the triangles so far. */
            CHECK_EQ(pqp_model_build_state(m), PQP_BUILD_STATE_BEGUN);
            CHECK_EQ(pqp_model_tris(m, &t, &nt), PQP_OK);
            CHECK_EQ(nt, k + 1);
            if (nt == k + 1) CHECK(memcmp(t[k].p3, tris_in[k][2], sizeof tris_in[k][2]) == 0);
        }
    }
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    CHECK_EQ(pqp_model_build_state(m), PQP_BUILD_STATE_PROCESSED);

    /* Triangles in the order added, with their ids. */
    CHECK_EQ(pqp_model_tris(m, &t, &nt), PQP_OK);
    CHECK_EQ(nt, N);
    for (k = 0; k < N && nt == N; k++) {
        CHECK(memcmp(t[k].p1, tris_in[k][0], sizeof tris_in[k][0]) == 0);
        CHECK(memcmp(t[k].p2, tris_in[k][1], sizeof tris_in[k][1]) == 0);
        CHECK(memcmp(t[k].p3, tris_in[k][2], sizeof tris_in[k][2]) == 0);
        CHECK_EQ(t[k].id, 1000 + k);
    }

    /* 2n - 1 volumes; walking them from the root meets every triangle once, inside every volume
     * above it. */
    CHECK_EQ(pqp_model_bvs(m, &b, &nb), PQP_OK);
    CHECK_EQ(nb, 2 * N - 1);
    if (nb == 2 * N - 1 && nt == N) {
        CHECK_EQ(walk(b, nb, t, 0, path, 0), N);
        for (k = 0; k < N; k++) CHECK(leaf_seen[k]);
    }

    /* The float view: the same values, rounded. */
    CHECK_EQ(pqp_model_tris_float(m, &tf, &nt), PQP_OK);
    CHECK_EQ(pqp_model_bvs_float(m, &bf, &nb), PQP_OK);
    CHECK(tf != NULL && bf != NULL);
    if (tf != NULL && bf != NULL) {
        for (k = 0; k < N; k++)
            for (a = 0; a < 3; a++) CHECK(tf[k].p2[a] == (float)t[k].p2[a]);
        for (k = 0; k < 2 * N - 1; k++) {
            CHECK(bf[k].R[2][1] == (float)b[k].R[2][1] && bf[k].r == (float)b[k].r);
            CHECK(bf[k].To[0] == (float)b[k].To[0] && bf[k].first_child == b[k].first_child);
        }
    }

    /* PQP's FitToTris on the root's axes gives the root. */
    {
        pqp_bv fit;
        memset(&fit, 0, sizeof fit);
        fit.first_child = b[0].first_child;
        CHECK_EQ(pqp_bv_fit(&fit, &b[0].R[0][0], t, N), PQP_OK);
        CHECK(memcmp(&fit, &b[0], offsetof(pqp_bv, first_child) + sizeof(int)) == 0);
    }

    /* A volume overlaps itself and is at minus twice its radius from itself. */
    {
        static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, Z[3] = {0, 0, 0};
        int o = -1;
        double d = 0;
        CHECK_EQ(pqp_bv_overlap(&o, I, Z, &b[1], &b[1]), PQP_OK);
        CHECK_EQ(o, 1);
        CHECK_EQ(pqp_bv_distance(&d, I, Z, &b[1], &b[1]), PQP_OK);
        CHECK_NEAR(d, -2 * b[1].r, 1e-12);
    }

    /* A copy answers the same; its closest triangles name the same triangles. */
    CHECK_EQ(pqp_model_clone(&copy, m), PQP_OK);
    CHECK(copy != NULL);
    {
        static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T2[3] = {0.3, -12, 0.1};
        static const double Z[3] = {0, 0, 0};
        pqp_distance_result *r1 = pqp_distance_result_create(), *r2 = pqp_distance_result_create();
        int a1 = -2, a2 = -2, c1 = -3, c2 = -3;
        CHECK_EQ(pqp_distance(r1, I, Z, m, I, T2, m, 0, 0, 2), PQP_OK);
        CHECK_EQ(pqp_distance(r2, I, Z, copy, I, T2, copy, 0, 0, 2), PQP_OK);
        CHECK(pqp_distance_result_distance(r1) == pqp_distance_result_distance(r2));
        CHECK_EQ(pqp_distance_result_triangles(r1, &a1, &a2), PQP_OK);
        CHECK_EQ(pqp_distance_result_triangles(r2, &c1, &c2), PQP_OK);
        CHECK(a1 == c1 && a2 == c2 && a1 >= 0 && a1 < N && a2 >= 0 && a2 < N);
        if (a1 >= 0 && a1 < N) {
            CHECK_EQ(t[a1].id, pqp_distance_result_id1(r1));
            CHECK_NEAR(shapes_point_triangle_distance(pqp_distance_result_p1(r1), tris_in[a1]),
                       0, 1e-9);
        }
        pqp_distance_result_destroy(r1);
        pqp_distance_result_destroy(r2);
    }
    pqp_model_destroy(m);
    /* The copy outlives the original, with its own view. */
    CHECK_EQ(pqp_model_bvs(copy, &b, &nb), PQP_OK);
    CHECK_EQ(nb, 2 * N - 1);
    CHECK_EQ(pqp_model_build_state(copy), PQP_BUILD_STATE_PROCESSED);
    pqp_model_destroy(copy);

    CHECK_DONE("legacy_view");
}
