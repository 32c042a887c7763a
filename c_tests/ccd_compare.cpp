// Triangle-level narrow phase of our library against libccd 2.1 (double precision):
//  - every pair we report as colliding must intersect by libccd's GJK (ccdGJKIntersect) on the two
//    triangles as convex shapes given by support functions;
//  - close pairs (boxes overlapping) that we do not report must not intersect by libccd;
//  - the triangle pair of our distance answer must be as far apart as we say, by libccd's point-triangle
//    and point-segment distances (with our own long double segment-segment for the edge pairs);
//  - on small meshes, our distance must equal the minimum of those libccd pair distances over all pairs,
//    and the tolerance verdict must agree with it.
// Disagreements are decided by brute force in long double; the run fails only when we are wrong.
#include <ccd/ccd.h>
#include <ccd/vec3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "harness/harness.hpp"

static_assert(sizeof(ccd_real_t) == sizeof(double), "libccd must be built with CCD_DOUBLE");

using namespace ht;

namespace {

struct CcdTri {
    ccd_vec3_t v[3];
};

void tri_support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out) {
    const CcdTri *t = static_cast<const CcdTri *>(obj);
    int best = 0;
    double bd = ccdVec3Dot(&t->v[0], dir);
    for (int k = 1; k < 3; ++k) {
        const double d = ccdVec3Dot(&t->v[k], dir);
        if (d > bd) {
            bd = d;
            best = k;
        }
    }
    ccdVec3Copy(out, &t->v[best]);
}

/// World triangles in double, as a C user of libccd would hold them.
std::vector<CcdTri> ccd_world(const Mesh &m, const Pose &p) {
    std::vector<CcdTri> out(m.tris.size());
    for (size_t i = 0; i < m.tris.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double *x = m.tris[i].p[k];
            double w[3];
            for (int r = 0; r < 3; ++r) w[r] = p.R[3 * r] * x[0] + p.R[3 * r + 1] * x[1] + p.R[3 * r + 2] * x[2] + p.T[r];
            ccdVec3Set(&out[i].v[k], w[0], w[1], w[2]);
        }
    return out;
}

bool gjk_intersect(const CcdTri &a, const CcdTri &b) {
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = tri_support;
    ccd.support2 = tri_support;
    ccd.max_iterations = 500;  // the default is unbounded
    return ccdGJKIntersect(&a, &b, &ccd) != 0;
}

double point_segment2(const ccd_vec3_t *p, const ccd_vec3_t *a, const ccd_vec3_t *b) {
    if (ccdVec3Eq(a, b)) return ccdVec3Dist2(p, a);
    return ccdVec3PointSegmentDist2(p, a, b, nullptr);
}

/// Squared distance from p to triangle t by libccd (its point-segment helper for degenerate triangles).
double point_tri2(const ccd_vec3_t *p, const CcdTri &t) {
    ccd_vec3_t e1, e2, n;
    ccdVec3Sub2(&e1, &t.v[1], &t.v[0]);
    ccdVec3Sub2(&e2, &t.v[2], &t.v[0]);
    ccdVec3Cross(&n, &e1, &e2);
    const double scale = std::max({ccdVec3Len2(&e1), ccdVec3Len2(&e2), 1e-300});
    if (ccdVec3Len2(&n) > 1e-20 * scale * scale) return ccdVec3PointTriDist2(p, &t.v[0], &t.v[1], &t.v[2], nullptr);
    return std::min({point_segment2(p, &t.v[0], &t.v[1]), point_segment2(p, &t.v[1], &t.v[2]),
                     point_segment2(p, &t.v[2], &t.v[0])});
}

LV lv(const ccd_vec3_t &v) { return {ccdVec3X(&v), ccdVec3Y(&v), ccdVec3Z(&v)}; }

/// Distance between two triangles by libccd: 0 if GJK says they intersect, else the minimum of the 6
/// vertex-triangle distances (libccd) and the 9 edge-edge distances (long double, libccd has none).
double ccd_pair_distance(const CcdTri &a, const CcdTri &b) {
    if (gjk_intersect(a, b)) return 0;
    double d2 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
        d2 = std::min(d2, point_tri2(&a.v[k], b));
        d2 = std::min(d2, point_tri2(&b.v[k], a));
        for (int l = 0; l < 3; ++l) {
            const bf::Closest<L> c =
                bf::segment_segment(lv(a.v[k]), lv(a.v[(k + 1) % 3]), lv(b.v[l]), lv(b.v[(l + 1) % 3]));
            d2 = std::min(d2, static_cast<double>(c.d2));
        }
    }
    return std::sqrt(d2);
}

