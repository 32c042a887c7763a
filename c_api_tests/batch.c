/* Batch queries (pqp_collide_batch, pqp_distance_batch, pqp_tolerance_batch): answers known by
 * construction (a rail sliding along a fence), the same answers as single calls at random poses on
 * every thread count, and every bad argument returning its code with nothing written. */
#include <pqp/pqp.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

#define FENCE 12
#define RAIL 0.5
#define N_SLIDE 200
#define N_RANDOM 150

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/* The four pose arrays of a batch of n queries. */
struct poses {
    double *R1, *T1, *R2, *T2;
    size_t n;
};

static int poses_alloc(struct poses *p, size_t n)
{
    p->n = n;
    p->R1 = (double *)malloc(9 * n * sizeof(double));
    p->T1 = (double *)malloc(3 * n * sizeof(double));
    p->R2 = (double *)malloc(9 * n * sizeof(double));
    p->T2 = (double *)malloc(3 * n * sizeof(double));
    return p->R1 && p->T1 && p->R2 && p->T2;
}

static void poses_free(struct poses *p)
{
    free(p->R1);
    free(p->T1);
    free(p->R2);
    free(p->T2);
}

/* A random rotation (from a random unit quaternion), row by row. */
static void random_rotation(uint64_t *rng, double R[9])
{
    double q[4], len = 0;
    int k;
    for (k = 0; k < 4; k++) {
        q[k] = 2 * check_unit(rng) - 1;
        len += q[k] * q[k];
    }
    len = sqrt(len);
    for (k = 0; k < 4; k++) q[k] /= len;
    R[0] = 1 - 2 * (q[2] * q[2] + q[3] * q[3]);
    R[1] = 2 * (q[1] * q[2] - q[3] * q[0]);
    R[2] = 2 * (q[1] * q[3] + q[2] * q[0]);
    R[3] = 2 * (q[1] * q[2] + q[3] * q[0]);
    R[4] = 1 - 2 * (q[1] * q[1] + q[3] * q[3]);
    R[5] = 2 * (q[2] * q[3] - q[1] * q[0]);
    R[6] = 2 * (q[1] * q[3] - q[2] * q[0]);
    R[7] = 2 * (q[2] * q[3] + q[1] * q[0]);
    R[8] = 1 - 2 * (q[1] * q[1] + q[2] * q[2]);
}

/* The gap between the rail slid to x = t (covering [t, t + RAIL]) and the nearest fence triangle
 * (x = k for k = 0 .. FENCE - 1): the rail's points lie in front of every fence triangle. */
static double slide_gap(double t)
{
    double best = INFINITY;
    int k;
    for (k = 0; k < FENCE; k++) {
        double g = k < t ? t - k : (k > t + RAIL ? k - (t + RAIL) : 0.0);
        if (g < best) best = g;
    }
    return best;
}

static void check_slide(const pqp_model *fence, const pqp_model *rail)
{
    struct poses p;
    int colliding[N_SLIDE], closer[N_SLIDE];
    double distance[N_SLIDE];
    const unsigned threads[4] = {0, 1, 2, 1000};
    size_t i;
    int t, some_hit = 0, some_miss = 0;
    if (!poses_alloc(&p, N_SLIDE)) {
        CHECK(0);
        poses_free(&p);
        return;
    }
    for (i = 0; i < p.n; i++) {
        memcpy(p.R1 + 9 * i, I3, sizeof I3);
        memcpy(p.R2 + 9 * i, I3, sizeof I3);
        p.T1[3 * i] = p.T1[3 * i + 1] = p.T1[3 * i + 2] = 0;
        /* From x = -1.3 to 12.6 in steps of 0.07: in front of, across and past the fence. */
        p.T2[3 * i] = -1.3 + 0.07 * (double)i;
        p.T2[3 * i + 1] = p.T2[3 * i + 2] = 0;
    }
    for (t = 0; t < 4; t++) {
        CHECK_EQ(pqp_collide_batch(colliding, p.n, p.R1, p.T1, fence, p.R2, p.T2, rail,
                                   PQP_ALL_CONTACTS, threads[t]),
                 PQP_OK);
        CHECK_EQ(pqp_distance_batch(distance, p.n, p.R1, p.T1, fence, p.R2, p.T2, rail, 0.0, 0.0,
                                    threads[t]),
                 PQP_OK);
        CHECK_EQ(pqp_tolerance_batch(closer, p.n, p.R1, p.T1, fence, p.R2, p.T2, rail, 0.1,
                                     threads[t]),
                 PQP_OK);
        for (i = 0; i < p.n; i++) {
            double gap = slide_gap(p.T2[3 * i]);
            /* Poses within rounding of a contact could go either way: skip them. */
            if (gap > 0 && gap < 1e-9) continue;
            CHECK_EQ(colliding[i], gap == 0);
            CHECK_NEAR(distance[i], gap, 1e-12);
            if (fabs(gap - 0.1) > 1e-9) CHECK_EQ(closer[i], gap <= 0.1);
            some_hit |= colliding[i];
            some_miss |= !colliding[i];
        }
    }
    CHECK(some_hit && some_miss);
    poses_free(&p);
}

