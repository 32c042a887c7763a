/* Moving and deforming models through the C ABI: pqp_model_refit (answers after a refit, PQP
 * 1.3's view refreshed, every bad argument's code with the model unchanged) and
 * pqp_self_collide (answers known by construction, adjacency, bad arguments), and
 * pqp_within_distance (pairs of two parallel sheets at known distances, bad arguments). */
#include <pqp/pqp.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};

#define N 10 /* grid cells per side */
#define NT (2 * N * N)

/* The sheet's vertex (i, j) at height z(i, j) = lift * x * x (x in [-1, 1]). */
static void sheet_vertex(int i, int j, double lift, double out[3])
{
    double x = 2.0 * i / N - 1.0, y = 2.0 * j / N - 1.0;
    out[0] = x;
    out[1] = y;
    out[2] = lift * x * x;
}

/* The sheet's triangles at `lift`, 9 doubles each, in the order pqp_model_add_tri got them. */
static void sheet_coords(double lift, double *c)
{
    int i, j, k = 0;
    for (i = 0; i < N; i++) {
        for (j = 0; j < N; j++) {
            sheet_vertex(i, j, lift, c + 9 * k);
            sheet_vertex(i + 1, j, lift, c + 9 * k + 3);
            sheet_vertex(i + 1, j + 1, lift, c + 9 * k + 6);
            k++;
            sheet_vertex(i, j, lift, c + 9 * k);
            sheet_vertex(i + 1, j + 1, lift, c + 9 * k + 3);
            sheet_vertex(i, j + 1, lift, c + 9 * k + 6);
            k++;
        }
    }
}

static pqp_model *model_of(const double *c, int n)
{
    pqp_model *m = pqp_model_create();
    int k;
    CHECK(m != NULL);
    CHECK_EQ(pqp_model_begin(m, n), PQP_OK);
    for (k = 0; k < n; k++) CHECK_EQ(pqp_model_add_tri(m, c + 9 * k, c + 9 * k + 3, c + 9 * k + 6, 100 + k), PQP_OK);
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    return m;
}

/* Distance from a tiny triangle at (0, 0, h) to the sheet: the sheet's lowest point under it is
 * its centre line x = 0, at height 0 whatever the lift, so the distance is h. At (0.5, 0, h) the
 * sheet is at lift / 4 there; the distance is at most h - lift / 4. */
static void refit_answers(void)
{
    static double c[9 * NT];
    double probe[9] = {-0.01, -0.01, 0.5, 0.01, -0.01, 0.5, 0.0, 0.01, 0.5};
    double T[3] = {0.5, 0.0, 0.0};
    pqp_model *sheet, *p, *rebuilt;
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_collide_result *r = pqp_collide_result_create();
    const pqp_tri *tris;
    const pqp_bv *bvs;
    int nt, nb, step, k, nr;
    sheet_coords(0.0, c);
    sheet = model_of(c, NT);
    p = model_of(probe, 1);
    /* The views are made before the refit, and must be made afresh after it. */
    CHECK_EQ(pqp_model_tris(sheet, &tris, &nt), PQP_OK);
    CHECK_EQ(pqp_model_bvs(sheet, &bvs, &nb), PQP_OK);
    for (step = 1; step <= 4; step++) {
        double lift = 0.5 * step;
        sheet_coords(lift, c);
        CHECK_EQ(pqp_model_refit(sheet, c, NT), PQP_OK);
        CHECK_EQ(pqp_model_num_tris(sheet), NT);
        rebuilt = model_of(c, NT);
        for (k = 0; k < 8; k++) {
            double dr, db;
            T[0] = 0.15 * k - 0.3;
            CHECK_EQ(pqp_distance(d, I3, ZERO3, sheet, I3, T, p, 0.0, 0.0, 2), PQP_OK);
            dr = pqp_distance_result_distance(d);
            CHECK_EQ(pqp_distance(d, I3, ZERO3, rebuilt, I3, T, p, 0.0, 0.0, 2), PQP_OK);
            db = pqp_distance_result_distance(d);
            CHECK_NEAR(dr, db, 1e-12);
            /* The sheet's height under the probe is about lift * x^2, never below it. */
            CHECK(dr <= 0.5 - lift * T[0] * T[0] + 1e-12 || lift * T[0] * T[0] >= 0.5);
            CHECK_EQ(pqp_collide(r, I3, ZERO3, sheet, I3, T, p, PQP_ALL_CONTACTS), PQP_OK);
            nr = pqp_collide_result_num_pairs(r);
            CHECK_EQ(pqp_collide(r, I3, ZERO3, rebuilt, I3, T, p, PQP_ALL_CONTACTS), PQP_OK);
            CHECK_EQ(nr, pqp_collide_result_num_pairs(r));
            CHECK_EQ(nr > 0, dr == 0.0);
        }
        pqp_model_destroy(rebuilt);
        CHECK_EQ(pqp_model_tris(sheet, &tris, &nt), PQP_OK);
        CHECK_EQ(nt, NT);
        CHECK(memcmp(tris[NT - 1].p3, c + 9 * (NT - 1) + 6, sizeof(double[3])) == 0);
        CHECK_EQ(tris[7].id, 107);
        CHECK_EQ(pqp_model_bvs(sheet, &bvs, &nb), PQP_OK);
        CHECK_EQ(nb, 2 * NT - 1);
        /* The root's box reaches the sheet's highest point, lift, along some axis. */
        CHECK(bvs[0].d[0] + bvs[0].d[1] + bvs[0].d[2] >= lift / 2);
    }
    pqp_collide_result_destroy(r);
    pqp_distance_result_destroy(d);
    pqp_model_destroy(p);
    pqp_model_destroy(sheet);
}