struct Workload {
    std::string name;
    Mesh a, b;
    int poses;
    bool global_distance;  ///< minimum over all pairs by libccd (small meshes only)
    std::vector<PosePair> fixed;
    bool contact = false;  ///< a is the box [-1,1]^3: b rests on its top face (contact_pair)
};

std::string pair_str(int i, int j) { return fmt("(%d,%d)", i, j); }

struct Ctx {
    Options opt;
    Report rep{"ccd_compare"};
    Rng rng{0};
};

void compare_pose(Ctx &c, const Workload &w, const OurModel &oa, const OurModel &ob, const PosePair &pp, int index) {
    Report &rep = c.rep;
    rep.set_context(fmt("%s pose %d: %s", w.name.c_str(), index, pp.kind.c_str()), pose_class(pp));
    rep.count("ccd: poses compared");
    const int na = int(w.a.tris.size()), nb = int(w.b.tris.size());
    const World WA = to_world(w.a, pp.a), WB = to_world(w.b, pp.b);
    const std::vector<CcdTri> CA = ccd_world(w.a, pp.a), CB = ccd_world(w.b, pp.b);
    const double band = band_for(WA, WB);

    // ---- collision (fresh result objects: create/destroy in the loop)
    pqp_collide_result *cr = pqp_collide_result_create();
    const CollideOut oc = our_collide(cr, pp, oa, ob, PQP_ALL_CONTACTS);
    pqp_collide_result_destroy(cr);
    if (!rep.check(oc.rc == PQP_OK, fmt("collide rc %d", oc.rc))) return;
    std::set<std::pair<int, int>> S;
    bool ids_ok = true;
    for (const auto &p : oc.pairs) {
        if (p.first < 0 || p.first >= na || p.second < 0 || p.second >= nb || !S.insert(p).second) ids_ok = false;
    }
    if (!rep.check(ids_ok, "collide: invalid or duplicate pair ids")) return;
    auto decide = [&](int i, int j, bool we_report, bool ccd_says) {
        const PairTruth t = pair_truth(WA, i, WB, j, band, pp.exact);
        const std::string d = fmt("pair %s: we %s, libccd GJK %s; brute force %s (distance %.3Lg, depth %.3Lg, band "
                                  "%.2g); %s",
                                  pair_str(i, j).c_str(), we_report ? "report" : "do not report",
                                  ccd_says ? "intersects" : "separate", truth_name(t.truth), t.dist, t.depth, band,
                                  pose_str(pp).c_str());
        if (t.truth == Truth::Borderline)
            rep.disagreement("libccd", we_report ? "collide: borderline pair only we report"
                                                 : "collide: borderline pair only libccd reports",
                             false, d);
        else if ((t.truth == Truth::Intersecting) == we_report)
            rep.disagreement("libccd", we_report ? "collide: GJK misses an intersecting pair"
                                                 : "collide: GJK intersects a separated pair",
                             false, d);
        else
            rep.disagreement("libccd", we_report ? "collide: we report a separated pair"
                                                 : "collide: we miss an intersecting pair",
                             true, d);
    };
    std::set<std::pair<int, int>> seen;
    box_pairs(WA, WB, band, [&](int i, int j) {
        seen.emplace(i, j);
        rep.count("ccd: close triangle pairs compared (GJK)");
        const bool ours = S.count({i, j}) != 0;
        const bool ccd = gjk_intersect(CA[size_t(i)], CB[size_t(j)]);
        if (ours != ccd) decide(i, j, ours, ccd);
    });
    for (const auto &p : S)  // reported pairs whose boxes are not even close
        if (!seen.count(p)) {
            rep.count("ccd: close triangle pairs compared (GJK)");
            const bool ccd = gjk_intersect(CA[size_t(p.first)], CB[size_t(p.second)]);
            if (!ccd) decide(p.first, p.second, true, ccd);
        }

    // ---- distance: the reported pair by libccd, and on small meshes the minimum over all pairs
    pqp_distance_result *dr = pqp_distance_result_create();
    const DistanceOut od = our_distance(dr, pp, oa, ob, 0, 0, 2);
    pqp_distance_result_destroy(dr);
    if (!rep.check(od.rc == PQP_OK, fmt("distance rc %d", od.rc))) return;
    if (!rep.check(od.id1 >= 0 && od.id1 < na && od.id2 >= 0 && od.id2 < nb && std::isfinite(od.d),
                   fmt("distance: ids (%d,%d), distance %.17g", od.id1, od.id2, od.d)))
        return;
    rep.count("ccd: distance answers checked (reported pair)");
    const double cp = ccd_pair_distance(CA[size_t(od.id1)], CB[size_t(od.id2)]);
    if (std::fabs(cp - od.d) > dist_tol(std::max(cp, od.d), band)) {
        const PairTruth t = pair_truth(WA, od.id1, WB, od.id2, band, pp.exact);
        const double tr = static_cast<double>(t.dist);
        const bool ours_ok = std::fabs(od.d - tr) <= dist_tol(tr, band);
        rep.disagreement("libccd", ours_ok ? "distance of the reported pair: libccd off" : "distance of the reported pair",
                         !ours_ok,
                         fmt("pair %s: ours %.17g, libccd %.17g, brute force %.17g; %s",
                             pair_str(od.id1, od.id2).c_str(), od.d, cp, tr, pose_str(pp).c_str()));
    }
    if (!w.global_distance) return;

    // Minimum over all pairs of the libccd pair distances, pruned by boxes.
    double best = ccd_pair_distance(CA[size_t(od.id1)], CB[size_t(od.id2)]);
    struct Cand {
        L box;
        int i, j;
    };
    std::vector<Cand> cands;
    box_pairs(WA, WB, best * (1 + 1e-9) + band, [&](int i, int j) { cands.push_back({box_distance(WA, i, WB, j), i, j}); });
    std::sort(cands.begin(), cands.end(), [](const Cand &x, const Cand &y) { return x.box < y.box; });
    for (const Cand &k : cands) {
        if (static_cast<double>(k.box) > best + band) break;
        rep.count("ccd: triangle pairs in global minimum");
        best = std::min(best, ccd_pair_distance(CA[size_t(k.i)], CB[size_t(k.j)]));
    }
    rep.count("ccd: distances compared (global minimum)");
    double truth = best;
    bool have_bf = false;
    auto brute = [&]() {
        if (!have_bf) truth = static_cast<double>(distance_truth(WA, WB, {{od.id1, od.id2}}).dist);
        have_bf = true;
    };
    if (std::fabs(best - od.d) > dist_tol(std::max(best, od.d), band)) {
        brute();
        const bool ours_ok = std::fabs(od.d - truth) <= dist_tol(truth, band);
        rep.disagreement("libccd", ours_ok ? "global distance: libccd off" : "global distance", !ours_ok,
                         fmt("ours %.17g, libccd %.17g, brute force %.17g; %s", od.d, best, truth,
                             pose_str(pp).c_str()));
    }

    // ---- tolerance verdicts against the libccd distance
    pqp_tolerance_result *tr = pqp_tolerance_result_create();
    for (double t : {0.0, best * (1 - 1e-6) - 4 * band, best * (1 + 1e-6) + 4 * band, c.rng.log_uniform(1e-9, 2.0)}) {
        if (!(t >= 0)) continue;
        const ToleranceOut ot = our_tolerance(tr, pp, oa, ob, t, 1 + index % 3);
        if (!rep.check(ot.rc == PQP_OK, fmt("tolerance rc %d", ot.rc))) continue;
        rep.count("ccd: tolerance verdicts compared");
        if (std::fabs(best - t) <= dist_tol(std::max(best, t), band) || ot.closer == (best <= t)) continue;
        brute();
        const bool amb = std::fabs(truth - t) <= dist_tol(std::max(truth, t), band);
        const bool we_wrong = !amb && ot.closer != (truth <= t);
        rep.disagreement("libccd", amb ? "tolerance verdict (borderline)" : "tolerance verdict", we_wrong,
                         fmt("t=%.17g: we say %d, libccd distance %.17g, brute force %.17g; %s", t, int(ot.closer), best,
                             truth, pose_str(pp).c_str()));
    }
    pqp_tolerance_result_destroy(tr);
}

