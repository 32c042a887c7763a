/* Time of first contact from C: pqp_time_of_contact on unit boxes moving by translation and by a
 * half turn, checked with pqp_distance at the interpolated poses (toc within the tolerance, every
 * sampled earlier time above 0.999 of it; no contact: every sample above it), a flight through a
 * fence of thin triangles at high speed, and every bad input (an error code, nothing written). */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "shapes.h"

static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
static const double ZERO[3] = {0, 0, 0};

/* The distance between a and b, a at the identity and b at (R, T). */
static double gap(pqp_distance_result *r, const pqp_model *a, const double R[9],
                  const double T[3], const pqp_model *b)
{
    if (pqp_distance(r, I3, ZERO, a, R, T, b, 0.0, 0.0, 2) != PQP_OK) return -1.0;
    return pqp_distance_result_distance(r);
}

/* b translating from Ta to Tb (rotation R throughout) past a, which stands still: checks the
 * answer with 400 samples; returns it. */
static pqp_contact_time check_flight(const pqp_model *a, const pqp_model *b, const double R[9],
                                     const double Ta[3], const double Tb[3], double tol)
{
    pqp_distance_result *r = pqp_distance_result_create();
    pqp_contact_time c;
    double T[3];
    int k, j;
    memset(&c, 0, sizeof c);
    CHECK_EQ(pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, R, Ta, R, Tb, b, tol), PQP_OK);
    if (c.contact) {
        CHECK(c.toc >= 0 && c.toc <= 1);
        for (j = 0; j < 3; j++) T[j] = Ta[j] + c.toc * (Tb[j] - Ta[j]);
        CHECK(gap(r, a, R, T, b) <= tol);
        for (k = 0; k < 400 && c.toc > 0; k++) {
            double t = c.toc * k / 400.0;
            for (j = 0; j < 3; j++) T[j] = Ta[j] + t * (Tb[j] - Ta[j]);
            CHECK(gap(r, a, R, T, b) > 0.999 * tol);
        }
        {
            double d2 = 0;
            for (j = 0; j < 3; j++) d2 += (c.point1[j] - c.point2[j]) * (c.point1[j] - c.point2[j]);
            CHECK(sqrt(d2) <= tol * (1 + 1e-9));
        }
        CHECK(c.id1 >= 0 && c.id2 >= 0);
    } else {
        CHECK(isinf(c.toc) && c.id1 == -1 && c.id2 == -1 && isnan(c.point1[0]) &&
              isnan(c.point2[2]));
        for (k = 0; k <= 400; k++) {
            double t = k / 400.0;
            for (j = 0; j < 3; j++) T[j] = Ta[j] + t * (Tb[j] - Ta[j]);
            CHECK(gap(r, a, R, T, b) > tol);
        }
    }
    pqp_distance_result_destroy(r);
    return c;
}

