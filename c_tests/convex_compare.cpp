// Convex polyhedra (pqp_convex_*) against FCL 0.7 and libccd 2.1, with brute force as the arbiter.
//
// Seeded random hull pairs (4 to 1,000 points; round, thin, flat-ish, needle-like, boxy with exact
// coplanar points) at separated, touching and penetrating poses, some with large offsets. For each
// pair and pose:
//   - distance: ours against FCL's `fcl::Convex<double>` distance (GJK, approximate: compared with a
//     relative tolerance); disagreements are decided by the arbiter;
//   - intersection: ours against ccdGJKIntersect on the same hull vertices (support functions);
//   - penetration depth: ours against ccdGJKPenetration (EPA) and ccdMPRPenetration; ours claims the
//     exact minimum, so it must not exceed theirs (beyond their tolerance) when their translation
//     really separates the hulls;
//   - our own contract, always: the closest points are `distance` apart, lie on the hulls and on the
//     reported features, and the separating slab between them holds every vertex (which certifies
//     the distance exactly, for any hull size); for overlaps the common point is in both hulls and
//     our separating translation separates.
// The arbiter (long double, world coordinates): for small hulls the exact minimum over vertex-face
// and edge-edge pairs, and the exact separating-axis minimum over face normals and edge-edge cross
// products (which is the penetration depth); for large hulls the certificates above.
// Coherent sequences check that warm starts (a pqp_convex_cache) answer as cold starts do.
// A run fails only when we are wrong; peer faults are counted in the summary.
#include <ccd/ccd.h>
#include <ccd/vec3.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "fcl_util.hpp"
#include "harness/harness.hpp"

using namespace ht;

