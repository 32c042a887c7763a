/* Built models are shared by threads querying them at once (const pqp_model *), each with its own
 * result objects: every thread gets the answers a single thread gets. */
#include <pqp/pqp.h>

#include <math.h>
#include <pthread.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

#define NUM_POSES 60
#define NUM_THREADS 4

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};

struct answers {
    int pairs[NUM_POSES];
    double distance[NUM_POSES];
    int closer[NUM_POSES];
    int failed;
};

struct job {
    const pqp_model *a, *b;
    struct answers out;
};

/* Model b's pose number k: a rotation about z by 0.1 k and a translation sweeping through a. */
static void pose(int k, double R[9], double T[3])
{
    double c = cos(0.1 * k), s = sin(0.1 * k);
    memcpy(R, I3, 9 * sizeof R[0]);
    R[0] = c;
    R[1] = -s;
    R[3] = s;
    R[4] = c;
    T[0] = -1.0 + 0.06 * k;
    T[1] = 0.2;
    T[2] = 0.3 * sin(0.5 * k);
}

static void *run(void *arg)
{
    struct job *job = (struct job *)arg;
    pqp_collide_result *c = pqp_collide_result_create();
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_tolerance_result *t = pqp_tolerance_result_create();
    int k;
    job->out.failed = !(c && d && t);
    for (k = 0; k < NUM_POSES && !job->out.failed; k++) {
        double R[9], T[3];
        pose(k, R, T);
        job->out.failed |= pqp_collide(c, I3, ZERO3, job->a, R, T, job->b, PQP_ALL_CONTACTS);
        job->out.failed |= pqp_distance(d, I3, ZERO3, job->a, R, T, job->b, 0.0, 0.0, 2);
        job->out.failed |= pqp_tolerance(t, I3, ZERO3, job->a, R, T, job->b, 0.1, 2);
        job->out.pairs[k] = pqp_collide_result_num_pairs(c);
        job->out.distance[k] = pqp_distance_result_distance(d);
        job->out.closer[k] = pqp_tolerance_result_closer_than_tolerance(t);
    }
    pqp_tolerance_result_destroy(t);
    pqp_distance_result_destroy(d);
    pqp_collide_result_destroy(c);
    return NULL;
}

int main(void)
{
    pqp_model *a = shapes_unit_box();
    pqp_model *b = shapes_fence(12);
    struct job serial, jobs[NUM_THREADS];
    pthread_t threads[NUM_THREADS];
    int i, k, some_pairs = 0, some_apart = 0;
    CHECK(a != NULL && b != NULL);
    if (!a || !b) CHECK_DONE("threads");

    serial.a = a;
    serial.b = b;
    run(&serial);
    CHECK_EQ(serial.out.failed, 0);
    for (k = 0; k < NUM_POSES; k++) {
        some_pairs |= serial.out.pairs[k] > 0;
        some_apart |= serial.out.distance[k] > 0;
    }
    CHECK(some_pairs && some_apart); /* the sweep exercises both answers */

    for (i = 0; i < NUM_THREADS; i++) {
        jobs[i].a = a;
        jobs[i].b = b;
        CHECK_EQ(pthread_create(&threads[i], NULL, run, &jobs[i]), 0);
    }
    for (i = 0; i < NUM_THREADS; i++) CHECK_EQ(pthread_join(threads[i], NULL), 0);
    for (i = 0; i < NUM_THREADS; i++) {
        CHECK_EQ(jobs[i].out.failed, 0);
        for (k = 0; k < NUM_POSES; k++) {
            CHECK_EQ(jobs[i].out.pairs[k], serial.out.pairs[k]);
            CHECK(jobs[i].out.distance[k] == serial.out.distance[k]);
            CHECK_EQ(jobs[i].out.closer[k], serial.out.closer[k]);
        }
    }
    pqp_model_destroy(a);
    pqp_model_destroy(b);
    CHECK_DONE("threads");
}
