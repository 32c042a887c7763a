// Compares our library (C ABI, and the PQP.h drop-in for a subset) with FCL 0.7 on the same meshes and
// poses: colliding triangle pairs, first-contact verdicts, exact and approximate distances, tolerance
// verdicts. Disagreements are decided by brute force in long double; the run fails only when our
// library is wrong (or inconsistent with its own contract).
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <set>

#include "fcl_util.hpp"
#include "harness/harness.hpp"

using namespace ht;

namespace {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;
using PairSet = std::set<std::pair<int, int>>;

std::shared_ptr<FclModel> fcl_model(const Mesh &m) {
    return fclu::mesh<fcl::OBBRSSd>(m.tris.size(), [&](size_t i, int k) { return m.tris[i].p[k]; });
}

fcl::Transform3d fcl_tf(const Pose &p) { return fclu::transform(p.R, p.T); }

struct FclPair {
    std::shared_ptr<FclModel> a, b;
};

struct FclCollide {
    bool colliding = false;
    PairSet pairs;
};

FclCollide fcl_collide(const FclPair &f, const PosePair &pp, bool first) {
    fcl::CollisionRequestd req(first ? 1 : std::numeric_limits<size_t>::max() / 2, false);
    fcl::CollisionResultd res;
    fcl::collide(f.a.get(), fcl_tf(pp.a), f.b.get(), fcl_tf(pp.b), req, res);
    FclCollide out;
    out.colliding = res.isCollision();
    std::vector<fcl::Contactd> cs;
    res.getContacts(cs);
    for (const auto &c : cs) out.pairs.emplace(c.b1, c.b2);
    return out;
}

struct FclDist {
    double d;
    int b1, b2;
};

FclDist fcl_distance(const FclPair &f, const PosePair &pp) {
    fcl::DistanceRequestd req(true);
    fcl::DistanceResultd res;
    fcl::distance(f.a.get(), fcl_tf(pp.a), f.b.get(), fcl_tf(pp.b), req, res);
    return {res.min_distance, static_cast<int>(res.b1), static_cast<int>(res.b2)};
}

LV model_point(const double *x) { return {x[0], x[1], x[2]}; }

void model_tri(const Mesh &m, int i, LV out[3]) {
    for (int k = 0; k < 3; ++k) out[k] = model_point(m.tris[size_t(i)].p[k]);
}

// ---------------------------------------------------------------------------------------------------
struct Workload {
    std::string name;
    Mesh a, b;
    int poses;
    int pqph_every;  ///< route every k-th pose also through PQP.h (0: never)
    std::vector<PosePair> fixed;  ///< explicit poses (exact cases, motion paths); random ones otherwise
    bool same_mesh = false;       ///< a and b are the same mesh: also try coincident poses
    bool contact = false;         ///< a is the box [-1,1]^3: b rests on its top face (contact_pair)
};

struct Ctx {
    Options opt;
    Report rep{"fcl_compare"};
    Rng rng{0};
};

constexpr long kFullDistanceBf = 60000;  ///< brute-force every distance when n*m is at most this

/// Aims `near` poses with FCL's closest triangle pair (the truth is computed independently later).
PosePair fcl_near_pair(Rng &rng, const Workload &w, const FclPair &f, double gap) {
    return near_pair(rng, w.a, w.b, w.a.radius(), w.b.radius(), gap, [&](const PosePair &pp) {
        const FclDist fd = fcl_distance(f, pp);
        return std::make_pair(fd.b1, fd.b2);
    });
}

// ---------------------------------------------------------------------------------------------------
struct Objects {
    const Workload &w;
    OurModel oa, ob;
    std::unique_ptr<PqpHModel> ha, hb;
    FclPair fcl;
    pqp_collide_result *col;        ///< reused across poses
    pqp_distance_result *cached;    ///< reused across poses: exercises the triangle cache
    pqp_tolerance_result *tol;      ///< reused across poses
    PQP_CollideResult hcol;
    PQP_DistanceResult hdist;
    PQP_ToleranceResult htol;
    explicit Objects(const Workload &wl)
        : w(wl), oa(wl.a), ob(wl.b), fcl{fcl_model(wl.a), fcl_model(wl.b)}, col(pqp_collide_result_create()),
          cached(pqp_distance_result_create()), tol(pqp_tolerance_result_create()) {
        if (wl.pqph_every > 0) {
            ha = std::make_unique<PqpHModel>(wl.a);
            hb = std::make_unique<PqpHModel>(wl.b);
        }
    }
    ~Objects() {
        pqp_collide_result_destroy(col);
        pqp_distance_result_destroy(cached);
        pqp_tolerance_result_destroy(tol);
    }
    Objects(const Objects &) = delete;
    Objects &operator=(const Objects &) = delete;
};

std::string pair_str(const std::pair<int, int> &p) { return fmt("(%d,%d)", p.first, p.second); }

bool valid_pairs(const std::vector<std::pair<int, int>> &v, int na, int nb, PairSet *out) {
    bool ok = true;
    for (const auto &p : v) {
        if (p.first < 0 || p.first >= na || p.second < 0 || p.second >= nb) ok = false;
        else if (!out->insert(p).second) ok = false;  // each pair reported once
    }
    return ok;
}

/// Checks a distance answer: its value within [lo - tol, hi + tol] of the truth, realised by its
/// triangle pair and by its closest points, which lie on those triangles.
void check_distance(Ctx &c, const char *what, const DistanceOut &o, const Mesh &A, const Mesh &B, const World &WA,
                    const World &WB, const PosePair &pp, double band, double lo, double hi) {
    Report &rep = c.rep;
    if (!rep.check(o.rc == PQP_OK, fmt("%s: rc %d", what, o.rc))) return;
    if (!rep.check(std::isfinite(o.d) && o.d >= 0, fmt("%s: distance %.17g", what, o.d))) return;
    const double tol_lo = dist_tol(lo, band), tol_hi = dist_tol(hi, band);
    rep.check(o.d >= lo - tol_lo && o.d <= hi + tol_hi,
              fmt("%s: distance %.17g outside [%.17g, %.17g] (brute force/agreed truth, tol %.2g)", what, o.d, lo,
                  hi, tol_hi));
    const LV w1 = to_world(pp.a.R, pp.a.T, o.p1), w2 = to_world(pp.b.R, pp.b.T, o.p2);
    const double pd = static_cast<double>(std::sqrt(bf::norm2(w1 - w2)));
    const double tol = dist_tol(o.d, band);
    rep.check(std::fabs(pd - o.d) <= tol,
              fmt("%s: closest points %.17g apart, distance %.17g", what, pd, o.d));
    if (o.id1 == -1 && o.id2 == -1 && o.overlap == -1) return;  // PQP.h: no ids
    const int na = int(A.tris.size()), nb = int(B.tris.size());
    if (!rep.check(o.id1 >= 0 && o.id1 < na && o.id2 >= 0 && o.id2 < nb,
                   fmt("%s: ids (%d,%d) out of range", what, o.id1, o.id2)))
        return;
    const PairTruth t = pair_truth(WA, o.id1, WB, o.id2, band, false);
    rep.check(std::fabs(static_cast<double>(t.dist) - o.d) <= tol,
              fmt("%s: reported pair (%d,%d) is %.17Lg apart, distance %.17g", what, o.id1, o.id2, t.dist, o.d));
    LV ta[3], tb[3];
    model_tri(A, o.id1, ta);
    model_tri(B, o.id2, tb);
    const double e1 = static_cast<double>(point_triangle_distance(model_point(o.p1), ta));
    const double e2 = static_cast<double>(point_triangle_distance(model_point(o.p2), tb));
    rep.check(e1 <= band && e2 <= band,
              fmt("%s: closest points off their triangles by %.3g and %.3g (band %.3g)", what, e1, e2, band));
    rep.check(o.overlap == (o.d == 0 ? 1 : 0), fmt("%s: overlap flag %d with distance %.17g", what, o.overlap, o.d));
}

void check_tolerance(Ctx &c, const char *what, const ToleranceOut &o, const PosePair &pp, double band, double t,
                     double dref) {
    Report &rep = c.rep;
    if (!rep.check(o.rc == PQP_OK, fmt("%s: rc %d", what, o.rc))) return;
    const double tol = dist_tol(std::max(t, dref), band);
    const bool ambiguous = std::fabs(dref - t) <= tol;
    if (!ambiguous)
        rep.check(o.closer == (dref <= t),
                  fmt("%s: verdict %d for t=%.17g, true distance %.17g", what, int(o.closer), t, dref));
    if (o.closer) {
        rep.check(o.d <= t + tol && o.d >= dref - tol,
                  fmt("%s: closer, distance %.17g, t=%.17g, true %.17g", what, o.d, t, dref));
        const LV w1 = to_world(pp.a.R, pp.a.T, o.p1), w2 = to_world(pp.b.R, pp.b.T, o.p2);
        const double pd = static_cast<double>(std::sqrt(bf::norm2(w1 - w2)));
        rep.check(std::fabs(pd - o.d) <= tol, fmt("%s: points %.17g apart, distance %.17g", what, pd, o.d));
    } else {
        rep.check(o.d > t && o.d <= dref + tol,
                  fmt("%s: not closer, bound %.17g should be in (t=%.17g, true %.17g]", what, o.d, t, dref));
    }
}

/// One refused query per pose (rotating through the kinds of error) on the reused result objects.
void error_path(Ctx &c, Objects &ob, const PosePair &pp, int index) {
    Report &rep = c.rep;
    PosePair bad = pp;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double d0 = pqp_distance_result_distance(ob.cached);
    const int i1 = pqp_distance_result_id1(ob.cached), i2 = pqp_distance_result_id2(ob.cached);
    const int n0 = pqp_collide_result_num_pairs(ob.col), c0 = pqp_collide_result_colliding(ob.col);
    const int t0 = pqp_tolerance_result_closer_than_tolerance(ob.tol);
    const double td0 = pqp_tolerance_result_distance(ob.tol);
    int rc = 0, want = 0;
    switch (index % 6) {
    case 0: rc = our_distance(ob.cached, pp, ob.oa, ob.ob, 0, 0, 0).rc, want = PQP_ERR_INVALID_ARGUMENT; break;
    case 1: rc = our_distance(ob.cached, pp, ob.oa, ob.ob, -1e-3, 0, 2).rc, want = PQP_ERR_INVALID_ARGUMENT; break;
    case 2:
        bad.b.R[index % 9] = nan;
        rc = our_distance(ob.cached, bad, ob.oa, ob.ob, 0, 0, 2).rc, want = PQP_ERR_NONFINITE_POSE;
        break;
    case 3: rc = our_collide(ob.col, pp, ob.oa, ob.ob, 0).rc, want = PQP_ERR_INVALID_ARGUMENT; break;
    case 4:
        bad.a.T[index % 3] = std::numeric_limits<double>::infinity();
        rc = our_collide(ob.col, bad, ob.oa, ob.ob, PQP_ALL_CONTACTS).rc, want = PQP_ERR_NONFINITE_POSE;
        break;
    default: rc = our_tolerance(ob.tol, pp, ob.oa, ob.ob, nan, 2).rc, want = PQP_ERR_INVALID_ARGUMENT;
    }
    rep.count("error paths exercised");
    rep.check(rc == want, fmt("error path %d: rc %d, expected %d", index % 6, rc, want));
    const double d1 = pqp_distance_result_distance(ob.cached), td1 = pqp_tolerance_result_distance(ob.tol);
    rep.check((d1 == d0 || (std::isnan(d0) && std::isnan(d1))) && pqp_distance_result_id1(ob.cached) == i1 &&
                  pqp_distance_result_id2(ob.cached) == i2 && pqp_collide_result_num_pairs(ob.col) == n0 &&
                  pqp_collide_result_colliding(ob.col) == c0 &&
                  pqp_tolerance_result_closer_than_tolerance(ob.tol) == t0 &&
                  (td1 == td0 || (std::isnan(td0) && std::isnan(td1))),
              "a refused query changed its result object");
}

// ---------------------------------------------------------------------------------------------------
void compare_pose(Ctx &c, Objects &ob, const PosePair &pp, int index) {
    Report &rep = c.rep;
    const Workload &w = ob.w;
    const int na = int(w.a.tris.size()), nb = int(w.b.tris.size());
    rep.set_context(fmt("%s pose %d: %s", w.name.c_str(), index, pp.kind.c_str()), pose_class(pp));
    const World WA = to_world(w.a, pp.a), WB = to_world(w.b, pp.b);
    const double band = band_for(WA, WB);
    rep.count("fcl: poses compared");

    // ---- collision, all contacts
    const CollideOut oc = our_collide(ob.col, pp, ob.oa, ob.ob, PQP_ALL_CONTACTS);
    if (!rep.check(oc.rc == PQP_OK, fmt("collide rc %d", oc.rc))) return;
    PairSet S;
    rep.check(valid_pairs(oc.pairs, na, nb, &S), "collide: invalid, duplicate or inconsistent pair ids");
    rep.check(oc.colliding == !S.empty(), "collide: colliding flag inconsistent with pairs");
    const FclCollide fc = fcl_collide(ob.fcl, pp, false);
    const CollideTruth ct = collide_truth(WA, WB, band, pp.exact);
    rep.count("brute force: triangle pairs tested (collision)", ct.pairs_tested);
    std::map<std::pair<int, int>, Truth> truth;
    for (const auto &p : ct.intersecting) truth[p] = Truth::Intersecting;
    for (const auto &p : ct.borderline) truth[p] = Truth::Borderline;
    auto truth_of = [&](const std::pair<int, int> &p) {
        auto it = truth.find(p);
        return it == truth.end() ? Truth::Separated : it->second;
    };
    PairSet all = S;
    all.insert(fc.pairs.begin(), fc.pairs.end());
    for (const auto &p : ct.intersecting) all.insert(p);
    rep.count("fcl: colliding triangle pairs compared", long(all.size()));
    bool any_int = !ct.intersecting.empty();
    for (const auto &p : all) {
        const bool inS = S.count(p) != 0, inF = fc.pairs.count(p) != 0;
        const Truth t = truth_of(p);
        const PairTruth pt = pair_truth(WA, p.first, WB, p.second, band, pp.exact);
        const std::string d = fmt("pair %s: %s, distance %.3Lg, depth %.3Lg, band %.2g; %s", pair_str(p).c_str(),
                                  truth_name(t), pt.dist, pt.depth, band, pose_str(pp).c_str());
        if (inS && inF) {
            rep.check(t != Truth::Separated, "collide: both report a separated pair: " + d);
        } else if (inS) {
            if (t == Truth::Intersecting) rep.disagreement("FCL", "collide: pair missed by FCL", false, d);
            else if (t == Truth::Borderline) rep.disagreement("FCL", "collide: borderline pair only we report", false, d);
            else rep.disagreement("FCL", "collide: we report a separated pair", true, d);
        } else if (inF) {
            if (t == Truth::Intersecting) rep.disagreement("FCL", "collide: we miss an intersecting pair", true, d);
            else if (t == Truth::Borderline) rep.disagreement("FCL", "collide: borderline pair only FCL reports", false, d);
            else rep.disagreement("FCL", "collide: FCL reports a separated pair", false, d);
        } else {
            rep.check(t != Truth::Intersecting, "collide: both miss an intersecting pair: " + d);
        }
    }
    const bool any_border = !ct.borderline.empty();

    // ---- collision, first contact
    CollideOut of = our_collide(ob.col, pp, ob.oa, ob.ob, PQP_FIRST_CONTACT);
    if (rep.check(of.rc == PQP_OK, fmt("first contact rc %d", of.rc))) {
        rep.check(of.colliding == !S.empty(), fmt("first contact says %d, all contacts found %zu pairs",
                                                  int(of.colliding), S.size()));
        PairSet F1;
        rep.check(valid_pairs(of.pairs, na, nb, &F1) && F1.size() == (of.colliding ? 1u : 0u) &&
                      (F1.empty() || S.count(*F1.begin())),
                  "first contact: expected one pair from the all-contacts set");
        const FclCollide ff = fcl_collide(ob.fcl, pp, true);
        rep.count("fcl: first-contact verdicts compared");
        if (ff.colliding != of.colliding) {
            const std::string d = fmt("we say %d, FCL says %d, truth: %s; %s", int(of.colliding), int(ff.colliding),
                                      any_int ? "intersecting" : any_border ? "borderline only" : "separated",
                                      pose_str(pp).c_str());
            const bool we_wrong = any_int ? !of.colliding : (!any_border && of.colliding);
            rep.disagreement("FCL", !any_int && any_border ? "first contact verdict, only borderline pairs"
                                                           : "first contact verdict",
                             we_wrong, d);
        }
    }

    // ---- exact distance
    const bool full_bf = long(na) * long(nb) <= kFullDistanceBf || pp.exact;
    const DistanceOut od = our_distance(ob.cached, pp, ob.oa, ob.ob, 0, 0, 2);
    if (!rep.check(od.rc == PQP_OK, fmt("distance rc %d", od.rc))) return;
    const FclDist fd = fcl_distance(ob.fcl, pp);
    rep.count("fcl: distances compared");
    const double f = std::max(0.0, fd.d);  // FCL may report a negative value for overlapping meshes
    double dref = f;
    bool have_bf = false;
    auto brute = [&]() {
        const DistanceTruth dt = distance_truth(WA, WB, {{od.id1, od.id2}, {fd.b1, fd.b2}});
        rep.count("brute force: triangle pairs tested (distance)", dt.pairs_tested);
        dref = static_cast<double>(dt.dist);
        have_bf = true;
    };
    if (full_bf) brute();
    const double tol = dist_tol(std::max(od.d, f), band);
    if (std::fabs(od.d - f) > tol) {
        if (!have_bf) brute();
        const double tr = dist_tol(dref, band);
        const bool ours_ok = std::fabs(od.d - dref) <= tr, fcl_ok = std::fabs(f - dref) <= tr;
        const std::string d = fmt("ours %.17g, FCL %.17g (raw %.17g, pair %d,%d), brute force %.17g; %s", od.d, f,
                                  fd.d, fd.b1, fd.b2, dref, pose_str(pp).c_str());
        if (ours_ok) rep.disagreement("FCL", f > dref ? "distance: FCL too large" : "distance: FCL too small", false, d);
        else rep.disagreement("FCL", fcl_ok ? "distance: ours wrong, FCL right" : "distance: both wrong", true, d);
    }  // else FCL's distance (agreed within tolerance) is the reference below
    check_distance(c, "distance", od, w.a, w.b, WA, WB, pp, band, dref, dref);

    // ---- an error path on the reused result objects: refused, and the results stay as they were
    error_path(c, ob, pp, index);

    // ---- approximate distance (fresh result objects: create/destroy in the loop)
    static const double kApprox[][2] = {{0.1, 1e9}, {10, 0.05}, {0.05, 0.01}, {1.0, 1e-3}};
    for (const auto &ra : kApprox) {
        pqp_distance_result *r = pqp_distance_result_create();
        const int q = 1 + index % 4;
        const DistanceOut oa = our_distance(r, pp, ob.oa, ob.ob, ra[0], ra[1], q);
        rep.count("fcl: approximate distances checked");
        const double hi = std::min(dref * (1 + ra[0]), dref + ra[1]);
        check_distance(c, fmt("approximate distance rel %g abs %g", ra[0], ra[1]).c_str(), oa, w.a, w.b, WA, WB, pp,
                       band, dref, hi);
        pqp_distance_result_destroy(r);
    }

    // ---- tolerance
    std::vector<double> ts = {0, dref * (1 + 1e-6) + 4 * band, c.rng.log_uniform(1e-9, 3.0)};
    if (dref > 0) ts.push_back(dref * (1 - 1e-6) - 4 * band);
    for (double t : ts) {
        if (!(t >= 0)) continue;
        ToleranceOut ot = our_tolerance(ob.tol, pp, ob.oa, ob.ob, t, 2);
        rep.count("fcl: tolerance verdicts compared");
        const double tb = dist_tol(std::max(t, dref), band);
        if (ot.rc == PQP_OK && std::fabs(dref - t) > tb && ot.closer != (dref <= t) && !have_bf) brute();
        if (ot.rc == PQP_OK && std::fabs(f - t) > dist_tol(std::max(t, f), band) && std::fabs(dref - t) > tb &&
            (f <= t) != ot.closer) {
            const bool we_wrong = ot.closer != (dref <= t);
            rep.disagreement("FCL", "tolerance verdict", we_wrong,
                             fmt("t=%.17g: we say %d, FCL distance %.17g, truth %.17g; %s", t, int(ot.closer), f, dref,
                                 pose_str(pp).c_str()));
        }
        check_tolerance(c, "tolerance", ot, pp, band, t, dref);
    }

    // ---- the PQP.h drop-in on a subset
    if (ob.ha && w.pqph_every > 0 && index % w.pqph_every == 0) {
        rep.count("PQP.h: poses compared");
        const CollideOut hc = pqph_collide(&ob.hcol, pp, *ob.ha, *ob.hb, PQP_ALL_CONTACTS);
        PairSet HS;
        rep.check(hc.rc == PQP_OK && valid_pairs(hc.pairs, na, nb, &HS) && HS == S && hc.colliding == !S.empty(),
                  "PQP.h: PQP_Collide pairs differ from the C ABI's");
        const CollideOut hf = pqph_collide(&ob.hcol, pp, *ob.ha, *ob.hb, PQP_FIRST_CONTACT);
        rep.check(hf.rc == PQP_OK && hf.colliding == !S.empty(), "PQP.h: first contact verdict");
        const DistanceOut hd = pqph_distance(&ob.hdist, pp, *ob.ha, *ob.hb, 0, 0, 2);
        check_distance(c, "PQP.h distance", hd, w.a, w.b, WA, WB, pp, band, dref, dref);
        const DistanceOut hbad = pqph_distance(&ob.hdist, pp, *ob.ha, *ob.hb, 0, 0, 0);  // refused, untouched
        rep.check(hbad.rc == PQP_ERR_INVALID_ARGUMENT && ob.hdist.Distance() == hd.d, "PQP.h: refused PQP_Distance");
        const DistanceOut ha = pqph_distance(&ob.hdist, pp, *ob.ha, *ob.hb, 0.1, 0.01, 3);
        check_distance(c, "PQP.h approximate distance", ha, w.a, w.b, WA, WB, pp, band, dref,
                       std::min(dref * 1.1, dref + 0.01));
        for (double t : ts) {
            if (!(t >= 0)) continue;
            const ToleranceOut ht = pqph_tolerance(&ob.htol, pp, *ob.ha, *ob.hb, t, 2);
            check_tolerance(c, "PQP.h tolerance", ht, pp, band, t, dref);
        }
    }
}

// ---------------------------------------------------------------------------------------------------
std::vector<PosePair> make_poses(Ctx &c, const Workload &w, const FclPair &f) {
    if (!w.fixed.empty()) return w.fixed;
    std::vector<PosePair> out;
    const double ra = w.a.radius(), rb = w.b.radius();
    for (int k = 0; k < w.poses; ++k) {
        PosePair pp;
        if (w.contact) {
            pp = contact_pair(c.rng, w.b, k % 3, contact_gap(c.rng), contact_tilt(c.rng));
            if (c.rng.uniform() < 0.3) add_offset(c.rng, pp);
            out.push_back(pp);
            continue;
        }
        switch (k % 10) {
        case 0:
        case 1:
            pp = random_pair(c.rng, ra, rb, 1.02, 3.0, "separated");
            break;
        case 2:
        case 3:
        case 4:
            pp = fcl_near_pair(c.rng, w, f, c.rng.log_uniform(1e-12, 1.0));
            break;
        case 5:
        case 6:
            pp = random_pair(c.rng, ra, rb, 0.6, 1.0, "shallow overlap");
            break;
        case 7:
        case 8:
            pp = random_pair(c.rng, ra, rb, 0.0, 0.6, "deep overlap");
            break;
        default:
            if (w.same_mesh) {
                pp = random_pair(c.rng, ra, rb, 0, 0, "coincident");
                pp.b = pp.a;
            } else {
                pp = random_pair(c.rng, ra, rb, 0.9, 1.1, "grazing");
            }
        }
        if (c.rng.uniform() < 0.3) add_offset(c.rng, pp);
        out.push_back(pp);
    }
    return out;
}

std::vector<PosePair> exact_poses(const std::vector<std::array<double, 3>> &ts, bool with_rotations) {
    std::vector<PosePair> out;
    const double rx[9] = {1, 0, 0, 0, 0, -1, 0, 1, 0};   // 90 degrees about x
    const double rz[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};   // 90 degrees about z
    for (int r = 0; r < (with_rotations ? 3 : 1); ++r)
        for (const auto &t : ts) {
            PosePair pp;
            pp.a = identity_pose();
            pp.b = identity_pose();
            if (r == 1) std::copy(rx, rx + 9, pp.b.R);
            if (r == 2) std::copy(rz, rz + 9, pp.b.R);
            for (int k = 0; k < 3; ++k) pp.b.T[k] = t[size_t(k)];
            pp.exact = true;
            pp.kind = fmt("exact rot%d T2=(%g %g %g)", r, t[0], t[1], t[2]);
            out.push_back(pp);
        }
    return out;
}

std::vector<PosePair> path_poses(const Options &o, int every) {
    auto read = [](const std::string &p, std::vector<Pose> *out) {
        FILE *fp = std::fopen(p.c_str(), "r");
        if (!fp) return false;
        int n = 0;
        bool ok = std::fscanf(fp, "%d", &n) == 1 && n > 0;
        for (int i = 0; ok && i < n; ++i) {
            Pose q;
            for (double &x : q.R) ok = ok && std::fscanf(fp, "%lf", &x) == 1;
            for (double &x : q.T) ok = ok && std::fscanf(fp, "%lf", &x) == 1;
            out->push_back(q);
        }
        std::fclose(fp);
        return ok;
    };
    std::vector<Pose> p1, p2;
    std::vector<PosePair> out;
    const std::string f1 = find_model(o, "torus1.path"), f2 = find_model(o, "torus2.path");
    if (f1.empty() || f2.empty() || !read(f1, &p1) || !read(f2, &p2)) return out;
    for (size_t i = 0; i < std::min(p1.size(), p2.size()); i += size_t(every)) {
        PosePair pp;
        pp.a = p1[i];
        pp.b = p2[i];
        orthonormalize(pp.a.R);  // the files hold 6 significant digits: make the rotations proper
        orthonormalize(pp.b.R);
        pp.kind = fmt("path frame %zu", i);
        out.push_back(pp);
    }
    return out;
}

std::vector<Workload> workloads(Ctx &c) {
    const Options &o = c.opt;
    Rng &g = c.rng;
    std::vector<Workload> w;
    auto add = [&](const Mesh &a, const Mesh &b, int poses, int pqph, bool same = false, bool contact = false) {
        Workload x;
        x.contact = contact;
        x.name = a.name + " vs " + b.name;
        x.a = a;
        x.b = b;
        x.poses = scaled(o, poses);
        x.pqph_every = pqph;
        x.same_mesh = same;
        w.push_back(std::move(x));
    };
    const Mesh s6 = make_sphere(1, 6, 12), s12 = make_sphere(1, 12, 24), s24 = make_sphere(1, 24, 48);
    const Mesh t8 = make_torus(0.7, 0.3, 8, 16), t12 = make_torus(0.7, 0.3, 12, 24);
    const Mesh t32 = make_torus(0.7, 0.3, 32, 64);
    add(s6, s6, 200, 4, true);
    add(s12, t12, 150, 5);
    add(s24, make_sphere(0.8, 8, 16), 100, 0);
    add(t8, t8, 200, 0, true);
    add(t32, make_torus(0.6, 0.2, 16, 32), 60, 0);
    add(make_soup(g, 200, 1, 0.2), make_soup(g, 200, 1, 0.2), 200, 5);
    add(make_soup(g, 400, 1, 0.6), make_sphere(0.9, 8, 16), 100, 0);
    add(make_thin(g, 240, 1, 0.3), make_thin(g, 240, 1, 0.3), 200, 5);
    add(make_thin(g, 300, 1, 0.5), s12, 120, 0);
    const Mesh bunny = normalized(load_or(o, "bunny.tris", make_sphere(1, 20, 56)));
    const Mesh torus = normalized(load_or(o, "torus.tris", make_torus(0.7, 0.3, 18, 37)));
    add(bunny, torus, 100, 10);
    add(bunny, bunny, 60, 0, true);
    add(torus, s6, 100, 0);
    // Resting contacts on a box face: face/edge/vertex down, gaps and penetrations of 1e-12..1e-2.
    const Mesh box2 = make_box(2), box4 = make_box(4);
    add(box4, box4, 300, 6, false, true);
    add(box2, s12, 150, 0, false, true);
    add(box4, make_thin(g, 200, 0.8, 0.4), 150, 0, false, true);
    add(box2, t12, 150, 0, false, true);
    add(box4, bunny, 100, 0, false, true);
    add(box2, make_flat(g, 150, 1.2), 200, 4, false, true);

    // Exact data at exact poses: touching decided without a band (touching counts as colliding).
    const Mesh grid = make_grid(4, 4), cube = make_cube();
    Workload e1{"grid4x4 vs grid4x4 (exact)", grid, grid, 0, 2, {}, true};
    e1.fixed = exact_poses({{{0, 0, 0}}, {{0.5, 0.5, 0}}, {{1, 0, 0}}, {{4, 0, 0}}, {{4, 4, 0}}, {{0, 0, 1}},
                            {{0.25, 0, 0}}, {{1, 2, 0.5}}, {{2, 0, 0}}, {{0, 0, -0.5}}, {{5, 0, 0}}},
                           true);
    w.push_back(e1);
    Workload e2{"cube vs cube (exact)", cube, cube, 0, 2, {}, true};
    e2.fixed = exact_poses({{{0, 0, 0}}, {{2, 0, 0}}, {{2, 2, 0}}, {{2, 2, 2}}, {{1, 0, 0}}, {{2.5, 0, 0}},
                            {{0, -2, 1}}, {{1, 1, 1}}, {{2, 1, 0.5}}, {{0, 0, 2.25}}},
                           true);
    w.push_back(e2);
    Workload e3{"cube vs grid4x4 (exact)", cube, grid, 0, 0, {}, false};
    e3.fixed = exact_poses({{{1, 1, 1}}, {{1, 1, -1}}, {{0, 0, 0}}, {{2, 2, 0.5}}, {{-1, -1, -1}}, {{1, 1, 1.5}}},
                           true);
    w.push_back(e3);
    for (const Mesh *m : {&s12, &t12}) {
        Workload e{m->name + " vs itself at identity (exact)", *m, *m, 0, 1, {}, true};
        e.a.exact = e.b.exact = true;
        e.fixed = exact_poses({{{0, 0, 0}}}, false);
        w.push_back(e);
    }
    // The demo motion: two tori tumbling through each other (if the path files are available).
    Mesh t1, t2;
    std::vector<PosePair> path = path_poses(o, std::max(1, int(20 / o.scale)));
    if (!path.empty() && load_tris(find_model(o, "torus1.tris"), &t1) && load_tris(find_model(o, "torus2.tris"), &t2)) {
        Workload p{"torus1 vs torus2 (demo path)", t1, t2, 0, 4, path, false};
        w.push_back(p);
    } else {
        std::printf("note: torus1/torus2 .tris/.path not found in [%s]; skipping the demo path workload\n",
                    join(o.models_dirs).c_str());
    }
    return w;
}

}  // namespace

int main(int argc, char **argv) {
    Ctx c;
    c.opt = parse_options(argc, argv);
    c.rng = Rng(c.opt.seed);
    announce("fcl_compare", c.opt);
    const auto t0 = std::chrono::steady_clock::now();
    return run_workloads(c.rep, c.opt, workloads(c), "poses", t0, [&](const Workload &w) -> size_t {
        Objects ob(w);
        if (!c.rep.check(ob.oa.build_rc == PQP_OK && ob.ob.build_rc == PQP_OK,
                         fmt("model build rc %d / %d", ob.oa.build_rc, ob.ob.build_rc)))
            return 0;
        if (ob.ha)
            c.rep.check(ob.ha->build_rc == PQP_OK && ob.hb->build_rc == PQP_OK, "PQP.h model build");
        const std::vector<PosePair> poses = make_poses(c, w, ob.fcl);
        for (size_t k = 0; k < poses.size(); ++k) compare_pose(c, ob, poses[k], int(k));
        return poses.size();
    });
}