static void refit_errors(void)
{
    static double c[9 * NT], moved[9 * NT];
    pqp_model *m, *fresh = pqp_model_create();
    pqp_distance_result *d = pqp_distance_result_create();
    double probe[9] = {0, 0, 1, 0.1, 0, 1, 0, 0.1, 1};
    pqp_model *p = model_of(probe, 1);
    const pqp_tri *tris;
    int nt;
    double before;
    sheet_coords(0.25, c);
    m = model_of(c, NT);
    CHECK_EQ(pqp_distance(d, I3, ZERO3, m, I3, ZERO3, p, 0.0, 0.0, 2), PQP_OK);
    before = pqp_distance_result_distance(d);
    sheet_coords(1.5, moved);
    CHECK_EQ(pqp_model_refit(NULL, moved, NT), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_refit(m, NULL, NT), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_refit(m, moved, NT - 1), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_model_refit(m, moved, NT + 1), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_model_refit(m, moved, (size_t)-1), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_model_refit(m, moved, 0), PQP_ERR_INVALID_ARGUMENT);
    moved[9 * NT - 1] = NAN;
    CHECK_EQ(pqp_model_refit(m, moved, NT), PQP_ERR_NONFINITE_COORDINATE);
    moved[9 * NT - 1] = INFINITY;
    CHECK_EQ(pqp_model_refit(m, moved, NT), PQP_ERR_NONFINITE_COORDINATE);
    moved[9 * NT - 1] = 2e150;
    CHECK_EQ(pqp_model_refit(m, moved, NT), PQP_ERR_NONFINITE_COORDINATE);
    /* Unchanged: the same distance and the same triangles. */
    CHECK_EQ(pqp_distance(d, I3, ZERO3, m, I3, ZERO3, p, 0.0, 0.0, 2), PQP_OK);
    CHECK(pqp_distance_result_distance(d) == before);
    CHECK_EQ(pqp_model_tris(m, &tris, &nt), PQP_OK);
    CHECK(tris[NT - 1].p3[2] == c[9 * NT - 1]);
    /* Unbuilt models: fresh, begun, and given triangles but not ended. */
    CHECK_EQ(pqp_model_refit(fresh, moved, 0), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_model_refit(fresh, moved, 1), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_model_begin(fresh, 1), PQP_OK);
    CHECK_EQ(pqp_model_add_tri(fresh, probe, probe + 3, probe + 6, 0), PQP_OK);
    CHECK_EQ(pqp_model_refit(fresh, probe, 1), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_model_end(fresh), PQP_OK);
    CHECK_EQ(pqp_model_refit(fresh, probe, 1), PQP_OK);
    pqp_model_destroy(fresh);
    pqp_model_destroy(p);
    pqp_model_destroy(m);
    pqp_distance_result_destroy(d);
}

/* Self-collision: a closed box (no pair), the box with a triangle folded onto its neighbour and
 * a duplicate (their pairs, the earlier added triangle first), and the error codes. */
