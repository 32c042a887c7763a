/* closest_point.c -- point queries of pqp-rs from C: the closest point of a posed model to a few
 * points (with and without a distance limit) and their signed distances (negative inside).
 *
 * Usage: closest_point [model.tris]
 * Without a file the model is the unit cube [0,1]^3. A .tris file holds the triangle count n, then
 * n triangles as nine numbers x1 y1 z1 ... z3 (ids are their indices). */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>

/* Adds the triangles of a .tris file to m; returns the count added, or -1. */
static int add_file(pqp_model *m, const char *path)
{
    FILE *f = fopen(path, "r");
    int n = 0, i, k;
    if (!f || fscanf(f, "%d", &n) != 1 || n <= 0) {
        fprintf(stderr, "cannot read %s\n", path);
        if (f) fclose(f);
        return -1;
    }
    for (i = 0; i < n; i++) {
        double p[9];
        for (k = 0; k < 9; k++)
            if (fscanf(f, "%lf", &p[k]) != 1) break;
        if (k < 9 || pqp_model_add_tri(m, p, p + 3, p + 6, i) != PQP_OK) {
            fprintf(stderr, "%s: bad triangle %d\n", path, i);
            fclose(f);
            return -1;
        }
    }
    fclose(f);
    return n;
}

/* Adds the unit cube, two triangles per face, facing outwards. */
static void add_cube(pqp_model *m)
{
    static const int faces[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                     {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                     {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    int k, v, a;
    for (k = 0; k < 12; k++) {
        double t[3][3];
        for (v = 0; v < 3; v++)
            for (a = 0; a < 3; a++) t[v][a] = (faces[k][v] >> (2 - a)) & 1;
        pqp_model_add_tri(m, t[0], t[1], t[2], k);
    }
}

int main(int argc, char **argv)
{
    /* The model turned 90 degrees about z and moved up by 0.5: x_world = R x + T. */
    const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1}, T[3] = {0, 0, 0.5};
    const double points[4][3] = {{-0.5, 0.5, 1.0}, {-0.5, 0.5, 3.0}, {2.0, 2.0, 2.0}, {0, 0, 0}};
    pqp_model *m = pqp_model_create();
    int i, rc;
    if (!m) return 1;
    pqp_model_begin(m, 12);
    if (argc > 1) {
        if (add_file(m, argv[1]) < 0) {
            pqp_model_destroy(m);
            return 1;
        }
    } else {
        add_cube(m);
    }
    rc = pqp_model_end(m);
    if (rc != PQP_OK) {
        fprintf(stderr, "%s\n", pqp_error_string(rc));
        pqp_model_destroy(m);
        return 1;
    }
    for (i = 0; i < 4; i++) {
        const double *p = points[i];
        pqp_point_result r, near;
        double sd;
        if ((rc = pqp_closest_point(&r, R, T, m, p, INFINITY)) != PQP_OK ||
            (rc = pqp_closest_point(&near, R, T, m, p, 1.0)) != PQP_OK ||
            (rc = pqp_signed_distance(&sd, R, T, m, p)) != PQP_OK) {
            fprintf(stderr, "%s\n", pqp_error_string(rc));
            pqp_model_destroy(m);
            return 1;
        }
        printf("point (%g, %g, %g): closest (%.6g, %.6g, %.6g) on triangle %d at %.6g; "
               "signed distance %.6g (%s)",
               p[0], p[1], p[2], r.point[0], r.point[1], r.point[2], r.triangle, r.distance, sd,
               sd < 0 ? "inside" : "outside");
        if (near.triangle < 0)
            printf("; nothing within 1\n");
        else
            printf("; within 1\n");
    }
    /* A bad argument is an error code, and nothing is written. */
    rc = pqp_closest_point(&(pqp_point_result){0}, R, T, m, points[0], -1.0);
    printf("max_distance -1: %s\n", pqp_error_string(rc));
    pqp_model_destroy(m);
    return 0;
}
