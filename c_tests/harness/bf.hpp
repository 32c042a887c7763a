// Brute-force triangle geometry, templated on the scalar (the tests use long double).
//
// These routines are the referee of the comparisons: deliberately simple formulations, independent of
// the library under test and of its peers (FCL, libccd).
//  - distance between two closed triangles = 0 if an edge of one crosses the other (orientation signs),
//    else the minimum over the 6 vertex-triangle and 9 edge-edge distances;
//  - penetration depth estimate = minimum overlap of the projections on the separating-axis candidates
//    (both normals and the 9 edge cross products: the face normals of the Minkowski difference).
#pragma once

#include <algorithm>
#include <cmath>

namespace bf {

template <class T> struct V {
    T x, y, z;
};

template <class T> inline V<T> operator+(const V<T> &a, const V<T> &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class T> inline V<T> operator-(const V<T> &a, const V<T> &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T> inline V<T> operator*(const V<T> &a, T s) { return {a.x * s, a.y * s, a.z * s}; }
template <class T> inline T dot(const V<T> &a, const V<T> &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> inline V<T> cross(const V<T> &a, const V<T> &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> inline T norm2(const V<T> &a) { return dot(a, a); }

/// Squared distance and the realising points: `p` on the first argument, `q` on the second.
template <class T> struct Closest {
    T d2;
    V<T> p, q;
};

template <class T> Closest<T> point_segment(const V<T> &p, const V<T> &a, const V<T> &b) {
    const V<T> ab = b - a;
    const T l2 = norm2(ab);
    T t = 0;
    if (l2 > 0) {
        t = dot(p - a, ab) / l2;
        t = std::min<T>(T(1), std::max<T>(T(0), t));
    }
    const V<T> c = a + ab * t;
    return {norm2(p - c), p, c};
}

template <class T> Closest<T> point_triangle(const V<T> &p, const V<T> *tri) {
    Closest<T> best = point_segment(p, tri[0], tri[1]);
    for (int i = 1; i < 3; ++i) {
        const Closest<T> c = point_segment(p, tri[i], tri[(i + 1) % 3]);
        if (c.d2 < best.d2) best = c;
    }
    const V<T> n = cross(tri[1] - tri[0], tri[2] - tri[0]);
    const T n2 = norm2(n);
    if (n2 > 0) {
        // Inside the prism over the triangle iff p is on the inner side of the three edge planes.
        const T s1 = dot(cross(tri[1] - tri[0], p - tri[0]), n);
        const T s2 = dot(cross(tri[2] - tri[1], p - tri[1]), n);
        const T s3 = dot(cross(tri[0] - tri[2], p - tri[2]), n);
        if (s1 >= 0 && s2 >= 0 && s3 >= 0) {
            const T h = dot(p - tri[0], n) / n2;
            const T d2 = h * h * n2;
            if (d2 < best.d2) best = {d2, p, p - n * h};
        }
    }
    return best;
}

template <class T> Closest<T> segment_segment(const V<T> &p0, const V<T> &p1, const V<T> &q0, const V<T> &q1) {
    // The minimum is at an endpoint of one segment or at the interior critical point.
    Closest<T> best = point_segment(p0, q0, q1);
    Closest<T> c = point_segment(p1, q0, q1);
    if (c.d2 < best.d2) best = c;
    c = point_segment(q0, p0, p1);
    if (c.d2 < best.d2) best = {c.d2, c.q, c.p};
    c = point_segment(q1, p0, p1);
    if (c.d2 < best.d2) best = {c.d2, c.q, c.p};
    const V<T> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const T a = norm2(d1), e = norm2(d2), b = dot(d1, d2), cc = dot(d1, r), f = dot(d2, r);
    const T den = a * e - b * b;
    if (den > 0) {
        const T s = (b * f - cc * e) / den;
        const T t = (a * f - b * cc) / den;
        if (s > 0 && s < 1 && t > 0 && t < 1) {
            const V<T> x = p0 + d1 * s, y = q0 + d2 * t;
            const T dd = norm2(x - y);
            if (dd < best.d2) best = {dd, x, y};
        }
    }
    return best;
}

template <class T> T orient(const V<T> &a, const V<T> &b, const V<T> &c, const V<T> &d) {
    return dot(cross(b - a, c - a), d - a);
}

/// Does segment pq cross triangle tri (endpoints strictly on both sides of its plane, crossing point in
/// the closed triangle)? Writes the crossing point.
template <class T> bool segment_crosses_triangle(const V<T> &p, const V<T> &q, const V<T> *tri, V<T> *x) {
    const T op = orient(tri[0], tri[1], tri[2], p);
    const T oq = orient(tri[0], tri[1], tri[2], q);
    if (!((op > 0 && oq < 0) || (op < 0 && oq > 0))) return false;
    const T s1 = orient(p, q, tri[0], tri[1]);
    const T s2 = orient(p, q, tri[1], tri[2]);
    const T s3 = orient(p, q, tri[2], tri[0]);
    const bool inside = (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
    if (inside) *x = p + (q - p) * (op / (op - oq));
    return inside;
}

template <class T> struct TriTri {
    T dist;   ///< separation distance, 0 if an edge crosses the other triangle
    T depth;  ///< penetration depth estimate (0 unless crossing)
    V<T> pa, pb;  ///< realising points on A and B (the crossing point when crossing)
    bool crossing;
};

template <class T> T sat_depth(const V<T> *a, const V<T> *b) {
    V<T> axes[11];
    int n = 0;
    axes[n++] = cross(a[1] - a[0], a[2] - a[0]);
    axes[n++] = cross(b[1] - b[0], b[2] - b[0]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) axes[n++] = cross(a[(i + 1) % 3] - a[i], b[(j + 1) % 3] - b[j]);
    T depth = -1;
    for (int k = 0; k < n; ++k) {
        const T l2 = norm2(axes[k]);
        if (!(l2 > 0) || !std::isfinite(static_cast<double>(l2))) continue;
        const V<T> u = axes[k] * (T(1) / std::sqrt(l2));
        T amin = dot(u, a[0]), amax = amin, bmin = dot(u, b[0]), bmax = bmin;
        for (int i = 1; i < 3; ++i) {
            const T pa = dot(u, a[i]), pb = dot(u, b[i]);
            amin = std::min(amin, pa);
            amax = std::max(amax, pa);
            bmin = std::min(bmin, pb);
            bmax = std::max(bmax, pb);
        }
        const T ov = std::min(amax - bmin, bmax - amin);
        if (depth < 0 || ov < depth) depth = ov;
    }
    return std::max<T>(T(0), depth);
}

template <class T> TriTri<T> triangle_triangle(const V<T> *a, const V<T> *b) {
    TriTri<T> r{};
    V<T> x{};
    for (int i = 0; i < 3 && !r.crossing; ++i) {
        if (segment_crosses_triangle(a[i], a[(i + 1) % 3], b, &x)) r.crossing = true;
        else if (segment_crosses_triangle(b[i], b[(i + 1) % 3], a, &x)) r.crossing = true;
    }
    if (r.crossing) {
        r.dist = 0;
        r.depth = sat_depth(a, b);
        r.pa = r.pb = x;
        return r;
    }
    Closest<T> best = point_triangle(a[0], b);
    for (int i = 0; i < 3; ++i) {
        Closest<T> c = point_triangle(a[i], b);
        if (c.d2 < best.d2) best = c;
        c = point_triangle(b[i], a);
        if (c.d2 < best.d2) best = {c.d2, c.q, c.p};
        for (int j = 0; j < 3; ++j) {
            c = segment_segment(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
            if (c.d2 < best.d2) best = c;
        }
    }
    r.dist = std::sqrt(best.d2);
    r.depth = 0;
    r.pa = best.p;
    r.pb = best.q;
    return r;
}

}  // namespace bf
