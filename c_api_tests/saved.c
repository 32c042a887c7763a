/* Saved models from C: pqp_model_serialize and pqp_model_deserialize. A model saved to a file and
 * loaded into another answers every query as the original, with the same counts of bound and
 * triangle tests, for every volume choice; the size query, codes and "nothing written" on every
 * error; every truncation and every flipped byte refused, the target model unchanged; loops of
 * save and load (leaks and double frees under AddressSanitizer). */
#include <pqp/pqp.h>

#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO3[3] = {0, 0, 0};

/* A model of random triangles near the unit cube with the given volume choices. */
static pqp_model *random_model(uint64_t *rng, int n, int volume, int collision)
{
    pqp_model *m = pqp_model_create();
    int k, j;
    CHECK(m != NULL);
    if (m == NULL) return NULL;
    CHECK_EQ(pqp_model_set_volume(m, volume), PQP_OK);
    CHECK_EQ(pqp_model_set_collision_volume(m, collision), PQP_OK);
    for (k = 0; k < n; k++) {
        double c[3], p[3][3];
        for (j = 0; j < 3; j++) c[j] = 2 * check_unit(rng) - 1;
        for (j = 0; j < 9; j++) p[j / 3][j % 3] = c[j % 3] + 0.4 * (check_unit(rng) - 0.5);
        CHECK_EQ(pqp_model_add_tri(m, p[0], p[1], p[2], 3 * k + 1), PQP_OK);
    }
    CHECK_EQ(pqp_model_end(m), PQP_OK);
    return m;
}

/* The saved bytes of m (malloc'd; *size their count), through the size query. */
static unsigned char *saved(const pqp_model *m, size_t *size)
{
    unsigned char *buf;
    size_t written = 0;
    *size = 0;
    CHECK_EQ(pqp_model_serialize(m, NULL, 0, size), PQP_ERR_BUFFER_TOO_SMALL);
    CHECK(*size > 0);
    buf = (unsigned char *)malloc(*size);
    CHECK(buf != NULL);
    if (buf == NULL) return NULL;
    CHECK_EQ(pqp_model_serialize(m, buf, *size, &written), PQP_OK);
    CHECK_EQ(written, *size);
    return buf;
}

/* A rotation about z by angle a, row by row. */
static void rot_z(double a, double R[9])
{
    memset(R, 0, 9 * sizeof(double));
    R[0] = cos(a);
    R[1] = -sin(a);
    R[3] = sin(a);
    R[4] = cos(a);
    R[8] = 1;
}

/* Every answer and count of a few queries between a and b at pose k, into out (at most 16). */
static int answers(const pqp_model *a, const pqp_model *b, int k, double out[16])
{
    pqp_collide_result *c = pqp_collide_result_create();
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_tolerance_result *t = pqp_tolerance_result_create();
    double R[9], T[3];
    int n = 0, t1 = -1, t2 = -1;
    rot_z(0.7 * k, R);
    T[0] = 0.3 * (k % 5) - 0.6;
    T[1] = 0.1 * k - 0.4;
    T[2] = 0.05 * (k % 3);
    CHECK_EQ(pqp_collide(c, I3, ZERO3, a, R, T, b, PQP_ALL_CONTACTS), PQP_OK);
    out[n++] = pqp_collide_result_num_pairs(c);
    out[n++] = (double)pqp_collide_result_num_bv_tests(c);
    out[n++] = (double)pqp_collide_result_num_tri_tests(c);
    CHECK_EQ(pqp_distance(d, I3, ZERO3, a, R, T, b, 0.0, 0.0, 2), PQP_OK);
    out[n++] = pqp_distance_result_distance(d);
    out[n++] = (double)pqp_distance_result_num_bv_tests(d);
    out[n++] = (double)pqp_distance_result_num_tri_tests(d);
    CHECK_EQ(pqp_distance_result_triangles(d, &t1, &t2), PQP_OK);
    out[n++] = t1;
    out[n++] = t2;
    CHECK_EQ(pqp_tolerance(t, I3, ZERO3, a, R, T, b, 0.05, 2), PQP_OK);
    out[n++] = pqp_tolerance_result_closer_than_tolerance(t);
    out[n++] = pqp_tolerance_result_distance(t);
    out[n++] = (double)pqp_tolerance_result_num_bv_tests(t);
    pqp_tolerance_result_destroy(t);
    pqp_distance_result_destroy(d);
    pqp_collide_result_destroy(c);
    return n;
}