std::vector<PosePair> make_poses(Ctx &c, const Workload &w) {
    if (!w.fixed.empty()) return w.fixed;
    std::vector<PosePair> out;
    const double ra = w.a.radius(), rb = w.b.radius();
    auto closest = [&](const PosePair &pp) {
        const DistanceTruth dt = distance_truth(to_world(w.a, pp.a), to_world(w.b, pp.b), {});
        return std::make_pair(dt.i, dt.j);
    };
    for (int k = 0; k < w.poses; ++k) {
        PosePair pp;
        if (w.contact) {
            pp = contact_pair(c.rng, w.b, k % 3, contact_gap(c.rng), contact_tilt(c.rng));
            if (c.rng.uniform() < 0.3) add_offset(c.rng, pp);
            out.push_back(pp);
            continue;
        }
        switch (k % 8) {
        case 0: pp = random_pair(c.rng, ra, rb, 1.02, 2.0, "separated"); break;
        case 1:
        case 2: pp = near_pair(c.rng, w.a, w.b, ra, rb, c.rng.log_uniform(1e-12, 1.0), closest); break;
        case 3:
        case 4: pp = random_pair(c.rng, ra, rb, 0.6, 1.0, "shallow overlap"); break;
        default: pp = random_pair(c.rng, ra, rb, 0.0, 0.6, "deep overlap");
        }
        if (c.rng.uniform() < 0.3) add_offset(c.rng, pp);
        out.push_back(pp);
    }
    return out;
}

