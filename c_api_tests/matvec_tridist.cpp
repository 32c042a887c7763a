// MatVec.h and TriDist.h as PQP 1.3 programs use them: every MatVec.h function on thousands of
// random inputs against reference arithmetic written another way (index formulas, long double,
// rotations of basis vectors, quaternion products), and TriDist / SegPoints on thousands of
// random triangle and segment pairs (general, coplanar, parallel, touching, intersecting,
// degenerate, at many scales) against an independent long double reference. It must compile
// unchanged as C++98 to C++20 with -Wall -Wextra -pedantic -Werror.
//
// Compiled with PQP_TEST_FLOAT defined (matvec_tridist_float.cpp does that), PQP_REAL is float,
// as for a user who edited PQP_Compile.h: this file then stands in for the edited PQP_Compile.h
// (defining its include guard keeps the installed one out), and the tolerances are float's. That
// build also removes <math.h>'s M_PI, to check the one MatVec.h defines in its place.
#ifdef PQP_TEST_FLOAT
#define PQP_COMPILE_H
typedef float PQP_REAL;
#include <math.h>
#undef M_PI
#endif

#include "MatVec.h"
#include "TriDist.h"
#ifndef PQP_TEST_FLOAT
#include "PQP.h" // programs include it beside the other two
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"

#ifdef PQP_TEST_FLOAT
static const char *const NAME = "matvec_tridist_float";
// Distances are computed in double and rounded to float, and so are the closest points.
static const double REL = 1e-6;      // relative error allowed on a distance
static const double ABS = 1e-6;      // absolute error allowed, times the coordinates' magnitude
static const double ON = 1e-6;       // how far off its triangle a closest point may be, likewise
static const double EIGEN = 1e-6;    // Meigen: reconstruction and orthonormality
#else
static const char *const NAME = "matvec_tridist";
static const double REL = 1e-12;
static const double ABS = 1e-14;
static const double ON = 1e-14;
static const double EIGEN = 1e-12;
#endif

typedef long double LD;

// PQP_REAL's unit roundoff times 2 (the distance from 1 to the next value).
static const LD EPS = std::numeric_limits<PQP_REAL>::epsilon();
// When PQP_REAL is narrower than double, results computed in double and rounded to PQP_REAL
// differ from the same arithmetic on the rounded values by this much, times the magnitudes.
static const LD CONVERT = sizeof(PQP_REAL) < sizeof(double) ? EPS : 0;

static int failures = 0;
static const char *current = "";  // the group of cases being checked, for failure messages
static int current_case = 0;      // the index of the case in its group

static void fail(const char *file, int line, const char *what)
{
    if (failures < 40)
        fprintf(stderr, "%s:%d: [%s, case %d] expected %s\n", file, line, current, current_case,
                what);
    failures++;
}

#define EXPECT(cond)                                     \
    do {                                                 \
        if (!(cond)) fail(__FILE__, __LINE__, #cond);    \
    } while (0)

static void group(const char *name)
{
    current = name;
    current_case = 0;
}

// ---- Random numbers (splitmix64): the same sequence on every run.

// A 64-bit constant from its two 32-bit halves (C++98 has no long long literals).
#define U64(hi, lo) (((uint64_t)(hi) << 32) | (uint64_t)(lo))

static uint64_t rng_state = U64(0x2545F491, 0x4F6CDD1D);

static uint64_t next_u64()
{
    return check_splitmix64(&rng_state);
}

// Uniform in [lo, hi).
static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * (double)(next_u64() >> 11) * (1.0 / 9007199254740992.0);
}

// Uniform integer in [lo, hi].
static int uniform_int(int lo, int hi)
{
    return lo + (int)(next_u64() % (uint64_t)(hi - lo + 1));
}

// A random power of ten in [10^lo, 10^hi].
static double decade(int lo, int hi)
{
    return std::pow(10.0, uniform_int(lo, hi));
}

static void random_vector(PQP_REAL v[3], double scale)
{
    for (int i = 0; i < 3; i++) {
        // Through a volatile: with PQP_REAL float, g++ 12.2 at -O3 (its SLP vectorizer) inlined
        // this into check_ogl and stored the double value, not its float rounding, into
        // MVtoOGL's output (seen in the assembly; -fno-tree-slp-vectorize or -O2 do not).
        volatile PQP_REAL x = (PQP_REAL)(uniform(-1, 1) * scale);
        v[i] = x;
    }
}

static void random_matrix(PQP_REAL m[3][3], double scale)
{
    for (int i = 0; i < 3; i++) random_vector(m[i], scale);
}

// ---- Long double helpers for the references.

static LD labs_(LD x)
{
    return x < 0 ? -x : x;
}

static LD ldot(const LD a[3], const LD b[3])
{
    LD s = 0;
    for (int i = 0; i < 3; i++) s += a[i] * b[i];
    return s;
}

// The Levi-Civita symbol.
static int levi(int i, int j, int k)
{
    if (i == j || j == k || k == i) return 0;
    return ((j - i + 3) % 3 == 1) ? 1 : -1;
}

static void lcross(LD r[3], const LD a[3], const LD b[3])
{
    LD t[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) t[i] += levi(i, j, k) * a[j] * b[k];
    for (int i = 0; i < 3; i++) r[i] = t[i];
}

static void to_ld(LD r[3], const PQP_REAL v[3])
{
    for (int i = 0; i < 3; i++) r[i] = v[i];
}

static LD lnorm(const LD v[3])
{
    return std::sqrt(ldot(v, v));
}

// |got - want| <= tol, a check with the numbers printed on failure.
static void near(const char *file, int line, const char *what, LD got, LD want, LD tol)
{
    if (!(labs_(got - want) <= tol)) {
        if (failures < 40)
            fprintf(stderr, "%s:%d: [%s, case %d] %s: got %.20Lg, want %.20Lg (tolerance %.3Lg)\n",
                    file, line, current, current_case, what, got, want, tol);
        failures++;
    }
}

#define NEAR(got, want, tol) near(__FILE__, __LINE__, #got, (LD)(got), (LD)(want), (LD)(tol))

