// Time of first contact (pqp_time_of_contact) against FCL 0.7's continuous collision by conservative
// advancement, on the same motions (c_tests/toc_fcl.hpp says how the motions are made identical),
// with FCL's mesh models in both of its swept sphere volumes (BVHModel<RSS> and BVHModel<OBBRSS>).
//
// What must hold, checked with our exact distance query (pqp_distance, rel = abs = 0) at poses this
// program interpolates itself:
// - our answer is conservative and first: the distance is above 0.999 tol on [0, toc) and at most
//   tol at toc; without contact, above tol (to a relative 1e-9) on [0, 1]. Checked by dense sampling
//   plus bisection: between two samples a and b the distance is proven above the threshold thr
//   when (d(a) - thr) + (d(b) - thr) > B (b - a), B bounding the speed of every point (this
//   program's own bound, from the vertices' radii); otherwise the interval is halved, until proven,
//   a sample fails (a failure), or B (b - a) <= 1e-7 thr (counted as unresolved, not a failure).
// - agreement with FCL. FCL stops advancing when its step, a distance over a bound on the motion
//   of a pair of triangles (or volumes) along the line between them, drops to t_err = 1e-5 (fixed
//   in FCL's traversal node): at FCL's toc the models are within about 1e-5 x that bound, which is
//   at most 1e-5 B for triangles. So we compare at tol = 1e-5 B: FCL's toc is then expected at or
//   after ours, with the distance at FCL's toc at most tol (the window its tolerance allows). What
//   falls outside is a disagreement, decided by our exact distance and collision queries:
//     * FCL earlier than ours: the distance at FCL's toc is above 0.999 tol (asserted: else our toc
//       would not be first); FCL stopped on a volume's bound larger than B, or a looser leaf bound;
//     * FCL later, with the distance at its toc above tol: the models were within tol at our toc
//       (asserted), FCL went past;
//     * FCL's toc at overlapping poses (our collision query says so at FCL's toc, toc > 0): FCL
//       passed the first contact;
//     * FCL without contact where we have one: our toc at a tolerance of 1e-12 of the scene's size
//       (models touching up to rounding) is computed and its distance asserted; FCL missed a
//       contact (tunnelling); when even that finds none, the closest approach is between the two
//       tolerances (a near miss FCL may rightly skip; counted as agreement within tolerance);
//     * FCL with a contact where we have none: the distance at FCL's toc is above tol (asserted).
//   FCL 0.7's conservative advancement on meshes misses most contacts (a known fault, see
//   toc_fcl.hpp), so FCL's naive continuous collision (1000 collision queries evenly spaced in t)
//   is compared as well, with our toc at the tiny tolerance: where FCL finds a collision, ours must
//   come no later (asserted, unless our own collision query disagrees there), and FCL's should be
//   within one sample (1/999) after ours; contacts FCL misses between samples are counted, shown
//   by our distance at our toc.
// Before any of this, FCL's InterpMotion poses are checked against this program's interpolation
// at six times (to 1e-12 of the scene's size): the motions compared are one.
// Only checks of our library fail the run; disagreements are counted by category.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "harness/harness.hpp"
#include "toc_fcl.hpp"

using namespace ht;