std::vector<Workload> workloads(Ctx &c) {
    Rng &g = c.rng;
    std::vector<Workload> w;
    auto add = [&](const Mesh &a, const Mesh &b, int poses, bool global, bool contact = false) {
        w.push_back({a.name + " vs " + b.name, a, b, scaled(c.opt, poses), global, {}, contact});
    };
    add(make_sphere(1, 6, 12), make_sphere(1, 6, 12), 300, true);
    add(make_torus(0.7, 0.3, 8, 16), make_sphere(0.8, 8, 16), 250, true);
    add(make_soup(g, 150, 1, 0.3), make_soup(g, 150, 1, 0.3), 300, true);
    add(make_thin(g, 150, 1, 0.4), make_thin(g, 150, 1, 0.4), 300, true);
    add(make_thin(g, 200, 1, 0.5), make_soup(g, 100, 1, 0.4), 200, true);
    const Mesh bunny = normalized(load_or(c.opt, "bunny.tris", make_sphere(1, 20, 56)));
    const Mesh torus = normalized(load_or(c.opt, "torus.tris", make_torus(0.7, 0.3, 18, 37)));
    add(bunny, torus, 40, false);
    add(make_box(2), make_box(2), 300, true, true);
    add(make_box(2), make_torus(0.7, 0.3, 8, 16), 200, true, true);
    add(make_box(4), make_thin(g, 120, 0.8, 0.4), 200, true, true);
    add(make_box(2), make_flat(g, 100, 1.2), 200, true, true);
    // Exact touching configurations at identity.
    Workload e{"cube vs grid4x4 (exact)", make_cube(), make_grid(4, 4), 0, true, {}, false};
    for (const auto &t : std::vector<std::array<double, 3>>{{1, 1, 1}, {1, 1, -1}, {0, 0, 0}, {2, 2, 0.5}, {-1, -1, -1}, {3, 3, 1.25}}) {
        PosePair pp;
        pp.a = identity_pose();
        pp.b = identity_pose();
        for (int k = 0; k < 3; ++k) pp.b.T[k] = t[size_t(k)];
        pp.exact = true;
        pp.kind = fmt("exact T2=(%g %g %g)", t[0], t[1], t[2]);
        e.fixed.push_back(pp);
    }
    w.push_back(e);
    return w;
}

}  // namespace

int main(int argc, char **argv) {
    Ctx c;
    c.opt = parse_options(argc, argv);
    c.rng = Rng(c.opt.seed ^ 0xccdull);
    announce("ccd_compare", c.opt);
    const auto t0 = std::chrono::steady_clock::now();
    return run_workloads(c.rep, c.opt, workloads(c), "poses", t0, [&](const Workload &w) -> size_t {
        const OurModel oa(w.a), ob(w.b);
        if (!c.rep.check(oa.build_rc == PQP_OK && ob.build_rc == PQP_OK, "model build")) return 0;
        const std::vector<PosePair> poses = make_poses(c, w);
        for (size_t k = 0; k < poses.size(); ++k) compare_pose(c, w, oa, ob, poses[k], int(k));
        return poses.size();
    });
}