static bool same_vector(const PQP_REAL a[3], const PQP_REAL b[3])
{
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

static bool same_matrix(const PQP_REAL a[3][3], const PQP_REAL b[3][3])
{
    return same_vector(a[0], b[0]) && same_vector(a[1], b[1]) && same_vector(a[2], b[2]);
}

// ======================================================================================
// MatVec.h

// Entry (i, j) of op1(M1) op2(M2), op transposing its matrix when asked, in long double; *mag is
// the sum of the terms' magnitudes (the scale of the rounding error of a 3-term sum).
static LD product_entry(const PQP_REAL M1[3][3], bool t1, const PQP_REAL M2[3][3], bool t2, int i,
                        int j, LD *mag)
{
    LD s = 0, m = 0;
    for (int k = 0; k < 3; k++) {
        LD a = t1 ? M1[k][i] : M1[i][k];
        LD b = t2 ? M2[j][k] : M2[k][j];
        s += a * b;
        m += labs_(a * b);
    }
    *mag = m;
    return s;
}

// Entry i of op(M) V, likewise.
static LD product_vector(const PQP_REAL M[3][3], bool t, const PQP_REAL V[3], int i, LD *mag)
{
    LD s = 0, m = 0;
    for (int k = 0; k < 3; k++) {
        LD a = t ? M[k][i] : M[i][k];
        s += a * V[k];
        m += labs_(a * V[k]);
    }
    *mag = m;
    return s;
}

static void check_setting_and_copying()
{
    group("setting and copying");
    for (current_case = 0; current_case < 2000; current_case++) {
        PQP_REAL M[3][3], R[3][3], V[3], W[3];
        random_matrix(M, decade(-3, 3));
        random_vector(V, 1);
        Midentity(R);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) EXPECT(R[i][j] == (i == j ? 1 : 0));
        McM(R, M);
        EXPECT(same_matrix(R, M));
        MTcM(R, M);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) EXPECT(R[j][i] == M[i][j]);
        MTcM(R, R); // in place: back to M
        EXPECT(same_matrix(R, M));
        VcV(W, V);
        EXPECT(same_vector(W, V));
        Videntity(W);
        EXPECT(W[0] == 0 && W[1] == 0 && W[2] == 0);
        int c = current_case % 3, cr = (current_case / 3) % 3;
        McolcV(W, M, c);
        for (int i = 0; i < 3; i++) EXPECT(W[i] == M[i][c]);
        PQP_REAL K[3][3];
        random_matrix(R, 1);
        McM(K, R);
        McolcMcol(R, cr, M, c);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) EXPECT(R[i][j] == (j == cr ? M[i][c] : K[i][j]));
        McolcMcol(M, cr, M, c); // in place
        for (int i = 0; i < 3; i++) EXPECT(M[i][cr] == M[i][c]);
    }
}

static void check_products()
{
    group("products");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL A[3][3], B[3][3], R[3][3], T[3], V[3], W[3], r[3];
        random_matrix(A, decade(-3, 3));
        random_matrix(B, decade(-3, 3));
        random_vector(T, decade(-3, 3));
        random_vector(V, decade(-3, 3));
        random_vector(W, decade(-3, 3));
        PQP_REAL s = (PQP_REAL)uniform(-4, 4);
        LD mag;
        // Matrix products: each entry a 3-term sum, within 2 EPS of its terms' magnitude.
        const bool tr[3][2] = {{false, false}, {false, true}, {true, false}};
        for (int form = 0; form < 3; form++) {
            if (form == 0) MxM(R, A, B);
            if (form == 1) MxMT(R, A, B);
            if (form == 2) MTxM(R, A, B);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) {
                    LD want = product_entry(A, tr[form][0], B, tr[form][1], i, j, &mag);
                    NEAR(R[i][j], want, 2 * EPS * mag);
                }
            // The output may be an input.
            PQP_REAL X[3][3], Y[3][3];
            McM(X, A);
            McM(Y, B);
            if (form == 0) MxM(X, X, B), MxM(Y, A, Y);
            if (form == 1) MxMT(X, X, B), MxMT(Y, A, Y);
            if (form == 2) MTxM(X, X, B), MTxM(Y, A, Y);
            EXPECT(same_matrix(X, R));
            EXPECT(same_matrix(Y, R));
        }
        MxMpV(R, A, B, T);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                LD want = product_entry(A, false, B, false, i, j, &mag) + T[i];
                NEAR(R[i][j], want, 3 * EPS * (mag + labs_(T[i])));
            }
        // Matrix times vector, plain, scaled, plus a vector, transposed.
        for (int form = 0; form < 6; form++) {
            bool t = form == 3 || form == 4;
            if (form == 0) MxV(r, A, V);
            if (form == 1) MxVpV(r, A, V, W);
            if (form == 2) sMxVpV(r, s, A, V, W);
            if (form == 3) MTxV(r, A, V);
            if (form == 4) sMTxV(r, s, A, V);
            if (form == 5) sMxV(r, s, A, V);
            for (int i = 0; i < 3; i++) {
                LD want = product_vector(A, t, V, i, &mag);
                LD scale = (form == 2 || form == 4 || form == 5) ? (LD)s : (LD)1;
                LD add = (form == 1 || form == 2) ? (LD)W[i] : (LD)0;
                NEAR(r[i], scale * want + add, 3 * EPS * (labs_(scale) * mag + labs_(add)));
            }
            PQP_REAL X[3];
            VcV(X, V);
            if (form == 0) MxV(X, A, X);
            if (form == 1) MxVpV(X, A, X, W);
            if (form == 2) sMxVpV(X, s, A, X, W);
            if (form == 3) MTxV(X, A, X);
            if (form == 4) sMTxV(X, s, A, X);
            if (form == 5) sMxV(X, s, A, X);
            EXPECT(same_vector(X, r));
        }
    }
}

static void check_vectors()
{
    group("vectors");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL a[3], b[3], r[3], X[3];
        random_vector(a, decade(-3, 3));
        random_vector(b, decade(-3, 3));
        PQP_REAL s = (PQP_REAL)uniform(-4, 4);
        LD la[3], lb[3], lr[3];
        to_ld(la, a);
        to_ld(lb, b);
        // One rounding each (two for V1 + V2 s).
        VmV(r, a, b);
        for (int i = 0; i < 3; i++) NEAR(r[i], la[i] - lb[i], EPS * labs_(la[i] - lb[i]));
        VpV(r, a, b);
        for (int i = 0; i < 3; i++) NEAR(r[i], la[i] + lb[i], EPS * labs_(la[i] + lb[i]));
        VpVxS(r, a, b, s);
        for (int i = 0; i < 3; i++)
            NEAR(r[i], la[i] + lb[i] * s, 2 * EPS * (labs_(la[i]) + labs_(lb[i] * s)));
        VxS(r, a, s);
        for (int i = 0; i < 3; i++) NEAR(r[i], la[i] * s, EPS * labs_(la[i] * s));
        VcrossV(r, a, b);
        lcross(lr, la, lb);
        for (int i = 0; i < 3; i++) {
            int j = (i + 1) % 3, k = (i + 2) % 3;
            NEAR(r[i], lr[i], 2 * EPS * (labs_(la[j] * lb[k]) + labs_(la[k] * lb[j])));
        }
        // In place: every vector operation with its output as an input.
        VcV(X, a); VmV(X, X, b); VmV(r, a, b); EXPECT(same_vector(X, r));
        VcV(X, b); VmV(X, a, X); EXPECT(same_vector(X, r));
        VcV(X, a); VpV(X, X, b); VpV(r, a, b); EXPECT(same_vector(X, r));
        VcV(X, a); VpVxS(X, X, b, s); VpVxS(r, a, b, s); EXPECT(same_vector(X, r));
        VcV(X, b); VpVxS(X, a, X, s); EXPECT(same_vector(X, r));
        VcV(X, a); VxS(X, X, s); VxS(r, a, s); EXPECT(same_vector(X, r));
        VcV(X, a); VcrossV(X, X, b); VcrossV(r, a, b); EXPECT(same_vector(X, r));
        VcV(X, b); VcrossV(X, a, X); EXPECT(same_vector(X, r));
        // Dot product, squared distance, length, normalization.
        LD terms = labs_(la[0] * lb[0]) + labs_(la[1] * lb[1]) + labs_(la[2] * lb[2]);
        NEAR(VdotV(a, b), ldot(la, lb), 2 * EPS * terms);
        LD d2 = 0;
        for (int i = 0; i < 3; i++) d2 += (la[i] - lb[i]) * (la[i] - lb[i]);
        NEAR(VdistV2(a, b), d2, 4 * EPS * d2);
        NEAR(Vlength(a), lnorm(la), 2 * EPS * lnorm(la));
        VcV(X, a);
        Vnormalize(X);
        for (int i = 0; i < 3; i++) NEAR(X[i], la[i] / lnorm(la), 2 * EPS);
        // The skew matrix: entries by the Levi-Civita symbol, and M x = a x x.
        PQP_REAL M[3][3];
        MskewV(M, a);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                LD want = 0;
                for (int k = 0; k < 3; k++) want -= levi(i, j, k) * la[k];
                EXPECT(M[i][j] == want);
            }
        MxV(r, M, b);
        VcrossV(X, a, b);
        EXPECT(same_vector(r, X));
    }
    PQP_REAL z[3] = {0, 0, 0};
    Vnormalize(z);
    EXPECT(z[0] == 0 && z[1] == 0 && z[2] == 0);
    EXPECT(Vlength(z) == 0);
}

