/*
 * MatVec.h -- the small 3x3 matrix and 3-vector helpers of PQP 1.3's MatVec.h, as provided by
 * pqp-rs (C++ only; header-only: nothing here needs the library).
 *
 * Matrices are PQP_REAL M[3][3], row by row (M[row][col]); vectors are PQP_REAL V[3]. PQP_REAL
 * comes from PQP_Compile.h (double unless edited there; float works too: every function computes
 * in double where it matters and converts back). The names and argument orders are PQP 1.3's:
 * the result comes first, and inputs are taken as const (non-const arrays convert).
 *
 * Differences from PQP 1.3 (all are fixes):
 * - Every function may be given its output as one of its inputs (MxM(R, R, S), MTcM(M, M), ...):
 *   results are formed in temporaries first. PQP 1.3 gave wrong answers for most such calls.
 * - Meigen leaves its input matrix unchanged (PQP 1.3 overwrote it), and its eigenvectors are
 *   orthonormal to rounding also for repeated eigenvalues.
 * - MRotQ of the zero quaternion is the identity (PQP 1.3 divided by zero).
 * - myfabs parenthesizes its argument (PQP 1.3's macro mis-expanded myfabs(a - b)).
 * PQP 1.3's internal ROTATE macro (a step of its Meigen) is not provided.
 */
#ifndef PQP_MATVEC_H
#define PQP_MATVEC_H

#ifndef __cplusplus
#error "MatVec.h is a C++ header"
#endif

#include "PQP_Compile.h"

#include <float.h>
#include <math.h>
#include <stdio.h>

/* Absolute value of any arithmetic expression (PQP 1.3's macro, with its argument parenthesized).
 * It evaluates x twice. */
#ifndef myfabs
#define myfabs(x) (((x) < 0) ? -(x) : (x))
#endif

/* pi, for systems whose <math.h> does not define it (glibc does). */
#ifndef M_PI
const PQP_REAL M_PI = (PQP_REAL)3.14159265358979323846;
#endif

/* Indices of a quaternion's components in PQP_REAL q[4]: x, y, z (the vector part), then w. */
const int QX = 0;
const int QY = 1;
const int QZ = 2;
const int QW = 3;

/* ---- Printing (to stdout or the given stream, one "%g %g %g" line per row). */

/* Prints the three rows of M to fp. */
inline void Mfprint(FILE *fp, const PQP_REAL M[3][3])
{
    for (int i = 0; i < 3; i++)
        fprintf(fp, "%g %g %g\n", (double)M[i][0], (double)M[i][1], (double)M[i][2]);
}

/* Prints the three rows of M to stdout. */
inline void Mprintg(const PQP_REAL M[3][3])
{
    Mfprint(stdout, M);
}

/* Prints the three rows of M to stdout (as Mprintg). */
inline void Mprint(const PQP_REAL M[3][3])
{
    Mfprint(stdout, M);
}

/* Prints V on one line to fp. */
inline void Vfprint(FILE *fp, const PQP_REAL V[3])
{
    fprintf(fp, "%g %g %g\n", (double)V[0], (double)V[1], (double)V[2]);
}

/* Prints V on one line to stdout. */
inline void Vprintg(const PQP_REAL V[3])
{
    Vfprint(stdout, V);
}

/* Prints V on one line to stdout (as Vprintg). */
inline void Vprint(const PQP_REAL V[3])
{
    Vfprint(stdout, V);
}

/* ---- Setting and copying. */

/* M = the identity. */
inline void Midentity(PQP_REAL M[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) M[i][j] = (PQP_REAL)(i == j ? 1 : 0);
}

/* V = the zero vector (PQP's name). */
inline void Videntity(PQP_REAL V[3])
{
    V[0] = V[1] = V[2] = (PQP_REAL)0;
}

