// Compares our swept-sphere primitives (pqp_model_set_sphere, _capsule, _box) with FCL 0.7's shapes
// (fcl::Sphere, fcl::Capsule, fcl::Box: the same shapes, the capsule also on z, centred, lz its
// length) against meshes: distance and collision at random poses, on the bunny, the torus and random
// soups, with huge and tiny sizes. FCL's sphere distance is exact up to rounding; its capsule- and
// box-vs-mesh distances are GJK-based (within about 1e-6, from above), so those get a looser tolerance. Collision verdicts are compared
// away from contact: when our primitive shrunk by a margin collides, FCL must collide; when it grown
// by the margin does not, FCL must not.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "fcl_util.hpp"
#include "harness/harness.hpp"

using namespace ht;

namespace {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<FclModel> fcl_mesh(const Mesh &m) {
    return fclu::mesh<fcl::OBBRSSd>(m.tris.size(), [&](size_t i, int k) { return m.tris[i].p[k]; });
}

pqp_model *our_mesh(const Mesh &m) {
    pqp_model *p = pqp_model_create();
    pqp_model_begin(p, static_cast<int>(m.tris.size()));
    for (size_t i = 0; i < m.tris.size(); ++i)
        pqp_model_add_tri(p, m.tris[i].p[0], m.tris[i].p[1], m.tris[i].p[2], static_cast<int>(i));
    pqp_model_end(p);
    return p;
}

fcl::Transform3d fcl_tf(const Pose &p) { return fclu::transform(p.R, p.T); }

enum Kind { kSphere, kCapsule, kBox };
const char *kind_name(Kind k) { return k == kSphere ? "sphere" : k == kCapsule ? "capsule" : "box"; }

struct Shape {
    Kind kind;
    double a, b, c;  ///< sphere: radius; capsule: radius, length; box: x, y, z
};

/// Our model of the shape grown by `grow` (negative: shrunk; sizes stay >= 0).
pqp_model *our_shape(const Shape &s, double grow) {
    pqp_model *m = pqp_model_create();
    auto g = [&](double x, double k) { return std::max(0.0, x + k * grow); };
    int rc = s.kind == kSphere    ? pqp_model_set_sphere(m, g(s.a, 1))
             : s.kind == kCapsule ? pqp_model_set_capsule(m, g(s.a, 1), s.b)
                                  : pqp_model_set_box(m, g(s.a, 2), g(s.b, 2), g(s.c, 2));
    if (rc != PQP_OK) std::printf("set shape rc %d\n", rc);
    return m;
}

std::shared_ptr<fcl::CollisionGeometryd> fcl_shape(const Shape &s) {
    if (s.kind == kSphere) return std::make_shared<fcl::Sphered>(s.a);
    if (s.kind == kCapsule) return std::make_shared<fcl::Capsuled>(s.a, s.b);
    return std::make_shared<fcl::Boxd>(s.a, s.b, s.c);
}

Shape random_shape(Rng &rng, double size) {
    Shape s;
    s.kind = static_cast<Kind>(rng.below(3));
    s.a = rng.uniform(0.05, 0.6) * size;
    s.b = rng.uniform(0.05, 1.0) * size;
    s.c = rng.uniform(0.05, 1.0) * size;
    return s;
}

/// Brute force in long double, world coordinates: the shape's core (a point, a segment, or the box's
/// twelve face triangles with the mesh's vertices tested against its inside) against every triangle,
/// less the radius.
L brute_distance(const Shape &s, const Pose &ps, const World &w) {
    std::vector<std::array<LV, 3>> core;
    auto at = [&](double x, double y, double z) {
        const double p[3] = {x, y, z};
        return to_world(ps.R, ps.T, p);
    };
    L radius = 0;
    if (s.kind != kBox) {
        const double h = s.kind == kCapsule ? s.b / 2 : 0.0;
        core.push_back({at(0, 0, -h), at(0, 0, h), at(0, 0, h)});
        radius = s.a;
    } else {
        const double h[3] = {s.a / 2, s.b / 2, s.c / 2};
        for (int k = 0; k < 3; ++k)
            for (int side = -1; side <= 1; side += 2) {
                const int u = (k + 1) % 3, v = (k + 2) % 3;
                auto corner = [&](int su, int sv) {
                    double p[3];
                    p[k] = side * h[k];
                    p[u] = su * h[u];
                    p[v] = sv * h[v];
                    return at(p[0], p[1], p[2]);
                };
                core.push_back({corner(-1, -1), corner(1, -1), corner(1, 1)});
                core.push_back({corner(-1, -1), corner(1, 1), corner(-1, 1)});
            }
        // A mesh vertex strictly inside the box: distance 0.
        for (const LV &x : w.v) {
            const LV d = {x.x - ps.T[0], x.y - ps.T[1], x.z - ps.T[2]};
            bool in = true;
            for (int i = 0; i < 3 && in; ++i) {
                const LV axis = {ps.R[i], ps.R[3 + i], ps.R[6 + i]};
                in = std::fabs(bf::dot(d, axis)) < (i == 0 ? h[0] : i == 1 ? h[1] : h[2]);
            }
            if (in) return 0;
        }
    }
    L best = INFINITY;
    for (const auto &c : core)
        for (int i = 0; i < w.size(); ++i) best = std::min(best, bf::triangle_triangle(c.data(), w.tri(i)).dist);
    return std::max<L>(0, best - radius);
}

int collides(const pqp_model *a, const Pose &pa, const pqp_model *b, const Pose &pb, pqp_collide_result *r) {
    pqp_collide(r, pa.R, pa.T, a, pb.R, pb.T, b, PQP_FIRST_CONTACT);
    return pqp_collide_result_colliding(r);
}

struct Ctx {
    Options opt;
    Rng rng{1};
    Report rep{"primitive_compare"};
    double worst[3] = {0, 0, 0};  ///< largest relative distance disagreement per kind
};

/// One mesh against random shapes at random poses.
void compare_mesh(Ctx &c, const Mesh &raw, double scale, int n) {
    // The mesh normalized to radius ~1, then scaled.
    Mesh mesh = normalized(raw);
    for (ht::Tri &t : mesh.tris)
        for (auto &p : t.p)
            for (double &x : p) x *= scale;
    auto fm = fcl_mesh(mesh);
    pqp_model *om = our_mesh(mesh);
    pqp_distance_result *dr = pqp_distance_result_create();
    pqp_collide_result *cr = pqp_collide_result_create();
    c.rep.set_context(mesh.name + " x" + fmt("%g", scale));
    for (int k = 0; k < n; ++k) {
        const Shape s = random_shape(c.rng, scale);
        Pose pm = random_pose(c.rng, 0.2 * scale), ps = random_pose(c.rng, 1.3 * scale);
        pqp_model *os = our_shape(s, 0.0);
        fcl::CollisionObjectd fo_mesh(fm, fcl_tf(pm)), fo_shape(fcl_shape(s), fcl_tf(ps));
        // Distance, both orders in ours.
        int rc = pqp_distance(dr, ps.R, ps.T, os, pm.R, pm.T, om, 0.0, 0.0, 2);
        const double ours = pqp_distance_result_distance(dr);
        pqp_distance(dr, pm.R, pm.T, om, ps.R, ps.T, os, 0.0, 0.0, 2);
        c.rep.check(rc == PQP_OK && pqp_distance_result_distance(dr) == ours,
                    fmt("%s: distance rc %d, orders %.17g vs %.17g", kind_name(s.kind), rc, ours,
                        pqp_distance_result_distance(dr)));
        fcl::DistanceRequestd dreq(true);
        fcl::DistanceResultd dres;
        fcl::distance(&fo_shape, &fo_mesh, dreq, dres);
        const double theirs = dres.min_distance;
        // FCL answers a non-positive distance when they collide. Its sphere-triangle distance is
        // exact up to rounding; its capsule and box distances come from GJK, which stops within an
        // absolute 1e-6 and approaches from above: ours must not exceed them.
        if (ours > 1e-9 * scale || theirs > 1e-9 * scale) {
            const double err = std::fabs(ours - theirs);
            c.worst[s.kind] = std::max(c.worst[s.kind], err / scale);
            const double tol = s.kind == kSphere ? 1e-9 * scale : 1e-5 * scale + 2e-6;
            if (!(err <= tol && ours <= theirs + 1e-9 * scale)) {
                // Brute force decides.
                const L bf = brute_distance(s, ps, to_world(mesh, pm));
                const bool we_wrong = std::fabs(static_cast<double>(bf) - ours) > 1e-9 * scale;
                c.rep.disagreement("FCL", std::string(kind_name(s.kind)) + " distance", we_wrong,
                                   fmt("ours %.17g, FCL %.17g, brute force %.17Lg", ours, theirs, bf));
            } else {
                c.rep.check(true, "");
            }
        }
        // Collision, away from contact.
        const double margin = 1e-7 * scale;
        pqp_model *small = our_shape(s, -margin), *big = our_shape(s, margin);
        fcl::CollisionRequestd creq;
        fcl::CollisionResultd cres;
        fcl::collide(&fo_shape, &fo_mesh, creq, cres);
        const bool fcl_hit = cres.isCollision();
        const int hit = collides(os, ps, om, pm, cr);
        c.rep.check(hit == (ours == 0.0), fmt("%s: collide %d, distance %.17g", kind_name(s.kind), hit, ours));
        // A disagreement is decided by brute force (FCL's GJK decides contact within about 1e-6,
        // which at a tiny scale is most of the shape).
        const bool small_hit = collides(small, ps, om, pm, cr);
        const bool big_hit = small_hit || collides(big, ps, om, pm, cr);
        if (small_hit != fcl_hit && (small_hit || !big_hit)) {
            const L bf = brute_distance(s, ps, to_world(mesh, pm));
            const bool we_wrong = small_hit ? bf > margin : bf <= margin;
            c.rep.disagreement("FCL", std::string(kind_name(s.kind)) + " collision", we_wrong,
                               fmt("ours %d, FCL %d, brute-force distance %.17Lg (margin %g)", int(small_hit),
                                   int(fcl_hit), bf, margin));
        } else if (small_hit) {
            c.rep.count(std::string(kind_name(s.kind)) + " colliding");
        } else if (!big_hit) {
            c.rep.count(std::string(kind_name(s.kind)) + " apart");
        } else {
            c.rep.count("collision within the margin (not compared)");
        }
        pqp_model_destroy(small);
        pqp_model_destroy(big);
        pqp_model_destroy(os);
    }
    pqp_collide_result_destroy(cr);
    pqp_distance_result_destroy(dr);
    pqp_model_destroy(om);
}

}  // namespace

int main(int argc, char **argv) {
    Ctx c;
    c.opt = parse_options(argc, argv);
    c.rng = Rng(c.opt.seed);
    announce("primitive_compare", c.opt);
    const auto t0 = std::chrono::steady_clock::now();
    const Mesh bunny = load_or(c.opt, "bunny.tris", make_sphere(1.0, 20, 40));
    const Mesh torus = load_or(c.opt, "torus.tris", make_torus(1.0, 0.3, 30, 20));
    const Mesh soup = make_soup(c.rng, 300, 1.0, 0.3);
    const int n = scaled(c.opt, 300);
    for (const Mesh *m : {&bunny, &torus, &soup}) compare_mesh(c, *m, 1.0, n);
    for (double s : {1e-6, 1e6}) compare_mesh(c, torus, s, scaled(c.opt, 100));
    std::printf("  worst distance disagreement / scale: sphere %.3g, capsule %.3g, box %.3g\n", c.worst[0],
                c.worst[1], c.worst[2]);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return c.rep.finish(secs);
}