// v rotated by angle t about the unit axis u, by Rodrigues' formula:
// v cos t + (u x v) sin t + u (u.v)(1 - cos t).
static void rodrigues(LD r[3], const LD u[3], LD t, const LD v[3])
{
    LD c = std::cos(t), s = std::sin(t), uv = ldot(u, v), uxv[3];
    lcross(uxv, u, v);
    for (int i = 0; i < 3; i++) r[i] = v[i] * c + uxv[i] * s + u[i] * uv * (1 - c);
}

static void check_rotations()
{
    group("axis rotations");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL t = (PQP_REAL)uniform(-7, 7), M[3][3];
        for (int axis = 0; axis < 3; axis++) {
            if (axis == 0) MRotX(M, t);
            if (axis == 1) MRotY(M, t);
            if (axis == 2) MRotZ(M, t);
            LD u[3] = {0, 0, 0};
            u[axis] = 1;
            // Column j of M is where the basis vector e_j goes.
            for (int j = 0; j < 3; j++) {
                LD e[3] = {0, 0, 0}, want[3];
                e[j] = 1;
                rodrigues(want, u, t, e);
                for (int i = 0; i < 3; i++) NEAR(M[i][j], want[i], EPS);
            }
        }
    }
    // MRotZ's layout as documented.
    PQP_REAL M[3][3];
    MRotZ(M, (PQP_REAL)0.5);
    EXPECT(M[0][1] < 0 && M[1][0] > 0 && M[0][1] == -M[1][0] && M[2][2] == 1 && M[0][2] == 0);

    group("quaternions");
    EXPECT(QX == 0 && QY == 1 && QZ == 2 && QW == 3);
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL q[4], v[3], R[3][3];
        double size = decade(-3, 3);
        for (int i = 0; i < 4; i++) q[i] = (PQP_REAL)(uniform(-1, 1) * size);
        random_vector(v, 1);
        MRotQ(R, q);
        // The unit quaternion (w; x, y, z) and the Hamilton product w' = q (0; v) q*.
        LD n = std::sqrt((LD)q[0] * q[0] + (LD)q[1] * q[1] + (LD)q[2] * q[2] + (LD)q[3] * q[3]);
        LD w = q[QW] / n, u[3] = {q[QX] / n, q[QY] / n, q[QZ] / n}, lv[3];
        to_ld(lv, v);
        // p = q (0; v) = (-u.v; w v + u x v), then p q* with q* = (w; -u).
        LD uxv[3];
        lcross(uxv, u, lv);
        LD pw = -ldot(u, lv), pv[3];
        for (int i = 0; i < 3; i++) pv[i] = w * lv[i] + uxv[i];
        // (pw; pv)(w; -u) = (pw w + pv.u; -pw u + w pv - pv x u)
        LD pvxu[3], rotated[3];
        lcross(pvxu, pv, u);
        NEAR(pw * w + ldot(pv, u), 0, 8 * EPS);
        for (int i = 0; i < 3; i++) rotated[i] = -pw * u[i] + w * pv[i] - pvxu[i];
        // PQP's MRotQ is the transpose of that rotation: R^T v is v rotated by q.
        for (int j = 0; j < 3; j++) {
            LD got = 0;
            for (int i = 0; i < 3; i++) got += (LD)R[i][j] * lv[i];
            NEAR(got, rotated[j], 16 * EPS);
        }
        // The documented entry: R[0][1] = 2 (xy + wz) / |q|^2.
        NEAR(R[0][1], 2 * (u[0] * u[1] + w * u[2]), 16 * EPS);
        // Every nonzero multiple of q gives the same matrix (to rounding).
        PQP_REAL q2[4], R2[3][3];
        for (int i = 0; i < 4; i++) q2[i] = -4 * q[i];
        MRotQ(R2, q2);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) NEAR(R2[i][j], R[i][j], 16 * EPS);
    }
    PQP_REAL zero[4] = {0, 0, 0, 0}, R[3][3], I[3][3];
    MRotQ(R, zero);
    Midentity(I);
    EXPECT(same_matrix(R, I));
    // The quaternion of a rotation by t about z, (0, 0, sin t/2, cos t/2), gives MRotZ(-t).
    PQP_REAL qz[4] = {0, 0, (PQP_REAL)std::sin(0.35), (PQP_REAL)std::cos(0.35)}, Z[3][3];
    MRotQ(R, qz);
    MRotZ(Z, (PQP_REAL)-0.7);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) NEAR(R[i][j], Z[i][j], 8 * EPS);
}

static LD det3(const PQP_REAL m[3][3])
{
    LD d = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) d += levi(i, j, k) * (LD)m[0][i] * m[1][j] * m[2][k];
    return d;
}

