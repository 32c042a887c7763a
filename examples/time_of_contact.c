/* time_of_contact.c -- continuous collision from C: a thin plate thrown through a wall in one
 * motion (100 units while turning a quarter turn) is caught at the time it reaches the wall, and a
 * throw that passes beside the wall reports no contact.
 *
 * Usage: time_of_contact
 * Each model moves from pose a (t = 0) to pose b (t = 1): translation linear, rotation at
 * constant angular velocity about a fixed axis (see pqp_time_of_contact in pqp.h). */
#include <pqp/pqp.h>

#include <stdio.h>

/* Builds the box [-hx, hx] x [-hy, hy] x [-hz, hz] (12 triangles) into a new model; NULL on error. */
static pqp_model *box(double hx, double hy, double hz)
{
    /* Corner i has coordinate k at +h[k] when bit k of i is set. */
    static const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                    {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    const double h[3] = {hx, hy, hz};
    double c[8][3];
    int i, k, rc;
    pqp_model *m = pqp_model_create();
    if (!m) return NULL;
    for (i = 0; i < 8; i++)
        for (k = 0; k < 3; k++) c[i][k] = (i >> k) & 1 ? h[k] : -h[k];
    rc = pqp_model_begin(m, 12);
    for (i = 0; i < 6 && rc == PQP_OK; i++) {
        const int *q = quads[i];
        rc = pqp_model_add_tri(m, c[q[0]], c[q[1]], c[q[2]], 2 * i);
        if (rc == PQP_OK) rc = pqp_model_add_tri(m, c[q[0]], c[q[2]], c[q[3]], 2 * i + 1);
    }
    if (rc == PQP_OK) rc = pqp_model_end(m);
    if (rc != PQP_OK) {
        pqp_model_destroy(m);
        return NULL;
    }
    return m;
}

/* Throws `plate` from x = -50 to x = +50 at height z, turning a quarter turn about x, against
 * `wall` standing still; prints the answer. Returns the error code. */
static int throw_at(const pqp_model *wall, const pqp_model *plate, double z)
{
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double quarter[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0}; /* a quarter turn about x */
    const double origin[3] = {0, 0, 0};
    const double from[3] = {-50, 0, z}, to[3] = {50, 0, z};
    pqp_contact_time c;
    int rc = pqp_time_of_contact(&c, I, origin, I, origin, wall, I, from, quarter, to, plate, 1e-4);
    if (rc != PQP_OK) {
        fprintf(stderr, "pqp_time_of_contact: error %d\n", rc);
        return rc;
    }
    if (c.contact)
        printf("thrown at height %g: contact at t = %.9f, triangles %d and %d, points (%.4f %.4f %.4f) and "
               "(%.4f %.4f %.4f)\n",
               z, c.toc, c.id1, c.id2, c.point1[0], c.point1[1], c.point1[2], c.point2[0], c.point2[1],
               c.point2[2]);
    else
        printf("thrown at height %g: no contact (toc %f)\n", z, c.toc);
    return PQP_OK;
}

int main(void)
{
    /* A wall 1e-3 thick in the plane x = 0, 2 x 2; a plate 1e-3 thick, 1 x 1. */
    pqp_model *wall = box(0.0005, 1, 1), *plate = box(0.0005, 0.5, 0.5);
    int rc = wall && plate ? PQP_OK : PQP_ERR_INTERNAL;
    if (rc == PQP_OK) rc = throw_at(wall, plate, 0.0); /* through the wall */
    if (rc == PQP_OK) rc = throw_at(wall, plate, 3.0); /* above it */
    pqp_model_destroy(wall);
    pqp_model_destroy(plate);
    return rc == PQP_OK ? 0 : 1;
}
