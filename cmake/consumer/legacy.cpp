// PQP 1.3 code using an installed pqp-rs through PQP.h, MatVec.h and TriDist.h: two triangles 2
// apart.
#include "MatVec.h"
#include "PQP.h"
#include "TriDist.h"

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
    // The same two triangles through TriDist, the second placed with MatVec.h's helpers.
    PQP_REAL s[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, t[3][3], p[3], q[3];
    for (int i = 0; i < 3; i++) MxVpV(t[i], R, s[i], T2);
    ok = ok && fabs(TriDist(p, q, s, t) - 2.0) < 1e-12 && fabs(VdistV2(p, q) - 4.0) < 1e-12;
    printf("consumer (PQP.h): %s\n", ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