namespace {

struct Case {
    std::string kind;
    toc::Motion m1, m2;
};

struct Workload {
    std::string name;
    Mesh a, b;
    std::vector<Case> cases;
};

std::vector<std::array<double, 9>> flat(const Mesh &m) {
    std::vector<std::array<double, 9>> out;
    for (const ht::Tri &t : m.tris)
        out.push_back({t.p[0][0], t.p[0][1], t.p[0][2], t.p[1][0], t.p[1][1], t.p[1][2], t.p[2][0], t.p[2][1], t.p[2][2]});
    return out;
}

toc::M3 rot(const double *R) {
    toc::M3 r;
    std::copy(R, R + 9, r.begin());
    return r;
}

/// The box [-hx, hx] x [-hy, hy] x [-hz, hz], 12 triangles.
Mesh slab(double hx, double hy, double hz) {
    Mesh m = make_box(1);
    for (ht::Tri &t : m.tris)
        for (auto &p : t.p) {
            p[0] *= hx;
            p[1] *= hy;
            p[2] *= hz;
        }
    m.name = fmt("slab %gx%gx%g", 2 * hx, 2 * hy, 2 * hz);
    return m;
}

/// A rotation turned from R by `angle` about a random axis.
toc::M3 turned(Rng &rng, const toc::M3 &R, double angle) {
    const LV d = rand_dir(rng);
    return toc::mul(toc::rotation_exp({double(d.x), double(d.y), double(d.z)}, angle), R);
}

struct Ctx {
    Options opt;
    Report rep{"toc_compare"};
    Rng rng{0};
};

/// Our side of one case: the models, a reused distance and collision result, the speed bound.
struct Ours {
    const OurModel &a, &b;
    const Case &c;
    double speed, scale;
    pqp_distance_result *dist = pqp_distance_result_create();
    pqp_collide_result *col = pqp_collide_result_create();
    long queries = 0;
    ~Ours() {
        pqp_distance_result_destroy(dist);
        pqp_collide_result_destroy(col);
    }
    PosePair at(double t) const {
        PosePair pp;
        toc::M3 R;
        toc::V3 T;
        toc::pose_at(c.m1, t, &R, &T);
        std::copy(R.begin(), R.end(), pp.a.R);
        std::copy(T.begin(), T.end(), pp.a.T);
        toc::pose_at(c.m2, t, &R, &T);
        std::copy(R.begin(), R.end(), pp.b.R);
        std::copy(T.begin(), T.end(), pp.b.T);
        return pp;
    }
    /// The exact distance at t (NaN on an error code).
    double distance(double t) {
        ++queries;
        const DistanceOut o = our_distance(dist, at(t), a, b, 0, 0, 2);
        return o.rc == PQP_OK ? o.d : NAN;
    }
    bool colliding(double t) { return our_collide(col, at(t), a, b, PQP_FIRST_CONTACT).colliding; }
    int time_of_contact(double tol, pqp_contact_time *out) const {
        return pqp_time_of_contact(out, c.m1.Ra.data(), c.m1.Ta.data(), c.m1.Rb.data(), c.m1.Tb.data(), a.get(),
                                   c.m2.Ra.data(), c.m2.Ta.data(), c.m2.Rb.data(), c.m2.Tb.data(), b.get(), tol);
    }
};

/// Dense sampling plus bisection on [lo, hi] (module comment): the first sampled time with a
/// distance at most thr (the end `hi` itself excepted when `open_end`), or -1 if none.
double first_below(Ours &o, double lo, double hi, double thr, bool open_end, long *unresolved) {
    struct Iv {
        double a, da, b, db;
    };
    const int n = 24;
    std::vector<double> ts, ds;
    for (int k = 0; k <= n; ++k) {
        const double t = k == n ? hi : lo + (hi - lo) * k / n;
        ts.push_back(t);
        ds.push_back(o.distance(t));
        if (!(ds.back() > thr) && !(open_end && k == n)) return t;
    }
    for (int k = 0; k < n; ++k) {
        std::vector<Iv> stack{{ts[size_t(k)], ds[size_t(k)], ts[size_t(k + 1)], ds[size_t(k + 1)]}};
        while (!stack.empty()) {
            const Iv iv = stack.back();
            stack.pop_back();
            const double reach = o.speed * (iv.b - iv.a);
            if ((iv.da - thr) + (iv.db - thr) > reach) continue;
            const double mid = 0.5 * (iv.a + iv.b);
            if (reach <= 1e-7 * thr || mid <= iv.a || mid >= iv.b) {
                ++*unresolved;
                continue;
            }
            const double dm = o.distance(mid);
            if (!(dm > thr)) return mid;
            stack.push_back({mid, dm, iv.b, iv.db});
            stack.push_back({iv.a, iv.da, mid, dm});
        }
    }
    return -1;
}

template <typename BV>
struct FclSide {
    std::string name;
    std::shared_ptr<fcl::BVHModel<BV>> a, b;
};

/// Compares FCL's answer with ours on one case (module comment).
void compare(Ctx &c, Ours &o, const pqp_contact_time &ours, const pqp_contact_time &t0, double tol,
             const std::string &peer, const toc::FclToc &f) {
    Report &rep = c.rep;
    const std::string detail =
        fmt("%s: ours %s toc %.12g, FCL %s toc %.12g (%ld steps), tol %.3g, B %.6g", o.c.kind.c_str(),
            ours.contact ? "contact" : "none", ours.toc, f.contact ? "contact" : "none", f.toc, f.steps, tol, o.speed);
    rep.count(peer + " queries");
    rep.count(peer + " steps", f.steps);
    if (!ours.contact && !f.contact) {
        rep.count(peer + " agree: no contact");
        return;
    }
    if (ours.contact && f.contact) {
        const double df = o.distance(f.toc);
        if (f.toc < ours.toc) {
            rep.check(df > 0.999 * tol * (1 - 1e-9) - 1e-12 * o.scale,
                      fmt("%s: distance %.17g at FCL's earlier toc, within tol: ours is not first", detail.c_str(), df));
            rep.disagreement(peer, "FCL stops early: distance at its toc above tol (shown)", false,
                             detail + fmt(", distance there %.3g tol", df / tol));
            return;
        }
        if (df <= tol * (1 + 1e-9) + 1e-12 * o.scale) {
            const bool overlap = f.toc > 0 && o.colliding(f.toc);
            if (!overlap) {
                rep.count(peer + " agree: toc in the window of FCL's tolerance");
                rep.count(peer + " agree: |toc difference| <= 1e-6", std::fabs(f.toc - ours.toc) <= 1e-6);
                return;
            }
        }
        if (f.toc > 0 && o.colliding(f.toc)) {
            rep.disagreement(peer, "FCL's toc at overlapping poses: past the first contact (shown)", false, detail);
            return;
        }
        rep.disagreement(peer, "FCL later: models within tol at our earlier toc (shown), not at FCL's", false,
                         detail + fmt(", distance at FCL's toc %.3g tol", df / tol));
        return;
    }
    if (ours.contact) {
        if (!t0.contact) {
            rep.count(peer + " agree within tolerance: near miss between 1e-12 and tol, FCL none");
            return;
        }
        rep.disagreement(peer, "FCL misses a contact (tunnelling): models touch at our toc (shown)", false,
                         detail + fmt(", touching at t = %.12g", t0.toc));
        return;
    }
    const double df = o.distance(f.toc);
    rep.check(df > tol * (1 - 1e-9), fmt("%s: distance %.17g at FCL's toc, but we found no contact", detail.c_str(), df));
    rep.disagreement(peer, "FCL contact, ours none: distance at FCL's toc above tol (shown)", false,
                     detail + fmt(", distance there %.3g tol", df / tol));
}

/// Compares FCL's naive continuous collision (`samples` collision queries) with our toc at the tiny
/// tolerance t0 (models touching up to rounding).
void compare_naive(Ctx &c, Ours &o, const pqp_contact_time &t0, double tiny, int samples, const toc::FclToc &f) {
    Report &rep = c.rep;
    const std::string peer = fmt("FCL naive (%d samples)", samples);
    const std::string detail = fmt("%s: ours (tol %.3g) %s toc %.12g, FCL %s toc %.12g", o.c.kind.c_str(), tiny,
                                   t0.contact ? "contact" : "none", t0.toc, f.contact ? "contact" : "none", f.toc);
    rep.count(peer + " queries");
    if (!t0.contact && !f.contact) {
        rep.count(peer + " agree: no contact");
        return;
    }
    if (f.contact) {
        // FCL's discrete query says the models overlap at its toc: ours must have found a touch no later.
        if (!t0.contact || t0.toc > f.toc) {
            rep.check(!o.colliding(f.toc), detail + ": our collision query says colliding at FCL's toc, our toc is later");
            rep.disagreement(peer, "FCL's collision query at its toc disagrees with ours (not colliding)", false, detail);
            return;
        }
        if (f.toc - t0.toc <= 1.0 / (samples - 1) + 1e-12) {
            rep.count(peer + " agree: FCL's toc within one sample after ours");
            return;
        }
        rep.disagreement(peer, "FCL misses an earlier contact between its samples: touching at our toc (shown)", false,
                         detail);
        return;
    }
    rep.disagreement(peer, "FCL misses a contact between its samples (tunnelling): touching at our toc (shown)", false,
                     detail);
}

void run_case(Ctx &c, const OurModel &oa, const OurModel &ob, const Workload &w, const Case &cs,
              const FclSide<fcl::RSSd> &rss, const FclSide<fcl::OBBRSSd> &obbrss) {
    Report &rep = c.rep;
    const double ra = w.a.radius(), rb = w.b.radius();
    Ours o{oa, ob, cs, toc::speed_bound(cs.m1, ra, cs.m2, rb) * (1 + 1e-9), 1};
    for (const toc::V3 *T : {&cs.m1.Ta, &cs.m1.Tb, &cs.m2.Ta, &cs.m2.Tb})
        o.scale = std::max(o.scale, std::sqrt((*T)[0] * (*T)[0] + (*T)[1] * (*T)[1] + (*T)[2] * (*T)[2]) + ra + rb);
    const double tol = std::max(1e-5 * o.speed, 1e-9 * o.scale);
    rep.set_context(w.name + ": " + cs.kind);
    pqp_contact_time ours;
    if (!rep.check(o.time_of_contact(tol, &ours) == PQP_OK, cs.kind + ": rc")) return;
    rep.count("our queries");
    rep.count("our contacts", ours.contact);
    // Conservative and first, by our exact distance.
    long unresolved = 0;
    const double slack = 1e-12 * o.scale;
    if (ours.contact) {
        if (!rep.check(ours.toc >= 0 && ours.toc <= 1, fmt("%s: toc %.17g", cs.kind.c_str(), ours.toc))) return;
        const double dt = o.distance(ours.toc);
        rep.check(dt <= tol * (1 + 1e-9) + slack, fmt("%s: distance %.17g at toc %.17g, tol %.17g", cs.kind.c_str(), dt,
                                                      ours.toc, tol));
        double gap = 0;
        for (int k = 0; k < 3; ++k) gap += (ours.point1[k] - ours.point2[k]) * (ours.point1[k] - ours.point2[k]);
        rep.check(std::sqrt(gap) <= tol * (1 + 1e-9) + slack && ours.id1 >= 0 &&
                      ours.id1 < int(w.a.tris.size()) && ours.id2 >= 0 && ours.id2 < int(w.b.tris.size()),
                  fmt("%s: closest pair %d %d, points %.17g apart", cs.kind.c_str(), ours.id1, ours.id2,
                      std::sqrt(gap)));
        if (ours.toc > 0) {
            const double bad = first_below(o, 0, ours.toc, 0.999 * tol - slack, true, &unresolved);
            rep.check(bad < 0, fmt("%s: distance at most 0.999 tol at t = %.17g < toc %.17g", cs.kind.c_str(), bad,
                                   ours.toc));
        }
    } else {
        const double bad = first_below(o, 0, 1, tol * (1 - 1e-9) - slack, false, &unresolved);
        rep.check(bad < 0, fmt("%s: no contact, but the distance is within tol at t = %.17g", cs.kind.c_str(), bad));
    }
    rep.count("sampling: intervals left unresolved (width below 1e-7 tol)", unresolved);
    // The motions FCL is given are ours.
    rep.check(toc::motion_mismatch(cs.m1) <= 1e-12 * o.scale && toc::motion_mismatch(cs.m2) <= 1e-12 * o.scale,
              cs.kind + ": FCL's InterpMotion poses differ from ours");
    // Our toc with the models touching up to rounding, for the comparisons.
    const double tiny = 1e-12 * o.scale;
    pqp_contact_time t0 = ours;
    if (ours.contact) {
        if (!rep.check(o.time_of_contact(tiny, &t0) == PQP_OK, cs.kind + ": tiny tolerance rc")) return;
        if (t0.contact) {
            const double d0 = o.distance(t0.toc);
            rep.check(t0.toc >= ours.toc && d0 <= tiny * (1 + 1e-9) + slack,
                      fmt("%s: distance %.17g at our toc %.17g (%.17g at tol) with tolerance %.3g", cs.kind.c_str(),
                          d0, t0.toc, ours.toc, tiny));
        }
    }
    compare(c, o, ours, t0, tol, "FCL RSS", toc::fcl_toc(*rss.a, cs.m1, *rss.b, cs.m2));
    compare(c, o, ours, t0, tol, "FCL OBBRSS", toc::fcl_toc(*obbrss.a, cs.m1, *obbrss.b, cs.m2));
    const int samples = 1000;
    compare_naive(c, o, t0, tiny, samples, toc::fcl_naive_toc(*obbrss.a, cs.m1, *obbrss.b, cs.m2, samples));
    rep.count("exact distance queries of the checks", o.queries);
}

std::vector<Workload> workloads(Ctx &c) {
    const Options &o = c.opt;
    Rng &g = c.rng;
    std::vector<Workload> w;
    // The falling tori: frame a to frame a + k.
    Mesh t1, t2;
    const auto p1 = toc::read_path(find_model(o, "torus1.path")), p2 = toc::read_path(find_model(o, "torus2.path"));
    if (!p1.empty() && !p2.empty() && load_tris(find_model(o, "torus1.tris"), &t1) &&
        load_tris(find_model(o, "torus2.tris"), &t2)) {
        const int n = int(std::min(p1.size(), p2.size()));
        for (const auto &[k, count] : {std::pair<int, int>{1, 40}, {10, 30}, {100, 16}, {600, 8}}) {
            Workload x{fmt("torus1 vs torus2, frames %d apart", k), t1, t2, {}};
            const int m = scaled(o, count);
            for (int i = 0; i < m; ++i) {
                const int a = int((long(n - k - 1) * i) / m);
                x.cases.push_back({fmt("frames %d -> %d", a, a + k), toc::between(p1[size_t(a)], p1[size_t(a + k)]),
                                   toc::between(p2[size_t(a)], p2[size_t(a + k)])});
            }
            w.push_back(std::move(x));
        }
    } else {
        std::printf("note: torus1/torus2 .tris/.path not found in [%s]; skipping the tori path\n",
                    join(o.models_dirs).c_str());
    }
    // Thin plates crossed at high speed: a wall 1e-3 thick (x = 0), a plate 1e-3 thick thrown 20 to
    // 200 units across it while turning up to 150 degrees; its path crosses the wall's plane at a
    // random height, inside the wall or just beside it. The wall drifts and turns slightly too.
    {
        Workload x{"thin plates at high speed", slab(0.0005, 1, 1), slab(0.0005, 0.5, 0.5), {}};
        const int m = scaled(o, 60);
        for (int i = 0; i < m; ++i) {
            Case cs;
            const double len = g.log_uniform(20, 200), y = g.uniform(-1.8, 1.8), z = g.uniform(-1.8, 1.8);
            double R[9];
            random_rotation(g, R);
            cs.m2.Ra = rot(R);
            cs.m2.Rb = turned(g, cs.m2.Ra, g.uniform(0, 2.6));
            const double s = g.uniform(0.2, 0.8);  // where along the path it crosses x = 0
            cs.m2.Ta = {-len * s, y + g.uniform(-0.3, 0.3), z + g.uniform(-0.3, 0.3)};
            cs.m2.Tb = {len * (1 - s), y, z};
            const toc::M3 I{1, 0, 0, 0, 1, 0, 0, 0, 1};
            cs.m1.Ra = I;
            cs.m1.Rb = turned(g, I, g.uniform(0, 0.05));
            cs.m1.Ta = {0, 0, 0};
            cs.m1.Tb = {g.uniform(-0.01, 0.01), g.uniform(-0.01, 0.01), g.uniform(-0.01, 0.01)};
            cs.kind = fmt("throw %d: %.4g units, crossing at (%.3f, %.3f)", i, len, y, z);
            x.cases.push_back(cs);
        }
        w.push_back(std::move(x));
    }
    // Generated meshes on random motions that mostly approach (sphere and torus).
    {
        Workload x{"sphere vs torus, random motions", make_sphere(1, 12, 24), make_torus(0.7, 0.3, 12, 24), {}};
        const int m = scaled(o, 40);
        for (int i = 0; i < m; ++i) {
            Case cs;
            double R[9];
            random_rotation(g, R);
            cs.m1.Ra = rot(R);
            cs.m1.Rb = turned(g, cs.m1.Ra, g.uniform(0, 2.5));
            random_rotation(g, R);
            cs.m2.Ra = rot(R);
            cs.m2.Rb = turned(g, cs.m2.Ra, g.uniform(0, 2.5));
            const LV d = rand_dir(g);
            const double gap = g.uniform(2.2, 6), across = g.uniform(0, 2.5);
            const LV side = rand_dir(g);
            cs.m1.Ta = {0, 0, 0};
            cs.m1.Tb = {g.uniform(-0.5, 0.5), g.uniform(-0.5, 0.5), g.uniform(-0.5, 0.5)};
            cs.m2.Ta = {double(d.x) * gap, double(d.y) * gap, double(d.z) * gap};
            cs.m2.Tb = {double(-d.x + side.x * across / 2) * gap / 2, double(-d.y + side.y * across / 2) * gap / 2,
                        double(-d.z + side.z * across / 2) * gap / 2};
            cs.kind = fmt("motion %d", i);
            x.cases.push_back(cs);
        }
        w.push_back(std::move(x));
    }
    return w;
}

}  // namespace

int main(int argc, char **argv) {
    Ctx c;
    c.opt = parse_options(argc, argv);
    c.rng = Rng(c.opt.seed);
    announce("toc_compare", c.opt);
    const auto t0 = std::chrono::steady_clock::now();
    return run_workloads(c.rep, c.opt, workloads(c), "motions", t0, [&](const Workload &w) -> size_t {
        const OurModel oa(w.a), ob(w.b);
        if (!c.rep.check(oa.build_rc == PQP_OK && ob.build_rc == PQP_OK, "model build")) return 0;
        const auto fa = flat(w.a), fb = flat(w.b);
        const FclSide<fcl::RSSd> rss{"RSS", toc::fcl_mesh<fcl::RSSd>(fa), toc::fcl_mesh<fcl::RSSd>(fb)};
        const FclSide<fcl::OBBRSSd> obbrss{"OBBRSS", toc::fcl_mesh<fcl::OBBRSSd>(fa), toc::fcl_mesh<fcl::OBBRSSd>(fb)};
        for (const Case &cs : w.cases) run_case(c, oa, ob, w, cs, rss, obbrss);
        return w.cases.size();
    });
}