/* Random poses of the unit box (turned) against the fence (moved): each batch answers what single calls answer. */
static void check_against_single_calls(const pqp_model *box, const pqp_model *fence)
{
    struct poses p;
    int colliding[N_RANDOM], closer[N_RANDOM], c_one[N_RANDOM], t_one[N_RANDOM];
    double distance[N_RANDOM], d_one[N_RANDOM], approx[N_RANDOM], a_one[N_RANDOM];
    const unsigned threads[5] = {0, 1, 2, 3, 1000};
    uint64_t rng = 2106;
    int some_hit = 0, some_miss = 0;
    pqp_collide_result *cr = pqp_collide_result_create();
    pqp_distance_result *dr;
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    size_t i;
    int t;
    if (!poses_alloc(&p, N_RANDOM) || !cr || !tr) {
        CHECK(0);
        poses_free(&p);
        return;
    }
    for (i = 0; i < p.n; i++) {
        int k;
        random_rotation(&rng, p.R1 + 9 * i);
        memcpy(p.R2 + 9 * i, I3, sizeof I3);
        for (k = 0; k < 3; k++) {
            p.T1[3 * i + k] = 3 * check_unit(&rng) - 1.5 + (k == 0 ? 5 : 0);
            p.T2[3 * i + k] = 0.5 * check_unit(&rng);
        }
    }
    /* Single calls: one collide and tolerance result reused, a fresh distance result each time. */
    for (i = 0; i < p.n; i++) {
        const double *R1 = p.R1 + 9 * i, *T1 = p.T1 + 3 * i, *R2 = p.R2 + 9 * i, *T2 = p.T2 + 3 * i;
        CHECK_EQ(pqp_collide(cr, R1, T1, box, R2, T2, fence, PQP_ALL_CONTACTS), PQP_OK);
        c_one[i] = pqp_collide_result_colliding(cr);
        CHECK_EQ(pqp_tolerance(tr, R1, T1, box, R2, T2, fence, 0.3, 2), PQP_OK);
        t_one[i] = pqp_tolerance_result_closer_than_tolerance(tr);
        dr = pqp_distance_result_create();
        CHECK_EQ(pqp_distance(dr, R1, T1, box, R2, T2, fence, 0.0, 0.0, 2), PQP_OK);
        d_one[i] = pqp_distance_result_distance(dr);
        pqp_distance_result_destroy(dr);
        dr = pqp_distance_result_create();
        CHECK_EQ(pqp_distance(dr, R1, T1, box, R2, T2, fence, 0.3, 0.2, 2), PQP_OK);
        a_one[i] = pqp_distance_result_distance(dr);
        pqp_distance_result_destroy(dr);
    }
    for (t = 0; t < 5; t++) {
        CHECK_EQ(pqp_collide_batch(colliding, p.n, p.R1, p.T1, box, p.R2, p.T2, fence,
                                   PQP_FIRST_CONTACT, threads[t]),
                 PQP_OK);
        CHECK_EQ(pqp_distance_batch(distance, p.n, p.R1, p.T1, box, p.R2, p.T2, fence, 0.0, 0.0,
                                    threads[t]),
                 PQP_OK);
        CHECK_EQ(pqp_distance_batch(approx, p.n, p.R1, p.T1, box, p.R2, p.T2, fence, 0.3, 0.2,
                                    threads[t]),
                 PQP_OK);
        CHECK_EQ(pqp_tolerance_batch(closer, p.n, p.R1, p.T1, box, p.R2, p.T2, fence, 0.3,
                                     threads[t]),
                 PQP_OK);
        for (i = 0; i < p.n; i++) {
            CHECK_EQ(colliding[i], c_one[i]);
            CHECK(distance[i] == d_one[i]);
            CHECK(approx[i] == a_one[i]);
            CHECK_EQ(closer[i], t_one[i]);
            some_hit |= colliding[i];
            some_miss |= !colliding[i];
        }
    }
    CHECK(some_hit && some_miss);
    pqp_collide_result_destroy(cr);
    pqp_tolerance_result_destroy(tr);
    poses_free(&p);
}