/* Mr = M. */
inline void McM(PQP_REAL Mr[3][3], const PQP_REAL M[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Mr[i][j] = M[i][j];
}

/* Mr = M transposed. */
inline void MTcM(PQP_REAL Mr[3][3], const PQP_REAL M[3][3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) t[i][j] = M[j][i];
    McM(Mr, t);
}

/* Vr = V. */
inline void VcV(PQP_REAL Vr[3], const PQP_REAL V[3])
{
    Vr[0] = V[0];
    Vr[1] = V[1];
    Vr[2] = V[2];
}

/* Vr = column c (0, 1 or 2) of M. */
inline void McolcV(PQP_REAL Vr[3], const PQP_REAL M[3][3], int c)
{
    PQP_REAL t[3] = {M[0][c], M[1][c], M[2][c]};
    VcV(Vr, t);
}

/* Column cr of Mr = column c of M (the other columns of Mr are kept). */
inline void McolcMcol(PQP_REAL Mr[3][3], int cr, const PQP_REAL M[3][3], int c)
{
    PQP_REAL t[3] = {M[0][c], M[1][c], M[2][c]};
    for (int i = 0; i < 3; i++) Mr[i][cr] = t[i];
}

/* ---- Products. Matrix products sum their three terms in PQP_REAL. */

/* Mr = M1 M2. */
inline void MxM(PQP_REAL Mr[3][3], const PQP_REAL M1[3][3], const PQP_REAL M2[3][3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[i][j] = M1[i][0] * M2[0][j] + M1[i][1] * M2[1][j] + M1[i][2] * M2[2][j];
    McM(Mr, t);
}

/* Mr = M1 M2^T. */
inline void MxMT(PQP_REAL Mr[3][3], const PQP_REAL M1[3][3], const PQP_REAL M2[3][3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[i][j] = M1[i][0] * M2[j][0] + M1[i][1] * M2[j][1] + M1[i][2] * M2[j][2];
    McM(Mr, t);
}

/* Mr = M1^T M2. */
inline void MTxM(PQP_REAL Mr[3][3], const PQP_REAL M1[3][3], const PQP_REAL M2[3][3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[i][j] = M1[0][i] * M2[0][j] + M1[1][i] * M2[1][j] + M1[2][i] * M2[2][j];
    McM(Mr, t);
}

/* Mr = M1 M2 with T added to every column: Mr[i][j] = (M1 M2)[i][j] + T[i] (PQP's definition). */
inline void MxMpV(PQP_REAL Mr[3][3], const PQP_REAL M1[3][3], const PQP_REAL M2[3][3],
                  const PQP_REAL T[3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[i][j] = M1[i][0] * M2[0][j] + M1[i][1] * M2[1][j] + M1[i][2] * M2[2][j] + T[i];
    McM(Mr, t);
}

/* Vr = M V. */
inline void MxV(PQP_REAL Vr[3], const PQP_REAL M[3][3], const PQP_REAL V[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++) t[i] = M[i][0] * V[0] + M[i][1] * V[1] + M[i][2] * V[2];
    VcV(Vr, t);
}

/* Vr = M V1 + V2. */
inline void MxVpV(PQP_REAL Vr[3], const PQP_REAL M[3][3], const PQP_REAL V1[3],
                  const PQP_REAL V2[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++) t[i] = M[i][0] * V1[0] + M[i][1] * V1[1] + M[i][2] * V1[2] + V2[i];
    VcV(Vr, t);
}

/* Vr = s (M V1) + V2. */
inline void sMxVpV(PQP_REAL Vr[3], PQP_REAL s, const PQP_REAL M[3][3], const PQP_REAL V1[3],
                   const PQP_REAL V2[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++)
        t[i] = s * (M[i][0] * V1[0] + M[i][1] * V1[1] + M[i][2] * V1[2]) + V2[i];
    VcV(Vr, t);
}

/* Vr = M^T V. */
inline void MTxV(PQP_REAL Vr[3], const PQP_REAL M[3][3], const PQP_REAL V[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++) t[i] = M[0][i] * V[0] + M[1][i] * V[1] + M[2][i] * V[2];
    VcV(Vr, t);
}

/* Vr = s (M^T V). */
inline void sMTxV(PQP_REAL Vr[3], PQP_REAL s, const PQP_REAL M[3][3], const PQP_REAL V[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++) t[i] = s * (M[0][i] * V[0] + M[1][i] * V[1] + M[2][i] * V[2]);
    VcV(Vr, t);
}

/* Vr = s (M V). */
inline void sMxV(PQP_REAL Vr[3], PQP_REAL s, const PQP_REAL M[3][3], const PQP_REAL V[3])
{
    PQP_REAL t[3];
    for (int i = 0; i < 3; i++) t[i] = s * (M[i][0] * V[0] + M[i][1] * V[1] + M[i][2] * V[2]);
    VcV(Vr, t);
}

/* ---- Vectors. */

/* Vr = V1 - V2. */
inline void VmV(PQP_REAL Vr[3], const PQP_REAL V1[3], const PQP_REAL V2[3])
{
    PQP_REAL t[3] = {V1[0] - V2[0], V1[1] - V2[1], V1[2] - V2[2]};
    VcV(Vr, t);
}

/* Vr = V1 + V2. */
inline void VpV(PQP_REAL Vr[3], const PQP_REAL V1[3], const PQP_REAL V2[3])
{
    PQP_REAL t[3] = {V1[0] + V2[0], V1[1] + V2[1], V1[2] + V2[2]};
    VcV(Vr, t);
}

/* Vr = V1 + V2 s. */
inline void VpVxS(PQP_REAL Vr[3], const PQP_REAL V1[3], const PQP_REAL V2[3], PQP_REAL s)
{
    PQP_REAL t[3] = {V1[0] + V2[0] * s, V1[1] + V2[1] * s, V1[2] + V2[2] * s};
    VcV(Vr, t);
}

/* Vr = V s. */
inline void VxS(PQP_REAL Vr[3], const PQP_REAL V[3], PQP_REAL s)
{
    PQP_REAL t[3] = {V[0] * s, V[1] * s, V[2] * s};
    VcV(Vr, t);
}

/* Vr = V1 x V2 (cross product). */
inline void VcrossV(PQP_REAL Vr[3], const PQP_REAL V1[3], const PQP_REAL V2[3])
{
    PQP_REAL t[3] = {V1[1] * V2[2] - V1[2] * V2[1], V1[2] * V2[0] - V1[0] * V2[2],
                     V1[0] * V2[1] - V1[1] * V2[0]};
    VcV(Vr, t);
}

/* V1 . V2 (dot product). */
inline PQP_REAL VdotV(const PQP_REAL V1[3], const PQP_REAL V2[3])
{
    return V1[0] * V2[0] + V1[1] * V2[1] + V1[2] * V2[2];
}

/* |V1 - V2|^2 (squared distance). */
inline PQP_REAL VdistV2(const PQP_REAL V1[3], const PQP_REAL V2[3])
{
    PQP_REAL d[3] = {V1[0] - V2[0], V1[1] - V2[1], V1[2] - V2[2]};
    return VdotV(d, d);
}

/* |V| (computed in double from the squared length, which overflows beyond about 1e154). */
inline PQP_REAL Vlength(const PQP_REAL V[3])
{
    double x = (double)V[0], y = (double)V[1], z = (double)V[2];
    return (PQP_REAL)sqrt(x * x + y * y + z * z);
}

/* Scales V to unit length in place; the zero vector stays zero. */
inline void Vnormalize(PQP_REAL V[3])
{
    double x = (double)V[0], y = (double)V[1], z = (double)V[2];
    double d = sqrt(x * x + y * y + z * z);
    if (d > 0) {
        V[0] = (PQP_REAL)(x / d);
        V[1] = (PQP_REAL)(y / d);
        V[2] = (PQP_REAL)(z / d);
    }
}

/* M = the skew-symmetric matrix of v: M x = v x x for every x. */
inline void MskewV(PQP_REAL M[3][3], const PQP_REAL v[3])
{
    PQP_REAL x = v[0], y = v[1], z = v[2];
    M[0][0] = 0;
    M[0][1] = -z;
    M[0][2] = y;
    M[1][0] = z;
    M[1][1] = 0;
    M[1][2] = -x;
    M[2][0] = -y;
    M[2][1] = x;
    M[2][2] = 0;
}

/* ---- Rotations. */

/* Mr = the right-handed rotation by t radians about the z axis: [[c, -s, 0], [s, c, 0], [0, 0, 1]]
 * with c = cos t, s = sin t. */
inline void MRotZ(PQP_REAL Mr[3][3], PQP_REAL t)
{
    PQP_REAL c = (PQP_REAL)cos((double)t), s = (PQP_REAL)sin((double)t);
    Midentity(Mr);
    Mr[0][0] = c;
    Mr[0][1] = -s;
    Mr[1][0] = s;
    Mr[1][1] = c;
}

/* Mr = the right-handed rotation by t radians about the x axis:
 * [[1, 0, 0], [0, c, -s], [0, s, c]]. */
inline void MRotX(PQP_REAL Mr[3][3], PQP_REAL t)
{
    PQP_REAL c = (PQP_REAL)cos((double)t), s = (PQP_REAL)sin((double)t);
    Midentity(Mr);
    Mr[1][1] = c;
    Mr[1][2] = -s;
    Mr[2][1] = s;
    Mr[2][2] = c;
}

/* Mr = the right-handed rotation by t radians about the y axis:
 * [[c, 0, s], [0, 1, 0], [-s, 0, c]]. */
inline void MRotY(PQP_REAL Mr[3][3], PQP_REAL t)
{
    PQP_REAL c = (PQP_REAL)cos((double)t), s = (PQP_REAL)sin((double)t);
    Midentity(Mr);
    Mr[0][0] = c;
    Mr[0][2] = s;
    Mr[2][0] = -s;
    Mr[2][2] = c;
}

/* Mr = the matrix PQP 1.3 makes of the quaternion q = (q[QX], q[QY], q[QZ], q[QW]) (vector part
 * first, scalar q[QW] last). q need not be of unit length: it is scaled by 2 / |q|^2, so every
 * nonzero multiple of q gives the same matrix; the zero quaternion gives the identity.
 *
 * Beware PQP's convention, kept here: the matrix is the TRANSPOSE of the rotation that q
 * represents in the usual (Hamilton, active) convention. With R the rotation taking v to
 * q v q^-1, MRotQ gives R^T, the rotation by the opposite angle: Mr[0][1] = 2 (xy + wz) / |q|^2,
 * where R[0][1] = 2 (xy - wz) / |q|^2. Use MTxV(v', Mr, v) to rotate v by q. */
inline void MRotQ(PQP_REAL Mr[3][3], const PQP_REAL q[4])
{
    double x = (double)q[QX], y = (double)q[QY], z = (double)q[QZ], w = (double)q[QW];
    double n = x * x + y * y + z * z + w * w;
    double k = n > 0 ? 2 / n : 0;
    /* R = I + k (w [v]x + [v]x^2) for v = (x, y, z), written out. */
    double R[3][3] = {{1 - k * (y * y + z * z), k * (x * y - w * z), k * (x * z + w * y)},
                      {k * (x * y + w * z), 1 - k * (x * x + z * z), k * (y * z - w * x)},
                      {k * (x * z - w * y), k * (y * z + w * x), 1 - k * (x * x + y * y)}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Mr[i][j] = (PQP_REAL)R[j][i];
}

/* Mr = the adjugate of m (the transpose of its cofactor matrix): Mr m = m Mr = det(m) I, so for an
 * invertible m it is det(m) times the inverse, and for a rotation it is the transpose. Entry by
 * entry, Mr[i][j] = m[j1][i1] m[j2][i2] - m[j1][i2] m[j2][i1] with i1 = (i+1)%3, i2 = (i+2)%3,
 * j1 = (j+1)%3, j2 = (j+2)%3. */
inline void Mqinverse(PQP_REAL Mr[3][3], const PQP_REAL m[3][3])
{
    PQP_REAL t[3][3];
    for (int i = 0; i < 3; i++) {
        int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; j++) {
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            t[i][j] = m[j1][i1] * m[j2][i2] - m[j1][i2] * m[j2][i1];
        }
    }
    McM(Mr, t);
}

/* ---- OpenGL. */

/* oglm = the pose (R, T) as OpenGL's column-major 4x4 matrix: oglm[4*j + i] is row i, column j of
 * [[R, T], [0 0 0 1]] (so oglm[0..2] is column 0 of R and oglm[12..14] is T). */
inline void MVtoOGL(double oglm[16], const PQP_REAL R[3][3], const PQP_REAL T[3])
{
    for (int j = 0; j < 3; j++) {
        for (int i = 0; i < 3; i++) oglm[4 * j + i] = (double)R[i][j];
        oglm[4 * j + 3] = 0.0;
        oglm[12 + j] = (double)T[j];
    }
    oglm[15] = 1.0;
}

/* (R, T) = the pose in OpenGL's column-major 4x4 matrix oglm (the inverse of MVtoOGL; the bottom
 * row of oglm is not read). */
inline void OGLtoMV(PQP_REAL R[3][3], PQP_REAL T[3], const double oglm[16])
{
    for (int j = 0; j < 3; j++) {
        for (int i = 0; i < 3; i++) R[i][j] = (PQP_REAL)oglm[4 * j + i];
        T[j] = (PQP_REAL)oglm[12 + j];
    }
}

/* ---- Eigen decomposition. */

/* Eigenvalues and eigenvectors of the symmetric matrix a (only its upper triangle is read):
 * a = vout diag(dout) vout^T with vout orthonormal. dout[k] is an eigenvalue and column k of vout
 * (vout[0][k], vout[1][k], vout[2][k]) a unit eigenvector for it. The eigenvalues are in no
 * particular order (PQP 1.3 did not sort them either) and each eigenvector's sign is arbitrary.
 * a is left unchanged and may be the same matrix as vout.
 *
 * Method: cyclic Jacobi rotations in double, on a copy of a scaled by a power of two (exactly) to
 * unit size, so that no intermediate overflows or underflows; each rotation zeroes one
 * off-diagonal entry, and sweeps repeat until the off-diagonal entries are negligible against the
 * matrix (they converge quadratically: a handful of sweeps). */
inline void Meigen(PQP_REAL vout[3][3], PQP_REAL dout[3], const PQP_REAL a[3][3])
{
    /* The symmetric matrix from a's upper triangle, and its largest magnitude. */
    double A[3][3], big = 0;
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
            A[i][j] = A[j][i] = (double)a[i][j];
            double m = fabs(A[i][j]);
            if (m > big) big = m;
        }
    /* Scale by 2^-e with 2^(e-1) <= big < 2^e (exact). */
    int e = 0;
    if (big > 0 && big <= DBL_MAX) frexp(big, &e);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) A[i][j] = ldexp(A[i][j], -e);
    double V[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int sweep = 0; sweep < 50; sweep++) {
        double off = fabs(A[0][1]) + fabs(A[0][2]) + fabs(A[1][2]);
        /* The entries of A started below 1 in magnitude (rotations keep the Frobenius norm, so
         * they stay below 3): an off-diagonal sum of 1e-18 is below a hundredth of a rounding of
         * the matrix. A NaN or infinite entry makes the eigenvalues non-finite (a NaN sum
         * never compares below, and runs all sweeps). */
        if (off <= 1e-18) break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                double apq = A[p][q];
                if (apq == 0) continue;
                /* The rotation by phi in the (p, q) plane with tan(2 phi) = 2 apq / (aqq - app)
                 * zeroes A[p][q]. t = tan(phi) is the root of t^2 + 2 theta t - 1 = 0 of smaller
                 * magnitude (|phi| <= pi/4), in a form without cancellation; when theta^2
                 * overflows, t is 0 and apq, negligible, is just dropped. */
                double theta = (A[q][q] - A[p][p]) / (2 * apq);
                double t = 1 / (fabs(theta) + sqrt(theta * theta + 1));
                if (theta < 0) t = -t;
                double c = 1 / sqrt(t * t + 1), s = t * c;
                /* A = J^T A J and V = V J, with J the identity except J[p][p] = J[q][q] = c,
                 * J[p][q] = s, J[q][p] = -s. */
                for (int k = 0; k < 3; k++) {
                    double akp = A[k][p], akq = A[k][q];
                    A[k][p] = c * akp - s * akq;
                    A[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    double apk = A[p][k], aqk = A[q][k];
                    A[p][k] = c * apk - s * aqk;
                    A[q][k] = s * apk + c * aqk;
                }
                A[p][q] = A[q][p] = 0; /* zero exactly, not to rounding */
                for (int k = 0; k < 3; k++) {
                    double vkp = V[k][p], vkq = V[k][q];
                    V[k][p] = c * vkp - s * vkq;
                    V[k][q] = s * vkp + c * vkq;
                }
            }
    }
    for (int k = 0; k < 3; k++) {
        dout[k] = (PQP_REAL)ldexp(A[k][k], e);
        for (int i = 0; i < 3; i++) vout[i][k] = (PQP_REAL)V[i][k];
    }
}

#endif /* PQP_MATVEC_H */