/* The pair (a1, b1) answers exactly as (a0, b0) does, at several poses. */
static void same_answers(const pqp_model *a0, const pqp_model *b0, const pqp_model *a1,
                         const pqp_model *b1)
{
    int k, i;
    for (k = 0; k < 12; k++) {
        double want[16], got[16];
        int n = answers(a0, b0, k, want);
        CHECK_EQ(answers(a1, b1, k, got), n);
        for (i = 0; i < n; i++) CHECK(memcmp(&want[i], &got[i], sizeof(double)) == 0);
    }
}

/* Saved to a file and loaded into a fresh model: the same answers, for every volume choice. */
static void through_a_file(void)
{
    static const int volumes[4] = {PQP_BV_RSS, PQP_BV_PSS, PQP_BV_LSS, PQP_BV_HYBRID};
    uint64_t rng = 41;
    int v, c;
    for (v = 0; v < 4; v++) {
        for (c = 0; c < 2; c++) {
            int collision = c ? PQP_COLLIDE_SSV : PQP_COLLIDE_OBB;
            pqp_model *a = random_model(&rng, 60, volumes[v], collision);
            pqp_model *b = random_model(&rng, 80, volumes[v], collision);
            pqp_model *loaded = pqp_model_create();
            size_t size, got;
            unsigned char *buf = saved(b, &size), *back;
            FILE *f = tmpfile();
            CHECK(f != NULL && buf != NULL && loaded != NULL);
            if (f == NULL || buf == NULL || loaded == NULL) return;
            CHECK_EQ(fwrite(buf, 1, size, f), size);
            rewind(f);
            back = (unsigned char *)malloc(size);
            CHECK(back != NULL);
            if (back == NULL) return;
            got = fread(back, 1, size, f);
            CHECK_EQ(got, size);
            fclose(f);
            CHECK_EQ(pqp_model_deserialize(loaded, back, size), PQP_OK);
            CHECK_EQ(pqp_model_num_tris(loaded), 80);
            CHECK_EQ(pqp_model_build_state(loaded), PQP_BUILD_STATE_PROCESSED);
            same_answers(a, b, a, loaded);
            same_answers(b, a, loaded, a); /* also as the first model */
            /* Saving the loaded model gives the same bytes. */
            {
                size_t size2;
                unsigned char *again = saved(loaded, &size2);
                CHECK(size2 == size && again != NULL && memcmp(again, buf, size) == 0);
                free(again);
            }
            free(back);
            free(buf);
            pqp_model_destroy(loaded);
            pqp_model_destroy(b);
            pqp_model_destroy(a);
        }
    }
}