static void check_adjugate()
{
    group("Mqinverse");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL m[3][3], r[3][3];
        double size = decade(-2, 2);
        random_matrix(m, size);
        Mqinverse(r, m);
        // r m = m r = det(m) I, to the rounding of products of three entries.
        LD det = det3(m), tol = 64 * EPS * size * size * size;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                LD rm = 0, mr = 0;
                for (int k = 0; k < 3; k++) {
                    rm += (LD)r[i][k] * m[k][j];
                    mr += (LD)m[i][k] * r[k][j];
                }
                NEAR(rm, i == j ? det : 0, tol);
                NEAR(mr, i == j ? det : 0, tol);
            }
        // In place.
        PQP_REAL x[3][3];
        McM(x, m);
        Mqinverse(x, x);
        EXPECT(same_matrix(x, r));
        // A rotation's adjugate is its transpose.
        PQP_REAL q[4], R[3][3];
        for (int i = 0; i < 4; i++) q[i] = (PQP_REAL)uniform(-1, 1);
        MRotQ(R, q);
        Mqinverse(r, R);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) NEAR(r[i][j], R[j][i], 16 * EPS);
    }
}

// Checks Meigen on the symmetric matrix a; `known`, if not NULL, are its eigenvalues in any order.
static void check_eigen_of(const PQP_REAL a[3][3], const LD *known)
{
    PQP_REAL copy[3][3], v[3][3], d[3];
    McM(copy, a);
    Meigen(v, d, a);
    EXPECT(same_matrix(copy, a)); // a is left unchanged
    LD big = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (labs_(a[i][j]) > big) big = labs_(a[i][j]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            // v^T v = I and v diag(d) v^T = a.
            LD vtv = 0, rec = 0;
            for (int k = 0; k < 3; k++) {
                vtv += (LD)v[k][i] * v[k][j];
                rec += (LD)v[i][k] * d[k] * v[j][k];
            }
            NEAR(vtv, i == j ? 1 : 0, EIGEN);
            NEAR(rec, a[i][j], EIGEN * big);
        }
    if (known) {
        // Sorted, the eigenvalues are the known ones.
        LD got[3] = {d[0], d[1], d[2]}, want[3] = {known[0], known[1], known[2]};
        for (int i = 0; i < 3; i++)
            for (int j = i + 1; j < 3; j++) {
                if (got[j] < got[i]) std::swap(got[i], got[j]);
                if (want[j] < want[i]) std::swap(want[i], want[j]);
            }
        for (int i = 0; i < 3; i++) NEAR(got[i], want[i], EIGEN * big);
    }
    // The output may be the input matrix itself.
    PQP_REAL w[3][3], e[3];
    McM(w, a);
    Meigen(w, e, w);
    EXPECT(same_matrix(w, v) && same_vector(e, d));
}

// a = Q diag(l) Q^T for a random rotation Q, rounded to PQP_REAL and made exactly symmetric.
static void with_eigenvalues(PQP_REAL a[3][3], const LD l[3])
{
    PQP_REAL q[4], Q[3][3];
    for (int i = 0; i < 4; i++) q[i] = (PQP_REAL)uniform(-1, 1);
    MRotQ(Q, q);
    for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
            LD s = 0;
            for (int k = 0; k < 3; k++) s += (LD)Q[i][k] * l[k] * Q[j][k];
            a[i][j] = a[j][i] = (PQP_REAL)s;
        }
}

static void check_eigen()
{
    group("Meigen, random symmetric");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL a[3][3];
#ifdef PQP_TEST_FLOAT
        double size = decade(-10, 10);
#else
        double size = decade(-200, 200);
#endif
        random_matrix(a, size);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < i; j++) a[i][j] = a[j][i];
        check_eigen_of(a, NULL);
    }
    group("Meigen, repeated eigenvalues");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL a[3][3];
        LD l[3];
        double size = decade(-3, 3);
        l[0] = l[1] = (PQP_REAL)(uniform(-1, 1) * size);
        l[2] = current_case % 3 == 0 ? l[0] : (LD)(PQP_REAL)(uniform(-1, 1) * size);
        if (current_case % 5 == 0) l[2] = 0; // singular
        with_eigenvalues(a, l);
        // The known eigenvalues hold to the rounding of a's entries (relative to its size).
        check_eigen_of(a, l);
    }
    group("Meigen, special matrices");
    PQP_REAL zero[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    LD zeros[3] = {0, 0, 0};
    check_eigen_of(zero, zeros);
    PQP_REAL diag[3][3] = {{3, 0, 0}, {0, -1, 0}, {0, 0, 2}};
    LD diags[3] = {3, -1, 2};
    check_eigen_of(diag, diags);
    PQP_REAL scalar[3][3] = {{5, 0, 0}, {0, 5, 0}, {0, 0, 5}};
    LD fives[3] = {5, 5, 5};
    check_eigen_of(scalar, fives);
    PQP_REAL swap[3][3] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 0}};
    LD swaps[3] = {1, -1, 0};
    check_eigen_of(swap, swaps);
    // Rank one: v v^T has eigenvalues |v|^2, 0, 0.
    PQP_REAL rank1[3][3] = {{1, 2, 3}, {2, 4, 6}, {3, 6, 9}};
    LD r1[3] = {14, 0, 0};
    check_eigen_of(rank1, r1);
    // A NaN or infinite entry gives non-finite eigenvalues (not a plausible answer).
    const int where[3][2] = {{0, 0}, {0, 1}, {1, 2}}; // on the diagonal, off it
    for (int k = 0; k < 6; k++) {
        PQP_REAL bad[3][3] = {{1, 2, 3}, {2, 4, 5}, {3, 5, 6}}, v[3][3], d[3];
        PQP_REAL x = k % 2 ? std::numeric_limits<PQP_REAL>::infinity()
                           : std::numeric_limits<PQP_REAL>::quiet_NaN();
        int r = where[k / 2][0], c = where[k / 2][1];
        bad[r][c] = bad[c][r] = x;
        Meigen(v, d, bad);
        bool finite = true;
        for (int i = 0; i < 3; i++) finite = finite && d[i] - d[i] == 0;
        EXPECT(!finite);
    }
    // Only the upper triangle is read.
    PQP_REAL upper[3][3] = {{1, 2, 3}, {-7, 4, 5}, {8, 9, 6}};
    PQP_REAL sym[3][3] = {{1, 2, 3}, {2, 4, 5}, {3, 5, 6}};
    PQP_REAL v1[3][3], v2[3][3], d1[3], d2[3];
    Meigen(v1, d1, upper);
    Meigen(v2, d2, sym);
    EXPECT(same_matrix(v1, v2) && same_vector(d1, d2));
}

static void check_ogl()
{
    group("OpenGL matrices");
    for (current_case = 0; current_case < 1000; current_case++) {
        PQP_REAL R[3][3], T[3], R2[3][3], T2[3];
        random_matrix(R, 1);
        random_vector(T, 100);
        double m[16];
        MVtoOGL(m, R, T);
        // Column-major: entry (row i, column j) at 4 j + i.
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) {
                double want = 0;
                if (i < 3 && j < 3) want = (double)R[i][j];
                if (i < 3 && j == 3) want = (double)T[i];
                if (i == 3 && j == 3) want = 1;
                EXPECT(m[4 * j + i] == want);
            }
        OGLtoMV(R2, T2, m);
        EXPECT(same_matrix(R, R2) && same_vector(T, T2));
    }
}