namespace {

// ---------------------------------------------------------------------------------------------------
// Hulls.

struct Hull {
    std::string kind;
    pqp_convex_model *m = nullptr;
    std::vector<double> v;               ///< hull vertices, 3 per vertex (model frame)
    std::vector<std::vector<int>> faces; ///< counter-clockwise from outside
    std::vector<std::pair<int, int>> edges;
    double radius = 0;                   ///< max |vertex|
    std::shared_ptr<fcl::Convexd> fcl;
    Hull() = default;
    Hull(const Hull &) = delete;
    Hull &operator=(const Hull &) = delete;
    ~Hull() { pqp_convex_model_destroy(m); }
    int nv() const { return static_cast<int>(v.size() / 3); }
};

/// Random points of a shape: round (in and on a sphere), thin (a slab), flat-ish (nearly coplanar,
/// with exact coplanar subsets), needle, boxy (grid points of a box: many exactly coplanar), all
/// with duplicates mixed in.
std::vector<double> random_points(Rng &rng, int n, int shape, std::string *kind) {
    static const char *names[] = {"round", "thin", "flatish", "needle", "boxy"};
    *kind = names[shape];
    double ax[3] = {1, 1, 1};
    if (shape == 1) ax[2] = rng.log_uniform(1e-3, 1e-1);
    if (shape == 2) ax[2] = rng.log_uniform(1e-7, 1e-4);
    if (shape == 3) ax[0] = ax[1] = rng.log_uniform(1e-3, 3e-2);
    std::vector<double> p;
    p.reserve(3 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        double x[3];
        if (shape == 4) {
            for (double &c : x) c = (rng.below(5) - 2) * 0.5;
        } else {
            const LV d = rand_dir(rng);
            const double r = rng.uniform() < 0.5 ? 1.0 : std::cbrt(rng.uniform());
            x[0] = static_cast<double>(d.x) * r * ax[0];
            x[1] = static_cast<double>(d.y) * r * ax[1];
            x[2] = static_cast<double>(d.z) * r * ax[2];
            // Flat-ish: a third of the points exactly on the plane z = 0.
            if (shape == 2 && rng.below(3) == 0) x[2] = 0;
        }
        for (double c : x) p.push_back(c);
        if (i > 0 && rng.below(20) == 0) {  // a duplicate of an earlier point
            const int j = rng.below(i);
            for (int k = 0; k < 3; ++k) p.push_back(p[3 * static_cast<size_t>(j) + k]);
            ++i;
        }
    }
    p.resize(3 * static_cast<size_t>(n));
    // Random rotation of the shape in its own frame, so that flat hulls are not axis-aligned.
    double R[9];
    random_rotation(rng, R);
    for (int i = 0; i < n; ++i) {
        double *q = &p[3 * static_cast<size_t>(i)];
        const double a = q[0], b = q[1], c = q[2];
        if (shape != 4)
            for (int r = 0; r < 3; ++r) q[r] = R[3 * r] * a + R[3 * r + 1] * b + R[3 * r + 2] * c;
    }
    return p;
}

/// Builds our model and reads its vertices, faces and edges back through the C API; builds FCL's.
bool make_hull(Report &rep, Rng &rng, int n, int shape, Hull *h) {
    std::vector<double> pts = random_points(rng, n, shape, &h->kind);
    const int rc = pqp_convex_model_from_points(&h->m, pts.data(), n);
    if (rc == PQP_ERR_DEGENERATE_POINTS) return false;  // e.g. 4 coplanar points: fine
    if (!rep.check(rc == PQP_OK && h->m, fmt("hull of %d %s points: rc %d", n, h->kind.c_str(), rc))) return false;
    const int nv = pqp_convex_model_num_vertices(h->m), ne = pqp_convex_model_num_edges(h->m),
              nf = pqp_convex_model_num_faces(h->m);
    rep.check(nv >= 4 && nv - ne + nf == 2, fmt("Euler: V %d E %d F %d", nv, ne, nf));
    h->v.resize(3 * static_cast<size_t>(nv));
    for (int i = 0; i < nv; ++i) pqp_convex_model_vertex(h->m, i, &h->v[3 * static_cast<size_t>(i)]);
    for (int i = 0; i < ne; ++i) {
        int t = 0, hd = 0;
        pqp_convex_model_edge(h->m, i, &t, &hd);
        h->edges.emplace_back(t, hd);
    }
    auto fv = std::make_shared<std::vector<int>>();
    for (int f = 0; f < nf; ++f) {
        std::vector<int> face(static_cast<size_t>(pqp_convex_model_face_num_vertices(h->m, f)));
        pqp_convex_model_face(h->m, f, face.data());
        fv->push_back(static_cast<int>(face.size()));
        for (int x : face) fv->push_back(x);
        h->faces.push_back(face);
    }
    for (int i = 0; i < nv; ++i) {
        const double *q = &h->v[3 * static_cast<size_t>(i)];
        h->radius = std::max(h->radius, std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
    }
    // Every input point is inside the hull (exact hull: within rounding of the face planes).
    auto fverts = std::make_shared<std::vector<fcl::Vector3d>>();
    for (int i = 0; i < nv; ++i) fverts->emplace_back(h->v[3 * i], h->v[3 * i + 1], h->v[3 * i + 2]);
    h->fcl = std::make_shared<fcl::Convexd>(fverts, nf, fv);
    return true;
}

// ---------------------------------------------------------------------------------------------------
// World coordinates in long double, and the arbiter.

struct WHull {
    std::vector<LV> v;
    const Hull *h;
};

WHull world_hull(const Hull &h, const Pose &p) {
    WHull w{{}, &h};
    for (int i = 0; i < h.nv(); ++i) w.v.push_back(to_world(p.R, p.T, &h.v[3 * static_cast<size_t>(i)]));
    return w;
}

// Vector algebra and the point-segment and segment-segment distances are the harness's (bf.hpp).
using bf::cross;
using bf::dot;
L norml(const LV &a) { return std::sqrt(bf::norm2(a)); }
L point_segment(const LV &p, const LV &a, const LV &b) { return std::sqrt(bf::point_segment(p, a, b).d2); }
L segment_segment(const LV &p0, const LV &p1, const LV &q0, const LV &q1) {
    return std::sqrt(bf::segment_segment(p0, p1, q0, q1).d2);
}
LV scaled_by(const LV &a, L s) { return LV{a.x * s, a.y * s, a.z * s}; }
LV neg(const LV &a) { return LV{-a.x, -a.y, -a.z}; }

/// Unit outward normal of face f.
LV face_normal(const WHull &w, int f) {
    const std::vector<int> &fc = w.h->faces[static_cast<size_t>(f)];
    LV n{0, 0, 0};
    for (size_t k = 0; k < fc.size(); ++k) {
        const LV &a = w.v[static_cast<size_t>(fc[k])], &b = w.v[static_cast<size_t>(fc[(k + 1) % fc.size()])];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return scaled_by(n, 1 / norml(n));
}

L point_face(const WHull &w, int f, const LV &p) {
    const std::vector<int> &fc = w.h->faces[static_cast<size_t>(f)];
    const LV n = face_normal(w, f);
    bool inside = true;
    for (size_t k = 0; k < fc.size() && inside; ++k) {
        const LV &a = w.v[static_cast<size_t>(fc[k])], &b = w.v[static_cast<size_t>(fc[(k + 1) % fc.size()])];
        if (dot(cross((b - a), (p - a)), n) < 0) inside = false;
    }
    if (inside) return std::fabs(dot((p - w.v[static_cast<size_t>(fc[0])]), n));
    L best = INFINITY;
    for (size_t k = 0; k < fc.size(); ++k)
        best = std::min(best, point_segment(p, w.v[static_cast<size_t>(fc[k])],
                                            w.v[static_cast<size_t>(fc[(k + 1) % fc.size()])]));
    return best;
}

/// max_a u.a - min_b u.b: how far B must move along u to clear A (<= 0: u separates them).
L overlap_along(const WHull &A, const WHull &B, const LV &u) {
    L hi = -INFINITY, lo = INFINITY;
    for (const LV &a : A.v) hi = std::max(hi, dot(u, a));
    for (const LV &b : B.v) lo = std::min(lo, dot(u, b));
    return hi - lo;
}

struct Brute {
    L sat;   ///< min over candidate axes of overlap_along: > 0 the penetration depth, < 0 separated
    L dist;  ///< exact distance (when separated)
};

/// Exact (in long double) separating-axis minimum and distance of two hulls.
Brute brute(const WHull &A, const WHull &B) {
    Brute r{INFINITY, INFINITY};
    auto axis = [&](const LV &u) {
        r.sat = std::min(r.sat, overlap_along(A, B, u));
        r.sat = std::min(r.sat, overlap_along(A, B, neg(u)));
    };
    for (size_t f = 0; f < A.h->faces.size(); ++f) axis(face_normal(A, static_cast<int>(f)));
    for (size_t f = 0; f < B.h->faces.size(); ++f) axis(face_normal(B, static_cast<int>(f)));
    for (const auto &ea : A.h->edges)
        for (const auto &eb : B.h->edges) {
            const LV c = cross((A.v[static_cast<size_t>(ea.second)] - A.v[static_cast<size_t>(ea.first)]),
                                (B.v[static_cast<size_t>(eb.second)] - B.v[static_cast<size_t>(eb.first)]));
            const L l = norml(c);
            if (l > 1e-30L) axis(scaled_by(c, 1 / l));
        }
    if (r.sat > 0) {
        r.dist = 0;
        return r;
    }
    for (size_t f = 0; f < B.h->faces.size(); ++f)
        for (const LV &a : A.v) r.dist = std::min(r.dist, point_face(B, static_cast<int>(f), a));
    for (size_t f = 0; f < A.h->faces.size(); ++f)
        for (const LV &b : B.v) r.dist = std::min(r.dist, point_face(A, static_cast<int>(f), b));
    for (const auto &ea : A.h->edges)
        for (const auto &eb : B.h->edges)
            r.dist = std::min(r.dist, segment_segment(A.v[static_cast<size_t>(ea.first)], A.v[static_cast<size_t>(ea.second)],
                                                      B.v[static_cast<size_t>(eb.first)], B.v[static_cast<size_t>(eb.second)]));
    return r;
}

/// How far p is outside the hull (max over face planes; <= 0 inside).
L outside(const WHull &w, const LV &p) {
    L m = -INFINITY;
    for (size_t f = 0; f < w.h->faces.size(); ++f) {
        const LV n = face_normal(w, static_cast<int>(f));
        m = std::max(m, dot((p - w.v[static_cast<size_t>(w.h->faces[f][0])]), n));
    }
    return m;
}

/// Distance of p (world) from a feature of the hull.
L from_feature(const WHull &w, int kind, int index, const LV &p) {
    const Hull &h = *w.h;
    if (kind == PQP_CONVEX_VERTEX && index >= 0 && index < h.nv()) return norml((p - w.v[static_cast<size_t>(index)]));
    if (kind == PQP_CONVEX_EDGE && index >= 0 && index < static_cast<int>(h.edges.size())) {
        const auto &e = h.edges[static_cast<size_t>(index)];
        return point_segment(p, w.v[static_cast<size_t>(e.first)], w.v[static_cast<size_t>(e.second)]);
    }
    if (kind == PQP_CONVEX_FACE && index >= 0 && index < static_cast<int>(h.faces.size())) return point_face(w, index, p);
    return INFINITY;
}

// ---------------------------------------------------------------------------------------------------
// Peers.

struct CcdHull {
    std::vector<ccd_vec3_t> v;
    ccd_vec3_t c;
};

CcdHull ccd_hull(const Hull &h, const Pose &p) {
    CcdHull out;
    L cx = 0, cy = 0, cz = 0;
    for (int i = 0; i < h.nv(); ++i) {
        const double *x = &h.v[3 * static_cast<size_t>(i)];
        double w[3];
        for (int r = 0; r < 3; ++r) w[r] = p.R[3 * r] * x[0] + p.R[3 * r + 1] * x[1] + p.R[3 * r + 2] * x[2] + p.T[r];
        ccd_vec3_t q;
        ccdVec3Set(&q, w[0], w[1], w[2]);
        out.v.push_back(q);
        cx += w[0], cy += w[1], cz += w[2];
    }
    const L n = h.nv();
    ccdVec3Set(&out.c, static_cast<double>(cx / n), static_cast<double>(cy / n), static_cast<double>(cz / n));
    return out;
}

void hull_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out) {
    const CcdHull *h = static_cast<const CcdHull *>(obj);
    size_t best = 0;
    double bd = ccdVec3Dot(&h->v[0], dir);
    for (size_t k = 1; k < h->v.size(); ++k) {
        const double d = ccdVec3Dot(&h->v[k], dir);
        if (d > bd) bd = d, best = k;
    }
    ccdVec3Copy(out, &h->v[best]);
}

void hull_center(const void *obj, ccd_vec3_t *out) { ccdVec3Copy(out, &static_cast<const CcdHull *>(obj)->c); }

ccd_t ccd_setup() {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = hull_support;
    ccd.support2 = hull_support;
    ccd.center1 = hull_center;
    ccd.center2 = hull_center;
    ccd.max_iterations = 500;  // libccd's default is unbounded
    return ccd;
}

fcl::Transform3d fcl_tf(const Pose &p) { return fclu::transform(p.R, p.T); }

double fcl_distance(const Hull &a, const Pose &pa, const Hull &b, const Pose &pb) {
    fcl::CollisionObjectd oa(a.fcl, fcl_tf(pa)), ob(b.fcl, fcl_tf(pb));
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(&oa, &ob, req, res);
    return res.min_distance;
}

// ---------------------------------------------------------------------------------------------------
// Our answers.

struct Ours {
    int rc;
    double d;
    int inter;
    LV w1, w2;  ///< world closest points
    int k1, i1, k2, i2;
};

Ours our_distance(pqp_convex_result *r, const Hull &a, const Pose &pa, const Hull &b, const Pose &pb,
                  pqp_convex_cache *cache) {
    Ours o{};
    o.rc = pqp_convex_distance(r, pa.R, pa.T, a.m, pb.R, pb.T, b.m, cache);
    o.d = pqp_convex_result_distance(r);
    o.inter = pqp_convex_result_intersecting(r);
    o.w1 = to_world(pa.R, pa.T, pqp_convex_result_p1(r));
    o.w2 = to_world(pb.R, pb.T, pqp_convex_result_p2(r));
    o.k1 = pqp_convex_result_feature1_kind(r), o.i1 = pqp_convex_result_feature1_index(r);
    o.k2 = pqp_convex_result_feature2_kind(r), o.i2 = pqp_convex_result_feature2_index(r);
    return o;
}

struct Ctx {
    Options opt;
    Report rep{"convex_compare"};
    Rng rng{1};
    pqp_convex_result *res = pqp_convex_result_create();
    ccd_t ccd = ccd_setup();
    ~Ctx() { pqp_convex_result_destroy(res); }
};

// The band of rounding: posing in double and the hulls' size.
double band_of(const Hull &a, const Pose &pa, const Hull &b, const Pose &pb) {
    double s = 1;
    for (int k = 0; k < 3; ++k) s = std::max({s, std::fabs(pa.T[k]) + a.radius, std::fabs(pb.T[k]) + b.radius});
    return 1e-12 * s;
}

/// Our own contract at one pose; returns our answer.
Ours check_ours(Ctx &c, const Hull &a, const Pose &pa, const Hull &b, const Pose &pb, const WHull &A,
                const WHull &B, double band) {
    Report &rep = c.rep;
    Ours o = our_distance(c.res, a, pa, b, pb, nullptr);
    rep.check(o.rc == PQP_OK, fmt("pqp_convex_distance rc %d", o.rc));
    const L gap = norml((o.w2 - o.w1));
    if (!o.inter) {
        rep.check(o.d > 0 && std::fabs(static_cast<double>(gap) - o.d) <= 1e-9 * o.d + band,
                  fmt("closest points %.17Lg apart, distance %.17g", gap, o.d));
        rep.check(std::fabs(static_cast<double>(outside(A, o.w1))) <= band &&
                      std::fabs(static_cast<double>(outside(B, o.w2))) <= band,
                  "closest points on the hulls");
        rep.check(from_feature(A, o.k1, o.i1, o.w1) <= band && from_feature(B, o.k2, o.i2, o.w2) <= band,
                  fmt("closest points on the features (%d %d, %d %d): %.3Lg %.3Lg", o.k1, o.i1, o.k2, o.i2,
                      from_feature(A, o.k1, o.i1, o.w1), from_feature(B, o.k2, o.i2, o.w2)));
        // The slab between the closest points holds every vertex: the distance is certified.
        if (gap > 0) {
            const LV u = scaled_by(o.w2 - o.w1, 1 / gap);
            const L lower = -overlap_along(A, B, u);
            // The witnesses carry rounding of about 1e-3 * band each, which tilts the slab by that
            // over the gap: over the hulls' extent that moves the bound by up to `tilt`.
            const double tilt = 1e-3 * band * 2 * (a.radius + b.radius) / static_cast<double>(gap);
            rep.check(lower >= static_cast<L>(o.d) - (1e-9 * o.d + band + tilt),
                      fmt("separating slab certifies %.17Lg, distance %.17g", lower, o.d));
        }
    } else {
        rep.check(o.d == 0, fmt("intersecting with distance %.17g", o.d));
        rep.check(gap <= band && outside(A, o.w1) <= band && outside(B, o.w1) <= band,
                  fmt("common point in both hulls: outside %.3Lg %.3Lg", outside(A, o.w1), outside(B, o.w1)));
    }
    return o;
}

struct Stats {
    long poses = 0, brute = 0, fcl = 0, ccd_int = 0, ccd_pen = 0, mpr_pen = 0, warm = 0;
};

/// Every comparison at one pose.
void compare_pose(Ctx &c, Stats &st, const Hull &a, const Pose &pa, const Hull &b, const Pose &pb, bool small) {
    Report &rep = c.rep;
    ++st.poses;
    const double band = band_of(a, pa, b, pb);
    const WHull A = world_hull(a, pa), B = world_hull(b, pb);
    const Ours o = check_ours(c, a, pa, b, pb, A, B, band);
    if (o.rc != PQP_OK) return;
    const double d = o.d;
    const double size = std::max(a.radius, b.radius);

    // Brute force on small hulls (always), and on demand.
    bool have_brute = false;
    Brute bf{0, 0};
    auto arbiter = [&]() -> const Brute & {
        if (!have_brute) bf = brute(A, B), have_brute = true, ++st.brute;
        return bf;
    };
    if (small) {
        const Brute &t = arbiter();
        if (t.sat < -band) {
            rep.check(!o.inter && std::fabs(static_cast<L>(d) - t.dist) <= 1e-9L * t.dist + band,
                      fmt("brute force: separated at %.17Lg, ours %.17g (inter %d)", t.dist, d, o.inter));
        } else if (t.sat > band) {
            rep.check(o.inter == 1, fmt("brute force: overlap %.3Lg, ours apart at %.17g", t.sat, d));
        }
    }

    // FCL distance (it answers a negative or zero value for overlapping shapes).
    const double fd = fcl_distance(a, pa, b, pb);
    if (!o.inter && fd > 0) {
        ++st.fcl;
        const double tol = 1e-6 * size + 1e-5 * d + band;
        if (std::fabs(fd - d) > tol) {
            const bool can = small || static_cast<double>(A.v.size()) * static_cast<double>(B.v.size()) <= 4e4;
            if (can) {
                const L t = arbiter().dist;
                const bool we = std::fabs(static_cast<L>(d) - t) > 1e-9L * t + band;
                rep.disagreement("FCL", fd > d ? "distance too large" : "distance too small", we,
                                 fmt("ours %.17g fcl %.17g brute %.17Lg", d, fd, t));
            } else {
                // Our distance is certified by check_ours (slab + points on the hulls).
                rep.disagreement("FCL", fd > d ? "distance too large (certificate)" : "distance too small (certificate)",
                                 false, fmt("ours %.17g fcl %.17g", d, fd));
            }
        }
    }

    // libccd intersection.
    CcdHull ca = ccd_hull(a, pa), cb = ccd_hull(b, pb);
    const int gi = ccdGJKIntersect(&ca, &cb, &c.ccd);
    ++st.ccd_int;
    if (gi != o.inter && !(o.inter ? false : d <= 1e-9 * size + band)) {
        const bool can = small || static_cast<double>(a.edges.size()) * static_cast<double>(b.edges.size()) <= 2e4;
        if (can) {
            const L s = arbiter().sat;
            const bool border = std::fabs(s) <= band;
            const bool we = !border && ((s > 0) != (o.inter == 1));
            rep.disagreement("libccd GJK", gi ? "says intersecting" : "says separate", we,
                             fmt("ours %d (d %.3g), sat %.3Lg", o.inter, d, s));
        } else {
            rep.disagreement("libccd GJK", std::string(gi ? "says intersecting" : "says separate") + " (certificate)",
                             false, fmt("ours %d (d %.3g)", o.inter, d));
        }
    }

    // Penetration depth.
    const int prc = pqp_convex_penetration(c.res, pa.R, pa.T, a.m, pb.R, pb.T, b.m, nullptr);
    rep.check(prc == PQP_OK, fmt("pqp_convex_penetration rc %d", prc));
    if (prc != PQP_OK || !o.inter) return;
    const double depth = pqp_convex_result_depth(c.res);
    const double *n = pqp_convex_result_normal(c.res);
    const LV un{n[0], n[1], n[2]};
    // Our translation separates: B moved by depth along n clears A.
    const L need = overlap_along(A, B, un);
    rep.check(depth >= 0 && need <= static_cast<L>(depth) + 1e-9L * depth + band,
              fmt("our translation (depth %.17g) leaves overlap %.17Lg", depth, need));
    {
        const LV q1 = to_world(pa.R, pa.T, pqp_convex_result_deepest_p1(c.res));
        const LV q2 = to_world(pb.R, pb.T, pqp_convex_result_deepest_p2(c.res));
        const LV e = q1 - q2 - scaled_by(un, static_cast<L>(depth));
        rep.check(norml(e) <= 1e-9 * depth + band * 10 && std::fabs(static_cast<double>(outside(A, q1))) <= band * 10,
                  fmt("deepest points: residual %.3Lg", norml(e)));
    }
    if (small) {
        const L t = arbiter().sat;
        if (t > band) rep.check(std::fabs(static_cast<L>(depth) - t) <= 1e-9L * t + band,
                                fmt("depth %.17g, brute force %.17Lg", depth, t));
    }
    if (depth <= 1e-9 * size + band) return;  // touching: the peers' penetration is not defined
    auto peer = [&](const char *name, bool mpr, long &counter) {
        ccd_real_t pd = 0;
        ccd_vec3_t dir, pos;
        const int rc = mpr ? ccdMPRPenetration(&ca, &cb, &c.ccd, &pd, &dir, &pos)
                           : ccdGJKPenetration(&ca, &cb, &c.ccd, &pd, &dir, &pos);
        if (rc != 0) {
            rep.disagreement(name, "no answer for overlapping hulls", false, fmt("rc %d, our depth %.3g", rc, depth));
            return;
        }
        ++counter;
        const double tol = 1e-4 * size + 1e-3 * pd + band;  // libccd's epa/mpr tolerance is 1e-4
        // Ours claims the minimum: theirs may be larger (MPR is an upper bound), not smaller.
        if (depth > pd + tol) {
            // Does their translation separate? Along +-dir, B must move by overlap_along.
            const LV u{ccdVec3X(&dir), ccdVec3Y(&dir), ccdVec3Z(&dir)};
            const L lu = norml(u);
            L need_theirs = INFINITY;
            if (lu > 0) {
                const LV v = scaled_by(u, 1 / lu);
                need_theirs = std::min(overlap_along(A, B, v), overlap_along(A, B, neg(v)));
            }
            const bool separates = need_theirs <= static_cast<L>(pd) + tol;
            const bool we = separates && static_cast<L>(depth) > need_theirs + 1e-9L * depth + band;
            std::string cat = separates ? "smaller depth" : "smaller depth, but its translation does not separate";
            if (small) cat += " (ours equals brute force)";
            rep.disagreement(name, cat, we, fmt("ours %.17g theirs %.17g (their direction needs %.17Lg)", depth, pd, need_theirs));
        } else if (pd > depth + tol) {
            rep.count(std::string(name) + ": depth larger than ours (not minimal)");
        }
    };
    peer("libccd EPA", false, st.ccd_pen);
    peer("libccd MPR", true, st.mpr_pen);
}

Pose pose_at(const double R[9], double x, double y, double z) {
    Pose p;
    std::copy(R, R + 9, p.R);
    p.T[0] = x, p.T[1] = y, p.T[2] = z;
    return p;
}

/// Random poses of one hull pair: separated, touching (moved along our closest-point direction to
/// a tiny gap or overlap), penetrating; a third offset far from the origin.
void pair_poses(Ctx &c, Stats &st, const Hull &a, const Hull &b, bool small) {
    Rng &rng = c.rng;
    for (int rep = 0; rep < 4; ++rep) {
        Pose pa, pb;
        random_rotation(rng, pa.R);
        random_rotation(rng, pb.R);
        const LV u = rand_dir(rng);
        const double rr = a.radius + b.radius;
        const int type = rep;  // 0 separated, 1 touching, 2 penetrating, 3 deep / near
        double k = type == 0 ? rng.uniform(1.02, 2.5) : type == 2 ? rng.uniform(0.3, 0.95) : rng.uniform(0.0, 0.3);
        double off[3] = {0, 0, 0};
        if (rng.below(3) == 0) {
            const double m = std::pow(10.0, rng.uniform(0, 5));
            for (double &x : off) x = m * rng.uniform(-1, 1);
        }
        for (int i = 0; i < 3; ++i) {
            pa.T[i] = off[i];
            pb.T[i] = off[i] + static_cast<double>(i == 0 ? u.x : i == 1 ? u.y : u.z) * rr * k;
        }
        if (type == 1) {
            // Apart first, then moved along our closest direction to a gap in {0, +-1e-12..1e-3}.
            pb.T[0] = off[0] + static_cast<double>(u.x) * rr * 1.5;
            pb.T[1] = off[1] + static_cast<double>(u.y) * rr * 1.5;
            pb.T[2] = off[2] + static_cast<double>(u.z) * rr * 1.5;
            Ours o = our_distance(c.res, a, pa, b, pb, nullptr);
            if (o.rc != PQP_OK || o.inter) continue;
            const L g = norml((o.w2 - o.w1));
            double gap = 0;
            if (rng.below(3)) gap = (rng.below(2) ? 1 : -1) * std::pow(10.0, rng.uniform(-12, -3));
            const double move = static_cast<double>(g) - gap;
            const LV dir = scaled_by(o.w2 - o.w1, 1 / g);
            pb.T[0] -= static_cast<double>(dir.x) * move;
            pb.T[1] -= static_cast<double>(dir.y) * move;
            pb.T[2] -= static_cast<double>(dir.z) * move;
        }
        c.rep.set_context(fmt("%s %d vs %s %d, pose %d", a.kind.c_str(), a.nv(), b.kind.c_str(), b.nv(), type),
                          type == 0 ? "separated" : type == 1 ? "touching" : "penetrating");
        compare_pose(c, st, a, pa, b, pb, small);
    }
}

/// A coherent path: b circles a and turns a little each frame, in and out of contact; warm (one
/// cache) against cold answers.
void coherent(Ctx &c, Stats &st, const Hull &a, const Hull &b, int frames) {
    Report &rep = c.rep;
    pqp_convex_cache *cache = pqp_convex_cache_create();
    pqp_convex_result *cold = pqp_convex_result_create();
    Pose pa;
    random_rotation(c.rng, pa.R);
    pa.T[0] = pa.T[1] = pa.T[2] = 0;
    double R0[9];
    random_rotation(c.rng, R0);
    const double rr = a.radius + b.radius;
    rep.set_context(fmt("coherent %s %d vs %s %d", a.kind.c_str(), a.nv(), b.kind.c_str(), b.nv()), "coherent");
    for (int f = 0; f < frames; ++f) {
        const double t = 0.01 * f;
        const double ct = std::cos(t * 3), s = std::sin(t * 3);
        // Turn about z by 3t, then R0.
        double Rz[9] = {ct, -s, 0, s, ct, 0, 0, 0, 1}, R[9];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) R[3 * i + j] = Rz[3 * i] * R0[j] + Rz[3 * i + 1] * R0[3 + j] + Rz[3 * i + 2] * R0[6 + j];
        const double r = rr * (0.8 + 0.5 * std::cos(t * 2));
        const Pose pb = pose_at(R, r * std::cos(t), r * std::sin(t), 0.1 * rr * std::sin(t * 5));
        const Ours w = our_distance(c.res, a, pa, b, pb, cache);
        const Ours k = our_distance(cold, a, pa, b, pb, nullptr);
        ++st.warm;
        const double band = band_of(a, pa, b, pb);
        const bool border = !w.inter != !k.inter && std::max(w.d, k.d) <= band;
        rep.check(w.rc == PQP_OK && (border || (w.inter == k.inter && std::fabs(w.d - k.d) <= 1e-9 * k.d + band)),
                  fmt("frame %d: warm %.17g (%d), cold %.17g (%d)", f, w.d, w.inter, k.d, k.inter));
    }
    pqp_convex_result_destroy(cold);
    pqp_convex_cache_destroy(cache);
}

int vertex_count(Rng &rng) {
    // Mostly small (the arbiter's range), some large, a few up to 1000.
    const int r = rng.below(10);
    if (r < 6) return 4 + rng.below(30);
    if (r < 9) return static_cast<int>(rng.log_uniform(34, 300));
    return static_cast<int>(rng.log_uniform(300, 1000));
}

}  // namespace