/* Every bad argument: its code, and the answers left as they were. */
static void check_errors(const pqp_model *box, const pqp_model *fence)
{
    enum { N = 5 };
    double R[9 * N], T[3 * N], bad_R[9 * N], bad_T[3 * N], d[N];
    int out[N], i, k, rc;
    pqp_model *unbuilt = pqp_model_create();
    CHECK(unbuilt != NULL);
    for (i = 0; i < N; i++) {
        memcpy(R + 9 * i, I3, sizeof I3);
        T[3 * i] = 0.1 * i;
        T[3 * i + 1] = T[3 * i + 2] = 0;
    }
    for (i = 0; i < N; i++) {
        out[i] = 7;
        d[i] = 7;
    }
    /* NULL pointers. */
    CHECK_EQ(pqp_collide_batch(NULL, N, R, T, box, R, T, fence, PQP_ALL_CONTACTS, 0),
             PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_collide_batch(out, N, NULL, T, box, R, T, fence, PQP_ALL_CONTACTS, 0),
             PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_distance_batch(d, N, R, NULL, box, R, T, fence, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_distance_batch(d, N, R, T, NULL, R, T, fence, 0, 0, 2), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, box, NULL, T, fence, 0.1, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, box, R, NULL, fence, 0.1, 1), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, box, R, T, NULL, 0.1, 1), PQP_ERR_NULL_POINTER);
    /* Bad scalars. */
    CHECK_EQ(pqp_collide_batch(out, N, R, T, box, R, T, fence, 0, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_collide_batch(out, N, R, T, box, R, T, fence, 3, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_distance_batch(d, N, R, T, box, R, T, fence, -1, 0, 2), PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_distance_batch(d, N, R, T, box, R, T, fence, 0, NAN, 2),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, box, R, T, fence, -0.1, 2),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, box, R, T, fence, NAN, 2),
             PQP_ERR_INVALID_ARGUMENT);
    /* Unbuilt models. */
    CHECK_EQ(pqp_collide_batch(out, N, R, T, unbuilt, R, T, fence, PQP_ALL_CONTACTS, 2),
             PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_distance_batch(d, N, R, T, box, R, T, unbuilt, 0, 0, 2),
             PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(pqp_tolerance_batch(out, N, R, T, unbuilt, R, T, box, 0.1, 2),
             PQP_ERR_UNPROCESSED_MODEL);
    /* A non-finite entry in the last pose of each array, in turn. */
    for (k = 0; k < 4; k++) {
        const double *r1 = R, *t1 = T, *r2 = R, *t2 = T;
        memcpy(bad_R, R, sizeof R);
        memcpy(bad_T, T, sizeof T);
        bad_R[9 * (N - 1) + 4] = NAN;
        bad_T[3 * (N - 1) + 2] = INFINITY;
        if (k == 0) r1 = bad_R;
        if (k == 1) t1 = bad_T;
        if (k == 2) r2 = bad_R;
        if (k == 3) t2 = bad_T;
        CHECK_EQ(pqp_collide_batch(out, N, r1, t1, box, r2, t2, fence, PQP_ALL_CONTACTS, 2),
                 PQP_ERR_NONFINITE_POSE);
        CHECK_EQ(pqp_distance_batch(d, N, r1, t1, box, r2, t2, fence, 0, 0, 0),
                 PQP_ERR_NONFINITE_POSE);
        CHECK_EQ(pqp_tolerance_batch(out, N, r1, t1, box, r2, t2, fence, 0.1, 1),
                 PQP_ERR_NONFINITE_POSE);
    }
    /* A count no array can hold. */
    CHECK_EQ(pqp_collide_batch(out, (size_t)-1, R, T, box, R, T, fence, PQP_ALL_CONTACTS, 2),
             PQP_ERR_INVALID_ARGUMENT);
    CHECK_EQ(pqp_distance_batch(d, (size_t)-1 / 9 + 1, R, T, box, R, T, fence, 0, 0, 2),
             PQP_ERR_INVALID_ARGUMENT);
    for (i = 0; i < N; i++) {
        CHECK_EQ(out[i], 7);
        CHECK(d[i] == 7);
    }
    /* n = 0: PQP_OK, nothing read. */
    CHECK_EQ(pqp_collide_batch(NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL, PQP_ALL_CONTACTS, 0),
             PQP_OK);
    CHECK_EQ(pqp_distance_batch(NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL, 0, 0, 0), PQP_OK);
    CHECK_EQ(pqp_tolerance_batch(NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL, 0.1, 0), PQP_OK);
    /* Then a good call answers. */
    rc = pqp_distance_batch(d, N, R, T, box, R, T, fence, 0, 0, 1000);
    CHECK_EQ(rc, PQP_OK);
    for (i = 0; i < N; i++) CHECK(d[i] == 0);
    pqp_model_destroy(unbuilt);
}

int main(void)
{
    pqp_model *fence = shapes_fence(FENCE);
    pqp_model *rail = shapes_rail(RAIL, 99);
    pqp_model *box = shapes_unit_box();
    CHECK(fence && rail && box);
    if (fence && rail && box) {
        check_slide(fence, rail);
        check_against_single_calls(box, fence);
        check_errors(box, fence);
    }
    pqp_model_destroy(fence);
    pqp_model_destroy(rail);
    pqp_model_destroy(box);
    CHECK_DONE("batch");
}