static void check_misc()
{
    group("myfabs, M_PI, printing");
    // The argument is parenthesized: PQP 1.3's macro made myfabs(1 - 3) -4.
    EXPECT(myfabs(1 - 3) == 2);
    EXPECT(myfabs(3 - 1) == 2);
    EXPECT(myfabs(-2.5) == 2.5);
    PQP_REAL x = (PQP_REAL)0.25, y = (PQP_REAL)0.75;
    EXPECT(myfabs(x - y) == (PQP_REAL)0.5);
    EXPECT(2 * myfabs(x - y) == 1); // the whole expansion is one operand
    NEAR(M_PI, std::acos((LD)-1), 2 * EPS);

    // Mfprint and Vfprint write "%g %g %g\n" per row.
    FILE *f = tmpfile();
    EXPECT(f != NULL);
    if (f == NULL) return;
    PQP_REAL M[3][3] = {
        {1, (PQP_REAL)-2.5, 3}, {(PQP_REAL)0.125, 0, 1000000}, {(PQP_REAL)1e-7, 7, 8}};
    PQP_REAL V[3] = {(PQP_REAL)0.5, -1, 123456};
    Mfprint(f, M);
    Vfprint(f, V);
    rewind(f);
    char text[512];
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    char want[512];
    sprintf(want, "%g %g %g\n%g %g %g\n%g %g %g\n%g %g %g\n", (double)M[0][0], (double)M[0][1],
            (double)M[0][2], (double)M[1][0], (double)M[1][1], (double)M[1][2], (double)M[2][0],
            (double)M[2][1], (double)M[2][2], (double)V[0], (double)V[1], (double)V[2]);
    EXPECT(strcmp(text, want) == 0);
    const char *start = "1 -2.5 3\n0.125 0 1e+06\n";
    EXPECT(strncmp(text, start, strlen(start)) == 0);
    // The stdout forms print the same lines (seen in this program's output).
    printf("MatVec.h printing to stdout:\n");
    Mprintg(M);
    Mprint(M);
    Vprintg(V);
    Vprint(V);
}

// ======================================================================================
// TriDist.h: the long double reference.

// Distance from x to the segment p + s a, s in [0, 1].
static LD ref_point_segment(const LD x[3], const LD p[3], const LD a[3])
{
    LD aa = ldot(a, a), s = 0, w[3];
    for (int i = 0; i < 3; i++) w[i] = x[i] - p[i];
    if (aa > 0) {
        s = ldot(w, a) / aa;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
    }
    LD g[3];
    for (int i = 0; i < 3; i++) g[i] = p[i] + s * a[i] - x[i];
    return lnorm(g);
}

// Distance between the segments p + s a and q + t b (s, t in [0, 1]): the smallest of the four
// endpoint-to-segment distances (the minimum over the boundary of the parameter square) and,
// for non-parallel segments, the distance at the lines' closest pair when it lies in the square.
static LD ref_segment_segment(const LD p[3], const LD a[3], const LD q[3], const LD b[3])
{
    LD pa[3], qb[3];
    for (int i = 0; i < 3; i++) {
        pa[i] = p[i] + a[i];
        qb[i] = q[i] + b[i];
    }
    LD best = ref_point_segment(p, q, b);
    best = std::min(best, ref_point_segment(pa, q, b));
    best = std::min(best, ref_point_segment(q, p, a));
    best = std::min(best, ref_point_segment(qb, p, a));
    LD n[3], r[3], rb[3], ra[3];
    lcross(n, a, b);
    LD nn = ldot(n, n);
    if (nn > 0) {
        for (int i = 0; i < 3; i++) r[i] = q[i] - p[i];
        lcross(rb, r, b);
        lcross(ra, r, a);
        LD s = ldot(rb, n) / nn, t = ldot(ra, n) / nn;
        if (s >= 0 && s <= 1 && t >= 0 && t <= 1) {
            LD g[3];
            for (int i = 0; i < 3; i++) g[i] = p[i] + s * a[i] - q[i] - t * b[i];
            best = std::min(best, lnorm(g));
        }
    }
    return best;
}

// Distance from x to the triangle t (any triangle, degenerate ones included).
static LD ref_point_triangle(const LD x[3], const LD t[3][3])
{
    LD e[3][3];
    for (int k = 0; k < 3; k++)
        for (int i = 0; i < 3; i++) e[k][i] = t[(k + 1) % 3][i] - t[k][i];
    LD n[3];
    lcross(n, e[0], e[1]);
    LD nn = ldot(n, n);
    if (nn > 0) {
        // Inside when x is on the inner side of each edge (its projection is in the triangle).
        bool inside = true;
        for (int k = 0; k < 3; k++) {
            LD w[3], c[3];
            for (int i = 0; i < 3; i++) w[i] = x[i] - t[k][i];
            lcross(c, e[k], w);
            if (ldot(c, n) < 0) inside = false;
        }
        if (inside) {
            LD w[3];
            for (int i = 0; i < 3; i++) w[i] = x[i] - t[0][i];
            return labs_(ldot(w, n)) / std::sqrt(nn);
        }
    }
    LD best = ref_point_segment(x, t[0], e[0]);
    best = std::min(best, ref_point_segment(x, t[1], e[1]));
    best = std::min(best, ref_point_segment(x, t[2], e[2]));
    return best;
}

// The distance from the triangle t to the point where the segment [e0, e1] crosses t's plane, if
// it crosses it strictly (the endpoints on opposite sides); +infinity otherwise.
static LD ref_edge_crossing(const LD e0[3], const LD e1[3], const LD t[3][3])
{
    LD u[3], v[3], n[3], w0[3], w1[3];
    for (int i = 0; i < 3; i++) {
        u[i] = t[1][i] - t[0][i];
        v[i] = t[2][i] - t[0][i];
        w0[i] = e0[i] - t[0][i];
        w1[i] = e1[i] - t[0][i];
    }
    lcross(n, u, v);
    LD d0 = ldot(w0, n), d1 = ldot(w1, n);
    if (!((d0 > 0 && d1 < 0) || (d0 < 0 && d1 > 0))) return std::numeric_limits<LD>::infinity();
    LD x[3], k = d0 / (d0 - d1);
    for (int i = 0; i < 3; i++) x[i] = e0[i] + k * (e1[i] - e0[i]);
    return ref_point_triangle(x, t);
}