int main(int argc, char **argv) {
    const auto t0 = std::chrono::steady_clock::now();
    Ctx c;
    c.opt = parse_options(argc, argv);
    c.rng = Rng(c.opt.seed);
    Stats st;
    const int pairs = scaled(c.opt, 1500);
    long built = 0, degenerate = 0;
    for (int p = 0; p < pairs; ++p) {
        Hull a, b;
        const int na = vertex_count(c.rng), nb = vertex_count(c.rng);
        c.rep.set_context(fmt("pair %d", p));
        if (!make_hull(c.rep, c.rng, na, c.rng.below(5), &a) || !make_hull(c.rep, c.rng, nb, c.rng.below(5), &b)) {
            ++degenerate;
            continue;
        }
        ++built;
        const bool small = a.nv() <= 40 && b.nv() <= 40;
        pair_poses(c, st, a, b, small);
        if (p % 10 == 0) coherent(c, st, a, b, 150);
    }
    c.rep.count("hull pairs built", built);
    c.rep.count("hull pairs skipped (degenerate point set, refused as documented)", degenerate);
    c.rep.count("poses compared", st.poses);
    c.rep.count("poses decided by brute force (long double)", st.brute);
    c.rep.count("FCL Convex distance comparisons (separated)", st.fcl);
    c.rep.count("libccd GJK intersection comparisons", st.ccd_int);
    c.rep.count("libccd EPA penetration comparisons", st.ccd_pen);
    c.rep.count("libccd MPR penetration comparisons", st.mpr_pen);
    c.rep.count("coherent frames, warm vs cold", st.warm);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return c.rep.finish(secs);
}
