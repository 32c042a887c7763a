/* primitives.c -- swept-sphere primitives of pqp-rs from C: a sphere, a capsule and a box as
 * models (no triangles), swept across a mesh and against each other, with collision, distance
 * (closest points and the triangle id), tolerance and the pairs within a distance.
 *
 * Usage: primitives
 * The mesh is a 2 x 2 floor of two triangles (ids 0 and 1) in the plane z = 0. */
#include <pqp/pqp.h>

#include <stdio.h>

int main(void)
{
    static const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, O[3] = {0, 0, 0};
    /* The capsule lies along world x: its z axis turned onto x. */
    static const double lying[9] = {0, 0, 1, 0, 1, 0, -1, 0, 0};
    const char *names[3] = {"sphere r 0.1", "capsule r 0.05 length 0.4", "box 0.3 x 0.2 x 0.1"};
    pqp_model *mesh = pqp_model_create(), *prim[3];
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_collide_result *c = pqp_collide_result_create();
    pqp_tolerance_result *t = pqp_tolerance_result_create();
    int i, k, rc;
    {
        const double a[3] = {-1, -1, 0}, b[3] = {1, -1, 0}, e[3] = {1, 1, 0}, f[3] = {-1, 1, 0};
        pqp_model_add_tri(mesh, a, b, e, 0);
        pqp_model_add_tri(mesh, a, e, f, 1);
    }
    if ((rc = pqp_model_end(mesh)) != PQP_OK) {
        fprintf(stderr, "%s\n", pqp_error_string(rc));
        return 1;
    }
    for (i = 0; i < 3; i++) prim[i] = pqp_model_create();
    pqp_model_set_sphere(prim[0], 0.1);
    pqp_model_set_capsule(prim[1], 0.05, 0.4);
    pqp_model_set_box(prim[2], 0.3, 0.2, 0.1);

    /* Each primitive lowered onto the mesh from z = 0.5 to z = -0.1. */
    for (i = 0; i < 3; i++) {
        printf("%s:\n", names[i]);
        for (k = 0; k <= 6; k++) {
            const double T[3] = {0.01, 0.02, (5 - k) * 0.1};
            const double *R = i == 1 ? lying : I;
            const double *p1, *p2;
            int t1, t2;
            if ((rc = pqp_distance(d, R, T, prim[i], I, O, mesh, 0.0, 0.0, 2)) != PQP_OK ||
                (rc = pqp_collide(c, R, T, prim[i], I, O, mesh, PQP_ALL_CONTACTS)) != PQP_OK ||
                (rc = pqp_tolerance(t, R, T, prim[i], I, O, mesh, 0.05, 2)) != PQP_OK) {
                fprintf(stderr, "%s\n", pqp_error_string(rc));
                return 1;
            }
            p1 = pqp_distance_result_p1(d);
            p2 = pqp_distance_result_p2(d);
            pqp_distance_result_triangles(d, &t1, &t2);
            printf("  z %5.2f: distance %.6g (primitive (%.3g, %.3g, %.3g), triangle %d at "
                   "(%.3g, %.3g, %.3g)); colliding pairs %d; within 0.05: %s\n",
                   T[2], pqp_distance_result_distance(d), p1[0], p1[1], p1[2],
                   pqp_distance_result_id2(d), p2[0], p2[1], p2[2],
                   pqp_collide_result_num_pairs(c),
                   pqp_tolerance_result_closer_than_tolerance(t) ? "yes" : "no");
        }
    }
    /* Primitives against each other: the box 0.2 above the sphere, and pairs within 0.1. */
    {
        const double up[3] = {0, 0, 0.2};
        pqp_distance(d, I, O, prim[0], I, up, prim[2], 0.0, 0.0, 2);
        pqp_within_distance(c, I, O, prim[0], I, up, prim[2], 0.1);
        printf("sphere and box 0.2 apart in z: distance %.6g, pairs within 0.1: %d (ids %d, %d)\n",
               pqp_distance_result_distance(d), pqp_collide_result_num_pairs(c),
               pqp_collide_result_id1(c, 0), pqp_collide_result_id2(c, 0));
    }
    /* A bad size is an error code, and the model stays the sphere it was. */
    rc = pqp_model_set_sphere(prim[0], -1.0);
    printf("radius -1: %s\n", pqp_error_string(rc));
    /* Point queries need triangles. */
    {
        pqp_point_result pr;
        rc = pqp_closest_point(&pr, I, O, prim[0], O, 1.0);
        printf("closest point on a sphere model: %s\n", pqp_error_string(rc));
    }
    for (i = 0; i < 3; i++) pqp_model_destroy(prim[i]);
    pqp_tolerance_result_destroy(t);
    pqp_collide_result_destroy(c);
    pqp_distance_result_destroy(d);
    pqp_model_destroy(mesh);
    return 0;
}