// The distance between triangles: the minimum over the 9 edge pairs, the 6 vertex-triangle
// pairs, and the 6 edge-crossing-triangle pairs (which find intersections). Each candidate is the
// distance of a pair of points of the triangles, and the closest pair is among them.
static LD ref_triangle_distance(const LD s[3][3], const LD t[3][3])
{
    LD best = std::numeric_limits<LD>::infinity();
    for (int i = 0; i < 3; i++) {
        int i1 = (i + 1) % 3;
        LD a[3], b[3];
        for (int k = 0; k < 3; k++) a[k] = s[i1][k] - s[i][k];
        for (int j = 0; j < 3; j++) {
            int j1 = (j + 1) % 3;
            for (int k = 0; k < 3; k++) b[k] = t[j1][k] - t[j][k];
            best = std::min(best, ref_segment_segment(s[i], a, t[j], b));
        }
        best = std::min(best, ref_point_triangle(s[i], t));
        best = std::min(best, ref_point_triangle(t[i], s));
        best = std::min(best, ref_edge_crossing(s[i], s[i1], t));
        best = std::min(best, ref_edge_crossing(t[i], t[i1], s));
    }
    return best;
}

// ======================================================================================
// TriDist.h: the checks.

// Cases checked, and how many of them were at distance 0 (so that the output shows the contact
// cases are exercised).
static int tri_cases = 0, tri_contacts = 0, seg_cases = 0, seg_contacts = 0;

static LD magnitude(const PQP_REAL s[3][3], const PQP_REAL t[3][3])
{
    LD m = 0;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) {
            m = std::max(m, labs_(s[i][k]));
            m = std::max(m, labs_(t[i][k]));
        }
    return m;
}

// TriDist(s, t) against the reference; `touching`: the triangles are known to share a point.
static void check_tridist(const PQP_REAL s[3][3], const PQP_REAL t[3][3], bool touching)
{
    tri_cases++;
    LD ls[3][3], lt[3][3];
    for (int i = 0; i < 3; i++) {
        to_ld(ls[i], s[i]);
        to_ld(lt[i], t[i]);
    }
    LD ref = ref_triangle_distance(ls, lt), scale = magnitude(s, t);
    PQP_REAL p[3], q[3];
    PQP_REAL d = TriDist(p, q, s, t);
    EXPECT(d >= 0);
    NEAR(d, ref, REL * ref + ABS * scale);
    // The points are on their triangles, and as far apart as the distance says.
    LD lp[3], lq[3], g[3];
    to_ld(lp, p);
    to_ld(lq, q);
    NEAR(ref_point_triangle(lp, ls), 0, ON * scale);
    NEAR(ref_point_triangle(lq, lt), 0, ON * scale);
    for (int i = 0; i < 3; i++) g[i] = lq[i] - lp[i];
    NEAR(lnorm(g), d, REL * d + ABS * scale);
    // Distance 0 exactly when they share a point, and then p == q.
    if (touching) EXPECT(d == 0);
    if (d == 0) {
        tri_contacts++;
        EXPECT(same_vector(p, q));
    }
    // The other order gives the same distance, and the points swapped.
    PQP_REAL p2[3], q2[3];
    PQP_REAL d2 = TriDist(p2, q2, t, s);
    NEAR(d2, d, REL * d + ABS * scale);
    NEAR(ref_point_triangle(lp, ls), 0, ON * scale);
    to_ld(lp, p2);
    to_ld(lq, q2);
    NEAR(ref_point_triangle(lp, lt), 0, ON * scale);
    NEAR(ref_point_triangle(lq, ls), 0, ON * scale);
}

static void random_triangle(PQP_REAL t[3][3], double size, const double at[3])
{
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) t[i][k] = (PQP_REAL)(at[k] + uniform(-1, 1) * size);
}

// Applies a random permutation of the axes and sign flips to both triangles (exact), so that the
// axis-aligned constructions below take every orientation.
static void shuffle_axes(PQP_REAL s[3][3], PQP_REAL t[3][3])
{
    int perm[3] = {0, 1, 2};
    for (int i = 2; i > 0; i--) std::swap(perm[i], perm[uniform_int(0, i)]);
    PQP_REAL sign[3];
    for (int k = 0; k < 3; k++) sign[k] = (PQP_REAL)(uniform_int(0, 1) ? 1 : -1);
    for (int i = 0; i < 3; i++) {
        PQP_REAL a[3], b[3];
        for (int k = 0; k < 3; k++) {
            a[k] = sign[k] * s[i][perm[k]];
            b[k] = sign[k] * t[i][perm[k]];
        }
        VcV(s[i], a);
        VcV(t[i], b);
    }
}