static void self_collision(void)
{
    static const double v[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    static const int f[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                 {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
    double c[9 * 14];
    int k, i;
    pqp_model *box, *bad, *fresh = pqp_model_create();
    pqp_collide_result *r = pqp_collide_result_create();
    for (k = 0; k < 12; k++)
        for (i = 0; i < 3; i++) memcpy(c + 9 * k + 3 * i, v[f[k][i]], sizeof(double[3]));
    box = model_of(c, 12);
    CHECK_EQ(pqp_self_collide(r, box, PQP_ALL_CONTACTS), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 0);
    /* Triangle 1 (0 3 2) folded onto triangle 0 (0 2 1) across their edge 0 2: its vertex 3
     * moved to (0.75, 0.25, 0), on 0's side. Triangle 13 duplicates triangle 4. */
    memcpy(c + 9 * 12, c + 9 * 1, sizeof(double[9]));
    c[9 * 12 + 3] = 0.75;
    c[9 * 12 + 4] = 0.25;
    memcpy(c + 9 * 13, c + 9 * 4, sizeof(double[9]));
    bad = model_of(c, 14);
    CHECK_EQ(pqp_self_collide(r, bad, PQP_ALL_CONTACTS), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 2);
    for (k = 0; k < pqp_collide_result_num_pairs(r); k++) {
        int a = pqp_collide_result_id1(r, k), b = pqp_collide_result_id2(r, k);
        CHECK((a == 100 && b == 112) || (a == 104 && b == 113));
    }
    CHECK_EQ(pqp_self_collide(r, bad, PQP_FIRST_CONTACT), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 1);
    /* Errors leave r as it was. */
    CHECK_EQ(pqp_self_collide(NULL, bad, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_self_collide(r, NULL, PQP_ALL_CONTACTS), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_self_collide(r, bad, 0), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_self_collide(r, bad, 3), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_self_collide(r, fresh, PQP_ALL_CONTACTS), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 1);
    /* After a refit that unfolds and moves the duplicate away: nothing. */
    memcpy(c + 9 * 12, c + 9 * 1, sizeof(double[9]));
    for (k = 0; k < 9; k++) c[9 * 13 + k] += 5.0;
    CHECK_EQ(pqp_model_refit(bad, c, 14), PQP_OK);
    CHECK_EQ(pqp_self_collide(r, bad, PQP_ALL_CONTACTS), PQP_OK);
    /* Triangle 12 is now triangle 1 again: identical triangles are reported. */
    CHECK_EQ(pqp_collide_result_num_pairs(r), 1);
    CHECK_EQ(pqp_collide_result_id1(r, 0), 101);
    CHECK_EQ(pqp_collide_result_id2(r, 0), 112);
    pqp_collide_result_destroy(r);
    pqp_model_destroy(fresh);
    pqp_model_destroy(bad);
    pqp_model_destroy(box);
}

/* Two copies of the flat sheet, the second lifted by 0.3 and shifted by half a cell along x:
 * every pair is at least 0.3 apart, and a triangle's pairs within 0.3 + s grow with s. */
static void within_distance(void)
{
    static double c[9 * NT];
    double T[3] = {0.1, 0.0, 0.3}, nan = NAN;
    pqp_model *a, *b, *fresh = pqp_model_create();
    pqp_collide_result *r = pqp_collide_result_create();
    int n0, n1, n2, k;
    sheet_coords(0.0, c);
    a = model_of(c, NT);
    b = model_of(c, NT);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.0), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 0);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.2999), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), 0);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.3), PQP_OK);
    n0 = pqp_collide_result_num_pairs(r);
    CHECK(n0 > 0);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.35), PQP_OK);
    n1 = pqp_collide_result_num_pairs(r);
    CHECK(n1 > n0);
    for (k = 0; k < n1; k++) {
        CHECK(pqp_collide_result_id1(r, k) >= 100 && pqp_collide_result_id1(r, k) < 100 + NT);
        CHECK(pqp_collide_result_id2(r, k) >= 100 && pqp_collide_result_id2(r, k) < 100 + NT);
    }
    /* Every pair, at an infinite tolerance. */
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, INFINITY), PQP_OK);
    CHECK_EQ(pqp_collide_result_num_pairs(r), NT * NT);
    /* Tolerance 0 gives the pairs of pqp_collide. */
    T[2] = 0.0;
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.0), PQP_OK);
    n2 = pqp_collide_result_num_pairs(r);
    CHECK_EQ(pqp_collide(r, I3, ZERO3, a, I3, T, b, PQP_ALL_CONTACTS), PQP_OK);
    CHECK_EQ(n2, pqp_collide_result_num_pairs(r));
    CHECK(n2 > 0);
    /* Errors leave r as it was. */
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, -1e-9), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, nan), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, fresh, 0.1), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_within_distance(NULL, I3, ZERO3, a, I3, T, b, 0.1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_within_distance(r, NULL, ZERO3, a, I3, T, b, 0.1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, NULL, b, 0.1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, NULL, I3, T, b, 0.1), PQP_ERR_NULL_POINTER);
    T[0] = nan;
    CHECK_EQ(pqp_within_distance(r, I3, ZERO3, a, I3, T, b, 0.1), PQP_ERR_NONFINITE_POSE);
    CHECK_EQ(pqp_collide_result_num_pairs(r), n2);
    pqp_collide_result_destroy(r);
    pqp_model_destroy(fresh);
    pqp_model_destroy(b);
    pqp_model_destroy(a);
}

int main(void)
{
    refit_answers();
    refit_errors();
    self_collision();
    within_distance();
    CHECK_DONE("motion");
}
