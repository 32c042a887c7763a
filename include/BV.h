/*
 * BV.h -- PQP 1.3's bounding volume record and its tests, as pqp-rs provides them.
 *
 * PQP_Model::b (and child(n)) is an array of these after EndModel: the model's hierarchy with PQP
 * 1.3's layout and meaning. b[0] is the root. An inner volume's children are b[first_child] and
 * b[first_child + 1]; a leaf (first_child < 0) holds the triangle tris[-first_child - 1]. The
 * root's R, Tr and To are in the model's frame; every other volume's are relative to its parent's
 * (R = Rparent^T R, Tr and To taken from the parent's Tr and To in the parent's axes).
 *
 * In a volume's own frame (axes: the columns of R) the rectangle swept sphere is every point
 * within r of the rectangle [0, l[0]] x [0, l[1]] of the xy-plane placed at Tr, and the oriented box
 * is [-d[0], d[0]] x [-d[1], d[1]] x [-d[2], d[2]] placed at To. Every volume contains its
 * triangles. The volumes are computed by pqp-rs (in double, from its own hierarchy); the values
 * differ from those PQP 1.3 would have computed, the meaning does not.
 */
#ifndef PQP_BV_H
#define PQP_BV_H

#ifndef __cplusplus
#error "BV.h is a C++ header; C code includes <pqp/pqp.h>"
#endif

#include <math.h>
#include <stddef.h>

#include <limits>
#include <new>

#include "PQP_Compile.h"
#include "Tri.h"
#include "pqp/pqp_cxx.h"

struct BV
{
    PQP_REAL R[3][3];  /* orientation: the columns are the volume's axes */
    PQP_REAL Tr[3];    /* rectangle swept sphere: the rectangle's corner */
    PQP_REAL l[2];     /* the rectangle's side lengths along the first two axes */
    PQP_REAL r;        /* the swept sphere's radius */
    PQP_REAL To[3];    /* oriented box: its centre */
    PQP_REAL d[3];     /* its half extents along the axes */
    int first_child;   /* >= 0: index of the first child; < 0: -(index + 1) of the triangle */

    /* 1 for a leaf (a volume holding one triangle), else 0. */
    int Leaf() { return first_child < 0; }

    /* The size the search compares to choose which volume to split: the rectangle's diagonal plus
     * the sphere's diameter (with PQP_BV_TYPE including RSS_TYPE, the default), else the box's
     * squared half diagonal. */
    PQP_REAL GetSize()
    {
#if PQP_BV_TYPE & RSS_TYPE
        return (PQP_REAL)(sqrt((double)l[0] * l[0] + (double)l[1] * l[1]) + 2.0 * r);
#else
        return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
#endif
    }

    /* Fits this volume to num_tris triangles on the axes given by the columns of O (orthonormal):
     * R = O, and Tr, l, r and To, d enclose every vertex, in the triangles' frame. first_child is
     * left as it is. Nothing changes if an argument is NULL or not finite or num_tris < 1. */
    void FitToTris(PQP_REAL O[3][3], Tri *tris, int num_tris);
};