static void check_triangles()
{
    const double origin[3] = {0, 0, 0};
    group("triangles, general");
    for (current_case = 0; current_case < 20000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double size = decade(-3, 3), at[3];
        for (int k = 0; k < 3; k++) at[k] = uniform(-2, 2) * size;
        random_triangle(s, size, origin);
        random_triangle(t, size * uniform(0.01, 2), at);
        // Some far from the origin: the triangles' size is then well below the coordinates'.
        if (current_case % 7 == 0) {
            double far = uniform(-1, 1) * size * 1e4;
            for (int i = 0; i < 3; i++) s[i][0] += (PQP_REAL)far, t[i][0] += (PQP_REAL)far;
        }
        check_tridist(s, t, false);
    }

    group("triangles, scaled by powers of two");
    for (current_case = 0; current_case < 2000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double at[3] = {uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)};
        random_triangle(s, 1, origin);
        random_triangle(t, 1, at);
#ifdef PQP_TEST_FLOAT
        PQP_REAL k = (PQP_REAL)std::ldexp(1.0, uniform_int(-100, 100));
#else
        // Coordinates up to about 1e145 and down to about 1e-271.
        PQP_REAL k = (PQP_REAL)std::ldexp(1.0, uniform_int(-900, 480));
#endif
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) s[i][j] *= k, t[i][j] *= k;
        check_tridist(s, t, false);
    }

    group("triangles, coplanar");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double at[3] = {uniform(-2, 2), uniform(-2, 2), 0};
        random_triangle(s, 1, origin);
        random_triangle(t, 1, at);
        PQP_REAL z = (PQP_REAL)uniform(-1, 1);
        for (int i = 0; i < 3; i++) s[i][2] = t[i][2] = z;
        shuffle_axes(s, t);
        check_tridist(s, t, false);
    }

    group("triangles, in parallel planes");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double at[3] = {uniform(-2, 2), uniform(-2, 2), 0};
        random_triangle(s, 1, origin);
        random_triangle(t, 1, at);
        PQP_REAL h = (PQP_REAL)(uniform(0, 1) * decade(-6, 0));
        for (int i = 0; i < 3; i++) {
            s[i][2] = 0;
            t[i][2] = h;
        }
        shuffle_axes(s, t);
        check_tridist(s, t, false);
    }

    group("triangles sharing a vertex");
    for (current_case = 0; current_case < 2000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double at[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
        random_triangle(s, 1, origin);
        random_triangle(t, 1, at);
        VcV(t[uniform_int(0, 2)], s[uniform_int(0, 2)]);
        check_tridist(s, t, true);
    }

    group("triangles sharing an edge");
    for (current_case = 0; current_case < 2000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        random_triangle(s, 1, origin);
        random_triangle(t, 1, origin);
        int i = uniform_int(0, 2), j = uniform_int(0, 2);
        VcV(t[j], s[i]);
        VcV(t[(j + 1) % 3], s[(i + 1) % 3]);
        check_tridist(s, t, true);
    }

    group("a vertex on the other's face");
    for (current_case = 0; current_case < 2000; current_case++) {
        // s in the plane z = c with integer coordinates; t's first vertex at a point of s with
        // dyadic barycentric coordinates (exact); t's other vertices above, or on both sides.
        PQP_REAL s[3][3], t[3][3];
        PQP_REAL c = (PQP_REAL)uniform_int(-4, 4);
        for (int i = 0; i < 3; i++) {
            s[i][0] = (PQP_REAL)uniform_int(-8, 8);
            s[i][1] = (PQP_REAL)uniform_int(-8, 8);
            s[i][2] = c;
        }
        int w[3] = {uniform_int(0, 8), uniform_int(0, 8), 0};
        w[2] = 16 - w[0] - w[1];
        for (int k = 0; k < 3; k++)
            t[0][k] = (PQP_REAL)((w[0] * s[0][k] + w[1] * s[1][k] + w[2] * s[2][k]) / 16.0);
        for (int i = 1; i < 3; i++) {
            t[i][0] = (PQP_REAL)uniform(-8, 8);
            t[i][1] = (PQP_REAL)uniform(-8, 8);
            double h = uniform(0.1, 4);
            t[i][2] = c + (PQP_REAL)((current_case % 2 && i == 2) ? -h : h);
        }
        shuffle_axes(s, t);
        check_tridist(s, t, true);
    }

    group("intersecting triangles");
    for (current_case = 0; current_case < 3000; current_case++) {
        // A point x well inside s, and t around x (x a convex combination of t's vertices with
        // weights at least 0.1), crossing s's plane at an angle.
        PQP_REAL s[3][3], t[3][3];
        random_triangle(s, 1, origin);
        double b[3] = {uniform(0.1, 1), uniform(0.1, 1), uniform(0.1, 1)};
        double sum = b[0] + b[1] + b[2], x[3];
        for (int k = 0; k < 3; k++) x[k] = (b[0] * s[0][k] + b[1] * s[1][k] + b[2] * s[2][k]) / sum;
        double c[3] = {uniform(0.1, 1), uniform(0.1, 1), uniform(0.1, 1)}, d[3][3];
        double csum = c[0] + c[1] + c[2];
        for (int k = 0; k < 3; k++) {
            d[0][k] = uniform(-1, 1);
            d[1][k] = uniform(-1, 1);
            d[2][k] = -(c[0] * d[0][k] + c[1] * d[1][k]) / c[2];
        }
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++) t[i][k] = (PQP_REAL)(x[k] + d[i][k] * csum);
        // Only when t crosses s's plane clearly (not nearly coplanar with s).
        LD e1[3], e2[3], n[3], m[3], f1[3], f2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = (LD)s[1][k] - s[0][k];
            e2[k] = (LD)s[2][k] - s[0][k];
            f1[k] = (LD)t[1][k] - t[0][k];
            f2[k] = (LD)t[2][k] - t[0][k];
        }
        lcross(n, e1, e2);
        lcross(m, f1, f2);
        LD cross[3];
        lcross(cross, n, m);
        // Nor when s is a sliver (x would be near its border).
        LD e3[3];
        for (int k = 0; k < 3; k++) e3[k] = (LD)s[2][k] - s[1][k];
        LD longest = std::max(lnorm(e1), std::max(lnorm(e2), lnorm(e3)));
        if (lnorm(cross) < 0.05 * lnorm(n) * lnorm(m) || lnorm(n) < 0.1 * longest * longest) {
            current_case--;
            continue;
        }
        check_tridist(s, t, true);
    }

    group("degenerate triangles");
    for (current_case = 0; current_case < 3000; current_case++) {
        PQP_REAL s[3][3], t[3][3];
        double at[3] = {uniform(-2, 2), uniform(-2, 2), uniform(-2, 2)};
        random_triangle(s, 1, origin);
        random_triangle(t, 1, at);
        // s: a segment (a repeated vertex), a point, or three collinear integer points.
        int kind = current_case % 3;
        int i = uniform_int(0, 2);
        if (kind == 0) VcV(s[(i + uniform_int(1, 2)) % 3], s[i]);
        if (kind == 1) VcV(s[1], s[0]), VcV(s[2], s[0]);
        if (kind == 2)
            for (int k = 0; k < 3; k++) {
                int a = uniform_int(-4, 4), d = uniform_int(-3, 3);
                s[0][k] = (PQP_REAL)a;
                s[1][k] = (PQP_REAL)(a + d);
                s[2][k] = (PQP_REAL)(a + uniform_int(-2, 2) * d);
            }
        // t: as it is, or degenerate as well.
        if (current_case % 4 == 1) VcV(t[2], t[0]);
        if (current_case % 4 == 2) VcV(t[1], t[0]), VcV(t[2], t[0]);
        check_tridist(s, t, false);
        // Degenerate and touching: the point s[0] as a vertex of t.
        VcV(t[uniform_int(0, 2)], s[0]);
        check_tridist(s, t, true);
    }
}

// SegPoints against the reference; `touching`: the segments are known to meet, at closest points
// computed exactly (so that X == Y).
static void check_segpoints(const PQP_REAL P[3], const PQP_REAL A[3], const PQP_REAL Q[3],
                            const PQP_REAL B[3], bool touching)
{
    seg_cases++;
    LD lP[3], lA[3], lQ[3], lB[3];
    to_ld(lP, P);
    to_ld(lA, A);
    to_ld(lQ, Q);
    to_ld(lB, B);
    LD ref = ref_segment_segment(lP, lA, lQ, lB), scale = 0;
    for (int i = 0; i < 3; i++) {
        scale = std::max(scale, labs_(lP[i]) + labs_(lA[i]));
        scale = std::max(scale, labs_(lQ[i]) + labs_(lB[i]));
    }
    PQP_REAL VEC[3], X[3], Y[3];
    SegPoints(VEC, X, Y, P, A, Q, B);
    LD lX[3], lY[3], g[3];
    to_ld(lX, X);
    to_ld(lY, Y);
    for (int i = 0; i < 3; i++) g[i] = lY[i] - lX[i];
    NEAR(lnorm(g), ref, REL * ref + ABS * scale);
    NEAR(ref_point_segment(lX, lP, lA), 0, ON * scale);
    NEAR(ref_point_segment(lY, lQ, lB), 0, ON * scale);
    if (touching) EXPECT(same_vector(X, Y));
    if (!same_vector(X, Y)) {
        // Apart: VEC = Y - X (computed in double, then rounded).
        for (int i = 0; i < 3; i++) NEAR(VEC[i], g[i], EPS * labs_(g[i]) + CONVERT * scale);
    } else if (touching || CONVERT == 0) {
        seg_contacts++;
        // Touching: VEC = +-(A x B), towards Q's side of P.
        LD n[3], r[3];
        lcross(n, lA, lB);
        for (int i = 0; i < 3; i++) r[i] = lQ[i] - lP[i];
        LD sign = ldot(n, r) < 0 ? -1 : 1;
        for (int i = 0; i < 3; i++) {
            int j = (i + 1) % 3, k = (i + 2) % 3;
            NEAR(VEC[i], sign * n[i], 2 * EPS * (labs_(lA[j] * lB[k]) + labs_(lA[k] * lB[j])));
        }
        LD v[3];
        to_ld(v, VEC);
        EXPECT(ldot(v, r) >= -ABS * scale * scale * scale);
    }
}

