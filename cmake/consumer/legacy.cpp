// PQP 1.3 code using an installed pqp-rs through PQP.h: two triangles 2 apart.
#include "PQP.h"

#include <math.h>
#include <stdio.h>

int main()
{
    PQP_Model m1, m2;
    PQP_REAL a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    m1.BeginModel();
    m1.AddTri(a, b, c, 0);
    m1.EndModel();
    m2.BeginModel();
    m2.AddTri(a, b, c, 1);
    m2.EndModel();
    PQP_REAL R[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, T1[3] = {0, 0, 0}, T2[3] = {0, 0, 2};
    PQP_DistanceResult dres;
    PQP_ToleranceResult tres;
    PQP_CollideResult cres;
    bool ok = PQP_Distance(&dres, R, T1, &m1, R, T2, &m2, 0.0, 0.0) == PQP_OK &&
              fabs(dres.Distance() - 2.0) < 1e-12 &&
              PQP_Tolerance(&tres, R, T1, &m1, R, T2, &m2, 2.5) == PQP_OK &&
              tres.CloserThanTolerance() == 1 &&
              PQP_Collide(&cres, R, T1, &m1, R, T2, &m2) == PQP_OK && cres.Colliding() == 0 &&
              m1.num_tris == 1;
    printf("consumer (PQP.h): %s\n", ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