int main(void)
{
    pqp_model *a = shapes_unit_box(), *b = shapes_unit_box(), *fence = shapes_fence(8);
    pqp_model *unbuilt = pqp_model_create();
    static const double half_turn[9] = {-1, 0, 0, 0, -1, 0, 0, 0, 1};
    /* Six digits, as the shared .path files write rotations (about 8 degrees about z). */
    static const double six[9] = {0.990268, 0.139173, 0, -0.139173, 0.990268, 0, 0, 0, 1};
    pqp_contact_time c, sentinel;
    double Ta[3] = {5, 0, 0}, Tb[3] = {-5, 0, 0}, over[3] = {-5, 3, 0};
    double bad[9];
    const double nan = NAN;
    int k;
    CHECK(a != NULL && b != NULL && fence != NULL && unbuilt != NULL);
    if (a == NULL || b == NULL || fence == NULL || unbuilt == NULL) CHECK_DONE("contact_time");

    /* Head on: b's face x = 0 reaches a's face x = 1 within tol when b is at x = 1 + tol. */
    c = check_flight(a, b, I3, Ta, Tb, 0.01);
    CHECK(c.contact);
    CHECK(c.toc >= (5 - 1.01) / 10 - 1e-12 && c.toc <= (5 - 1.00999) / 10 + 1e-12);
    CHECK_NEAR(c.point1[0], 1.0, 1e-12);
    CHECK(c.point2[0] > 1.0 && c.point2[0] <= 1.01 + 1e-12);
    /* Over the top: no contact. */
    c = check_flight(a, b, I3, Ta, over, 0.01);
    CHECK(!c.contact);
    /* Already within tolerance: toc 0. */
    c = check_flight(a, b, I3, ZERO, Tb, 0.01);
    CHECK(c.contact && c.toc == 0);

    /* A half turn of b about z (its corner at the origin turns round it), next to a. */
    {
        double Tnext[3] = {1.5, 0, 0};
        CHECK_EQ(pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Tnext, half_turn, Tnext, b,
                                     0.01),
                 PQP_OK);
        /* Turning the documented way (about +z), b's side y = 0 sweeps towards -x and meets a's
         * face x = 1 within tolerance before a quarter turn. */
        CHECK(c.contact && c.toc > 0 && c.toc < 0.5);
        /* Six-digit rotations are accepted. */
        CHECK_EQ(pqp_time_of_contact(&c, I3, ZERO, six, ZERO, a, six, Ta, I3, Tb, b, 0.01), PQP_OK);
        CHECK(c.contact);
    }

    /* Issue 38: a half turn from Ra = [0 0 1; 1 0 0; 0 1 0] to Rb = [0 0 1; -1 0 0; 0 -1 0]
     * (Ra^T Rb = diag(-1, -1, 1)) turns +pi about Ra's body z, the world x axis: b's corner
     * (1, 0, 0) goes from world (0, 1, 0) through (0, 0, 1) at t = 1/2 to (0, -1, 0), b sweeping
     * the half y < 0 of the (y, z) plane by z > 0 only. So a box at y in [-1.7, -0.7], z in
     * [0.1, 1.1] is touched before t = 1/2; one at y in [0.7, 1.7], z in [-1.1, -0.1] never
     * (turning the other way round, only that one would be). */
    {
        const double Ra[9] = {0, 0, 1, 1, 0, 0, 0, 1, 0}, Rb[9] = {0, 0, 1, -1, 0, 0, 0, -1, 0};
        const double up[3] = {0, -1.7, 0.1}, down[3] = {0, 0.7, -1.1};
        CHECK_EQ(pqp_time_of_contact(&c, I3, up, I3, up, a, Ra, ZERO, Rb, ZERO, b, 0.01), PQP_OK);
        CHECK(c.contact && c.toc > 0.2 && c.toc < 0.5);
        CHECK_EQ(pqp_time_of_contact(&c, I3, down, I3, down, a, Ra, ZERO, Rb, ZERO, b, 0.01),
                 PQP_OK);
        CHECK(!c.contact);
    }

    /* A thin triangle fence (8 triangles at x = 0..7) crossed at high speed: the first one hit. */
    {
        double from[3] = {-1000, 0.1, 0.1}, to[3] = {1000, 0.1, 0.1};
        /* b is [0,1]^3 at from + t (to - from): its face x = 1 meets the fence's plane x = 0. */
        c = check_flight(fence, b, I3, from, to, 1e-3);
        CHECK(c.contact && c.id1 == 0);
        CHECK_NEAR(c.toc, (1000 - 1 - 1e-3) / 2000.0, 1e-9);
    }

    /* Bad input: an error code and nothing written. */
    memset(&sentinel, 0x5a, sizeof sentinel);
    c = sentinel;
#define BAD(expected, call)                                      \
    do {                                                         \
        CHECK_EQ(call, expected);                                \
        CHECK(memcmp(&c, &sentinel, sizeof c) == 0);             \
    } while (0)
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(NULL, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, NULL, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, NULL, I3, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, NULL, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, NULL, a, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, NULL, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, NULL, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, NULL, I3, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, NULL, Tb, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, NULL, b, 0.1));
    BAD(PQP_ERR_NULL_POINTER, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, NULL, 0.1));
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, 0.0));
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, -1.0));
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, nan));
    BAD(PQP_ERR_UNPROCESSED_MODEL, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, unbuilt, I3, Ta, I3, Tb, b, 0.1));
    BAD(PQP_ERR_UNPROCESSED_MODEL, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, unbuilt, 0.1));
    for (k = 0; k < 9; k++) {
        memcpy(bad, I3, sizeof bad);
        bad[k] = k % 2 ? nan : INFINITY;
        BAD(PQP_ERR_NONFINITE_POSE, pqp_time_of_contact(&c, I3, ZERO, bad, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
        BAD(PQP_ERR_NONFINITE_POSE, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, bad, Ta, I3, Tb, b, 0.1));
    }
    {
        double bad_t[3] = {0, 1e200, 0};
        BAD(PQP_ERR_NONFINITE_POSE, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, I3, bad_t, b, 0.1));
    }
    /* Not rotations: scaled, sheared, a reflection. */
    memcpy(bad, I3, sizeof bad);
    bad[0] = 1.01;
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, bad, ZERO, I3, ZERO, a, I3, Ta, I3, Tb, b, 0.1));
    bad[0] = 1, bad[1] = 1e-4;
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, I3, Ta, bad, Tb, b, 0.1));
    bad[1] = 0, bad[8] = -1;
    BAD(PQP_ERR_INVALID_ARGUMENT, pqp_time_of_contact(&c, I3, ZERO, I3, ZERO, a, bad, Ta, I3, Tb, b, 0.1));
#undef BAD

    pqp_model_destroy(a);
    pqp_model_destroy(b);
    pqp_model_destroy(fence);
    pqp_model_destroy(unbuilt);
    CHECK_DONE("contact_time");
}