// An integer vector whose squared length is a power of two (so that the segment kernel's
// reciprocals are exact), times k.
static void dyadic_direction(PQP_REAL v[3], int k)
{
    static const int dirs[9][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1},
                                   {0, 1, 1}, {1, -1, 0}, {-1, 0, 1}, {0, 1, -1}};
    const int *d = dirs[uniform_int(0, 8)];
    int sign = uniform_int(0, 1) ? 1 : -1;
    for (int i = 0; i < 3; i++) v[i] = (PQP_REAL)(sign * k * d[i]);
}

static void check_segments()
{
    group("segments, general");
    for (current_case = 0; current_case < 20000; current_case++) {
        PQP_REAL P[3], A[3], Q[3], B[3];
        double size = decade(-3, 3);
        random_vector(P, size);
        random_vector(A, size);
        random_vector(Q, size * 2);
        random_vector(B, size * uniform(0.01, 2));
        check_segpoints(P, A, Q, B, false);
        check_segpoints(Q, B, P, A, false);
    }
    group("segments, parallel, collinear and degenerate");
    for (current_case = 0; current_case < 6000; current_case++) {
        PQP_REAL P[3], A[3], Q[3], B[3];
        random_vector(P, 1);
        random_vector(A, 1);
        random_vector(Q, 1);
        int kind = current_case % 6;
        PQP_REAL k = (PQP_REAL)(uniform_int(0, 1) ? 2 : -0.5);
        VxS(B, A, k); // parallel (exactly: times a power of two)
        if (kind == 1) VpVxS(Q, P, A, (PQP_REAL)uniform_int(-3, 3)); // collinear (to rounding)
        if (kind == 2) Videntity(A);                                   // a point and a segment
        if (kind == 3) Videntity(B);
        if (kind == 4) Videntity(A), Videntity(B);                     // two points
        if (kind == 5) random_vector(B, 1), VpVxS(B, B, A, (PQP_REAL)1e3); // nearly parallel
        check_segpoints(P, A, Q, B, false);
    }
    group("segments, touching");
    for (current_case = 0; current_case < 4000; current_case++) {
        // Crossing at an integer point C at dyadic parameters, or meeting end to end.
        PQP_REAL C[3], P[3], A[3], Q[3], B[3];
        for (int i = 0; i < 3; i++) C[i] = (PQP_REAL)uniform_int(-8, 8);
        dyadic_direction(A, 4 << uniform_int(0, 2));
        dyadic_direction(B, 4 << uniform_int(0, 2));
        PQP_REAL a = (PQP_REAL)(uniform_int(0, 4) / 4.0), b = (PQP_REAL)(uniform_int(0, 4) / 4.0);
        if (current_case % 2) a = 1, b = 0; // end to end: P + A == Q
        VpVxS(P, C, A, -a);
        VpVxS(Q, C, B, -b);
        // Parallel directions meet only end to end (or overlap, where X == Y is not promised).
        PQP_REAL n[3];
        VcrossV(n, A, B);
        bool parallel = n[0] == 0 && n[1] == 0 && n[2] == 0;
        check_segpoints(P, A, Q, B, !parallel || (a == 1 && b == 0));
    }
}

static void check_nonfinite()
{
    group("non-finite input");
    const PQP_REAL inf = std::numeric_limits<PQP_REAL>::infinity();
    const PQP_REAL nan = std::numeric_limits<PQP_REAL>::quiet_NaN();
#ifdef PQP_TEST_FLOAT
    const int bad_kinds = 2;
#else
    const int bad_kinds = 3;
#endif
    PQP_REAL bads[3] = {nan, -inf, 0};
#ifndef PQP_TEST_FLOAT
    bads[2] = 1e200; // finite, but beyond the library's 1e150
#endif
    for (int kind = 0; kind < bad_kinds; kind++) {
        PQP_REAL bad = bads[kind];
        for (current_case = 0; current_case < 18; current_case++) {
            PQP_REAL s[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
            PQP_REAL t[3][3] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
            int c = current_case % 9;
            if (current_case < 9) s[c / 3][c % 3] = bad;
            else t[c / 3][c % 3] = bad;
            PQP_REAL p[3] = {1, 2, 3}, q[3] = {1, 2, 3};
            PQP_REAL d = TriDist(p, q, s, t);
            EXPECT(d != d);
            for (int i = 0; i < 3; i++) EXPECT(p[i] != p[i] && q[i] != q[i]);
        }
        for (current_case = 0; current_case < 12; current_case++) {
            PQP_REAL v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}, {0, 0, 1}};
            v[current_case / 3][current_case % 3] = bad;
            PQP_REAL VEC[3], X[3], Y[3];
            SegPoints(VEC, X, Y, v[0], v[1], v[2], v[3]);
            for (int i = 0; i < 3; i++) EXPECT(VEC[i] != VEC[i] && X[i] != X[i] && Y[i] != Y[i]);
        }
    }
    // The C functions directly: NULL pointers are refused.
    double d = 0, p[3], q[3];
    const double s[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    EXPECT(pqp_triangle_distance(NULL, p, q, s, s) == PQP_ERR_NULL_POINTER);
    EXPECT(pqp_triangle_distance(&d, p, q, s, NULL) == PQP_ERR_NULL_POINTER);
    EXPECT(pqp_segment_distance(&d, p, q, s, s, s, NULL) == PQP_ERR_NULL_POINTER);
    EXPECT(pqp_segment_distance(&d, NULL, q, s, s, s, s) == PQP_ERR_NULL_POINTER);
    EXPECT(pqp_triangle_distance(&d, p, q, s, s) == PQP_OK && d == 0);
}

int main()
{
    check_setting_and_copying();
    check_products();
    check_vectors();
    check_rotations();
    check_adjugate();
    check_eigen();
    check_ogl();
    check_misc();
    check_triangles();
    check_segments();
    check_nonfinite();
    printf("%s: checked against the reference: %d triangle pairs (%d at distance 0), %d segment "
           "pairs (%d touching)\n", NAME, tri_cases, tri_contacts, seg_cases, seg_contacts);
    if (failures) {
        fprintf(stderr, "%s: %d check(s) failed\n", NAME, failures);
        return 1;
    }
    printf("%s: all checks passed\n", NAME);
    return 0;
}
