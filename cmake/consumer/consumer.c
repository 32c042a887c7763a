/* A C program using an installed pqp-rs: two triangles 2 apart. Exits 0 if the answers are right. */
#include <pqp/pqp.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

int main(void)
{
    const double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, T1[3] = {0, 0, 0}, T2[3] = {0, 0, 2};
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    pqp_model *m = pqp_model_create();
    pqp_distance_result *d = pqp_distance_result_create();
    pqp_collide_result *cr = pqp_collide_result_create();
    int ok;
    pqp_model_begin(m, 1);
    pqp_model_add_tri(m, a, b, c, 0);
    ok = pqp_model_end(m) == PQP_OK;
    ok = ok && pqp_distance(d, R, T1, m, R, T2, m, 0.0, 0.0, 2) == PQP_OK;
    ok = ok && fabs(pqp_distance_result_distance(d) - 2.0) < 1e-12;
    ok = ok && pqp_collide(cr, R, T1, m, R, T2, m, PQP_ALL_CONTACTS) == PQP_OK;
    ok = ok && pqp_collide_result_colliding(cr) == 0;
    ok = ok && pqp_model_end(NULL) == PQP_ERR_NULL_POINTER;
    ok = ok && strcmp(pqp_version(), "1.0.0") == 0;
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(d);
    pqp_model_destroy(m);
    printf("consumer (C, pqp %s): %s\n", pqp_version(), ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
