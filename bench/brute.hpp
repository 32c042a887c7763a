// Brute-force referees, used only when the two libraries disagree on a pose.
//
// Written from the definitions, independently of both libraries: the distance between two triangles
// that do not intersect is the least of the 6 vertex-triangle and 9 edge-edge distances; two
// triangles intersect when an edge of one crosses the other. Plain double arithmetic, so a pose whose
// answer hinges on a rounding-level contact is reported as such rather than decided.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "workloads.hpp"

namespace brute {

using V = std::array<double, 3>;

inline V sub(const V& a, const V& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V add(const V& a, const V& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V scale(const V& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V cross(const V& a, const V& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V& a) { return std::sqrt(dot(a, a)); }

inline double point_segment(const V& p, const V& a, const V& b) {
    const V ab = sub(b, a);
    const double len2 = dot(ab, ab);
    double t = len2 > 0.0 ? dot(sub(p, a), ab) / len2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    return norm(sub(p, add(a, scale(ab, t))));
}

inline double point_triangle(const V& p, const V& a, const V& b, const V& c) {
    const V n = cross(sub(b, a), sub(c, a));
    const double n2 = dot(n, n);
    if (n2 > 0.0) {
        const double s1 = dot(n, cross(sub(b, a), sub(p, a)));
        const double s2 = dot(n, cross(sub(c, b), sub(p, b)));
        const double s3 = dot(n, cross(sub(a, c), sub(p, c)));
        if (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) return std::fabs(dot(sub(p, a), n)) / std::sqrt(n2);
    }
    return std::min({point_segment(p, a, b), point_segment(p, b, c), point_segment(p, c, a)});
}

inline double segment_segment(const V& a, const V& b, const V& c, const V& d) {
    double best = std::min({point_segment(a, c, d), point_segment(b, c, d), point_segment(c, a, b),
                            point_segment(d, a, b)});
    // The interior critical point of the line-line problem, when the lines are not parallel.
    const V d1 = sub(b, a), d2 = sub(d, c), r = sub(a, c);
    const double A = dot(d1, d1), E = dot(d2, d2), B = dot(d1, d2), C = dot(d1, r), F = dot(d2, r);
    const double den = A * E - B * B;
    if (den > 1e-24 * A * E) {
        const double s = (B * F - C * E) / den;
        const double t = (A * F - B * C) / den;
        if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)
            best = std::min(best, norm(sub(add(a, scale(d1, s)), add(c, scale(d2, t)))));
    }
    return best;
}

// Whether segment pq meets triangle abc (non-coplanar case; coplanar contact is left to the
// distance test, which then reports ~0).
inline bool segment_hits_triangle(const V& p, const V& q, const V& a, const V& b, const V& c) {
    const V n = cross(sub(b, a), sub(c, a));
    const double op = dot(n, sub(p, a));
    const double oq = dot(n, sub(q, a));
    if ((op > 0.0 && oq > 0.0) || (op < 0.0 && oq < 0.0) || op == oq) return false;
    const V x = add(p, scale(sub(q, p), op / (op - oq)));
    const double s1 = dot(n, cross(sub(b, a), sub(x, a)));
    const double s2 = dot(n, cross(sub(c, b), sub(x, b)));
    const double s3 = dot(n, cross(sub(a, c), sub(x, c)));
    return s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0;
}

struct WTri {
    std::array<V, 3> v;
    V centre;
    double radius;
    int id;
};

inline bool tris_intersect(const WTri& s, const WTri& t) {
    for (int i = 0; i < 3; ++i) {
        if (segment_hits_triangle(s.v[i], s.v[(i + 1) % 3], t.v[0], t.v[1], t.v[2])) return true;
        if (segment_hits_triangle(t.v[i], t.v[(i + 1) % 3], s.v[0], s.v[1], s.v[2])) return true;
    }
    return false;
}

inline double tri_distance(const WTri& s, const WTri& t) {
    if (tris_intersect(s, t)) return 0.0;
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        d = std::min(d, point_triangle(s.v[i], t.v[0], t.v[1], t.v[2]));
        d = std::min(d, point_triangle(t.v[i], s.v[0], s.v[1], s.v[2]));
        for (int j = 0; j < 3; ++j)
            d = std::min(d, segment_segment(s.v[i], s.v[(i + 1) % 3], t.v[j], t.v[(j + 1) % 3]));
    }
    return d;
}

inline std::vector<WTri> place(const bench::Mesh& m, const bench::Pose& p) {
    std::vector<WTri> out;
    out.reserve(m.size());
    for (size_t k = 0; k < m.size(); ++k) {
        WTri w;
        for (int i = 0; i < 3; ++i) {
            const double* x = &m[k][3 * i];
            for (int r = 0; r < 3; ++r)
                w.v[i][r] = p.R[3 * r] * x[0] + p.R[3 * r + 1] * x[1] + p.R[3 * r + 2] * x[2] + p.T[r];
        }
        w.centre = scale(add(add(w.v[0], w.v[1]), w.v[2]), 1.0 / 3.0);
        w.radius = std::max({norm(sub(w.v[0], w.centre)), norm(sub(w.v[1], w.centre)),
                             norm(sub(w.v[2], w.centre))});
        w.id = static_cast<int>(k);
        out.push_back(w);
    }
    return out;
}

// Calls f(s, t) for every triangle pair whose bounding spheres are within `reach` of each other
// (a sweep along x over model 2's sorted centres).
template <class F>
void near_pairs(const std::vector<WTri>& a, std::vector<WTri> b, double reach, F&& f) {
    std::sort(b.begin(), b.end(), [](const WTri& x, const WTri& y) { return x.centre[0] < y.centre[0]; });
    double rmax = 0.0;
    for (const auto& t : b) rmax = std::max(rmax, t.radius);
    for (const auto& s : a) {
        const double lo = s.centre[0] - s.radius - rmax - reach;
        const double hi = s.centre[0] + s.radius + rmax + reach;
        auto it = std::lower_bound(b.begin(), b.end(), lo,
                                   [](const WTri& x, double v) { return x.centre[0] < v; });
        for (; it != b.end() && it->centre[0] <= hi; ++it) {
            if (norm(sub(s.centre, it->centre)) - s.radius - it->radius <= reach) f(s, *it);
        }
    }
}

// The least triangle-pair distance, searched among pairs that could be within `upper` (pass the
// larger of the two disputed answers); +inf if no pair is that close.
inline double mesh_distance(const bench::Mesh& m1, const bench::Pose& p1, const bench::Mesh& m2,
                            const bench::Pose& p2, double upper) {
    const auto a = place(m1, p1), b = place(m2, p2);
    double best = std::numeric_limits<double>::infinity();
    near_pairs(a, b, upper * (1.0 + 1e-9) + 1e-12,
               [&](const WTri& s, const WTri& t) { best = std::min(best, tri_distance(s, t)); });
    return best;
}

// Every intersecting triangle pair, by id, sorted.
inline std::vector<std::pair<int, int>> mesh_contacts(const bench::Mesh& m1, const bench::Pose& p1,
                                                      const bench::Mesh& m2, const bench::Pose& p2) {
    const auto a = place(m1, p1), b = place(m2, p2);
    std::vector<std::pair<int, int>> out;
    near_pairs(a, b, 0.0, [&](const WTri& s, const WTri& t) {
        if (tris_intersect(s, t)) out.emplace_back(s.id, t.id);
    });
    std::sort(out.begin(), out.end());
    return out;
}

// The distance between two particular triangles of the posed meshes (to see how close to a
// touching configuration a disputed contact pair is).
inline double pair_distance(const bench::Mesh& m1, const bench::Pose& p1, int id1, const bench::Mesh& m2,
                            const bench::Pose& p2, int id2) {
    const bench::Mesh one{m1[static_cast<size_t>(id1)]}, two{m2[static_cast<size_t>(id2)]};
    return tri_distance(place(one, p1)[0], place(two, p2)[0]);
}

}  // namespace brute