namespace pqp_detail {

/* PQP_REAL arrays widened to double for the C interface. */
inline void widen3(double out[3], const PQP_REAL v[3])
{
    for (int i = 0; i < 3; i++) out[i] = v[i];
}

inline void widen33(double out[9], const PQP_REAL m[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) out[3 * i + j] = m[i][j];
}

/* (NULL reads as zeros: what the C getters return for a result that has no point.) */
inline void narrow3(PQP_REAL out[3], const double v[3])
{
    for (int i = 0; i < 3; i++) out[i] = v != NULL ? (PQP_REAL)v[i] : (PQP_REAL)0;
}

inline void narrow33(PQP_REAL out[3][3], const double m[3][3])
{
    for (int i = 0; i < 3; i++) narrow3(out[i], m[i]);
}

/* A BV as the C interface's pqp_bv, and back. */
inline void widen_bv(pqp_bv *out, const BV *b)
{
    for (int i = 0; i < 3; i++) {
        widen3(out->R[i], b->R[i]);
        out->Tr[i] = b->Tr[i];
        out->To[i] = b->To[i];
        out->d[i] = b->d[i];
    }
    out->l[0] = b->l[0];
    out->l[1] = b->l[1];
    out->r = b->r;
    out->first_child = b->first_child;
}

inline void narrow_bv(BV *out, const pqp_bv *b)
{
    narrow33(out->R, b->R);
    narrow3(out->Tr, b->Tr);
    narrow3(out->To, b->To);
    narrow3(out->d, b->d);
    out->l[0] = (PQP_REAL)b->l[0];
    out->l[1] = (PQP_REAL)b->l[1];
    out->r = (PQP_REAL)b->r;
    out->first_child = b->first_child;
}

/* The arguments of BV_Overlap and BV_Distance widened for the C interface. */
struct bv_pair
{
    double R[9], T[3];
    pqp_bv b1, b2;
    bv_pair(PQP_REAL r[3][3], PQP_REAL t[3], const BV *v1, const BV *v2)
    {
        widen33(R, r);
        widen3(T, t);
        widen_bv(&b1, v1);
        widen_bv(&b2, v2);
    }
};

inline bool all_given(PQP_REAL R[3][3], PQP_REAL T[3], const BV *b1, const BV *b2)
{
    return R != NULL && T != NULL && b1 != NULL && b2 != NULL;
}

} /* namespace pqp_detail */

inline void BV::FitToTris(PQP_REAL O[3][3], Tri *tris, int num_tris)
{
    if (O == NULL || tris == NULL || num_tris < 1) return;
    pqp_tri *wide = new (std::nothrow) pqp_tri[num_tris];
    if (wide == NULL) return;
    for (int k = 0; k < num_tris; k++) {
        pqp_detail::widen3(wide[k].p1, tris[k].p1);
        pqp_detail::widen3(wide[k].p2, tris[k].p2);
        pqp_detail::widen3(wide[k].p3, tris[k].p3);
        wide[k].id = tris[k].id;
    }
    double axes[9];
    pqp_detail::widen33(axes, O);
    pqp_bv fitted;
    pqp_detail::widen_bv(&fitted, this);
    if (pqp_bv_fit(&fitted, axes, wide, num_tris) == PQP_OK) pqp_detail::narrow_bv(this, &fitted);
    delete[] wide;
}

/* Whether the oriented boxes of b1 and b2 overlap (touching counts), where (R, T) places b2's box
 * frame in b1's: a point x of b2's frame is R x + T in b1's. Only the boxes' half extents d are
 * read; the volumes' own R and To are the caller's to fold into (R, T), as PQP 1.3's search did.
 * Returns 1 or 0; 1 when an argument is NULL or not finite (the boxes cannot be shown apart). */
inline int BV_Overlap(PQP_REAL R[3][3], PQP_REAL T[3], BV *b1, BV *b2)
{
    if (!pqp_detail::all_given(R, T, b1, b2)) return 1;
    pqp_detail::bv_pair w(R, T, b1, b2);
    int overlap = 1;
    if (pqp_bv_overlap(&overlap, w.R, w.T, &w.b1, &w.b2) != PQP_OK) return 1;
    return overlap;
}

/* A lower bound on the distance between the rectangle swept spheres of b1 and b2, where (R, T)
 * places b2's rectangle frame in b1's (a point x of b2's frame is R x + T in b1's): the distance
 * between the two rectangles less both radii, negative when the volumes overlap. Only l and r are
 * read; the volumes' own R and Tr are the caller's to fold into (R, T), as PQP 1.3's search did.
 * NaN when an argument is NULL or not finite. */
inline PQP_REAL BV_Distance(PQP_REAL R[3][3], PQP_REAL T[3], BV *b1, BV *b2)
{
    const PQP_REAL nan = std::numeric_limits<PQP_REAL>::quiet_NaN();
    if (!pqp_detail::all_given(R, T, b1, b2)) return nan;
    pqp_detail::bv_pair w(R, T, b1, b2);
    double d = 0.0;
    if (pqp_bv_distance(&d, w.R, w.T, &w.b1, &w.b2) != PQP_OK) return nan;
    return (PQP_REAL)d;
}

#endif /* PQP_BV_H */