static void codes_and_nothing_written(void)
{
    pqp_model *m = shapes_fence(7), *fresh = pqp_model_create();
    size_t size = 0, needed, s;
    unsigned char *buf = saved(m, &needed), *pattern;
    CHECK(m != NULL && fresh != NULL && buf != NULL);
    if (m == NULL || fresh == NULL || buf == NULL) return;
    pattern = (unsigned char *)malloc(needed);
    CHECK(pattern != NULL);
    if (pattern == NULL) return;
    memset(pattern, 0x5a, needed);

    CHECK_EQ(pqp_model_serialize(NULL, pattern, needed, &size), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_serialize(m, pattern, needed, NULL), PQP_ERR_NULL_POINTER);
    size = 0;
    CHECK_EQ(pqp_model_serialize(m, pattern, needed - 1, &size), PQP_ERR_BUFFER_TOO_SMALL);
    CHECK_EQ(size, needed);
    size = 0;
    CHECK_EQ(pqp_model_serialize(m, NULL, (size_t)-1, &size), PQP_ERR_BUFFER_TOO_SMALL);
    CHECK_EQ(size, needed);
    size = 3;
    CHECK_EQ(pqp_model_serialize(fresh, pattern, needed, &size), PQP_ERR_UNPROCESSED_MODEL);
    CHECK_EQ(size, 3);
    for (s = 0; s < needed; s++) CHECK(pattern[s] == 0x5a);

    CHECK_EQ(pqp_model_deserialize(NULL, buf, needed), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_deserialize(fresh, NULL, needed), PQP_ERR_NULL_POINTER);
    CHECK_EQ(pqp_model_deserialize(fresh, pattern, needed), PQP_ERR_INVALID_DATA);
    CHECK_EQ(pqp_model_build_state(fresh), PQP_BUILD_STATE_EMPTY);

    CHECK(strcmp(pqp_error_string(PQP_ERR_BUFFER_TOO_SMALL), "unknown error code") != 0);
    CHECK(strcmp(pqp_error_string(PQP_ERR_INVALID_DATA), "unknown error code") != 0);
    CHECK_EQ(PQP_ERR_BUFFER_TOO_SMALL, -13);
    CHECK_EQ(PQP_ERR_INVALID_DATA, -14);
    free(pattern);
    free(buf);
    pqp_model_destroy(fresh);
    pqp_model_destroy(m);
}

/* Every truncation and every flipped byte of a small model's bytes is refused, and the model
 * loaded into stays as it was (the box, answering as the box). */
static void bad_bytes_change_nothing(void)
{
    pqp_model *fence = shapes_fence(5), *box = shapes_unit_box(), *target = shapes_unit_box();
    size_t size, len, at;
    unsigned char *buf = saved(fence, &size);
    CHECK(fence != NULL && box != NULL && target != NULL && buf != NULL);
    if (fence == NULL || box == NULL || target == NULL || buf == NULL) return;
    for (len = 0; len < size; len++)
        CHECK_EQ(pqp_model_deserialize(target, buf, len), PQP_ERR_INVALID_DATA);
    for (at = 0; at < size; at++) {
        buf[at] ^= 0x04;
        CHECK_EQ(pqp_model_deserialize(target, buf, size), PQP_ERR_INVALID_DATA);
        buf[at] ^= 0x04;
    }
    CHECK_EQ(pqp_model_num_tris(target), 12);
    same_answers(fence, box, fence, target);
    /* Then a good one replaces it. */
    CHECK_EQ(pqp_model_deserialize(target, buf, size), PQP_OK);
    CHECK_EQ(pqp_model_num_tris(target), 5);
    same_answers(box, fence, box, target);
    free(buf);
    pqp_model_destroy(target);
    pqp_model_destroy(box);
    pqp_model_destroy(fence);
}

/* Save and load in a loop, into the same model and into new ones. */
static void loops(void)
{
    pqp_model *fence = shapes_fence(9), *again = pqp_model_create();
    size_t size;
    unsigned char *buf = saved(fence, &size);
    int i;
    CHECK(buf != NULL && again != NULL);
    if (buf == NULL || again == NULL) return;
    for (i = 0; i < 300; i++) {
        pqp_model *m = pqp_model_create();
        CHECK_EQ(pqp_model_deserialize(m, buf, size), PQP_OK);
        CHECK_EQ(pqp_model_deserialize(again, buf, size), PQP_OK);
        pqp_model_destroy(m);
    }
    CHECK_EQ(pqp_model_num_tris(again), 9);
    free(buf);
    pqp_model_destroy(again);
    pqp_model_destroy(fence);
}

int main(void)
{
    through_a_file();
    codes_and_nothing_written();
    bad_bytes_change_nothing();
    loops();
    CHECK_DONE("saved");
}
