// Primitives against meshes: pqp-rs's swept-sphere primitives (pqp_model_set_sphere, _capsule,
// _box) against FCL 0.7's shapes (fcl::Sphere, Capsule, Box) and against the same primitive meshed
// into triangles in pqp-rs, per query: distance, collision (first contact) and tolerance, in one
// run (see BENCHMARKS.md, "Primitives"). Run by hand; never a test.
//
//   primitive_bench [--models DIR] [--queries N] [--rounds N]
//
// Meshes: the bunny and the torus (DIR/bunny.tris, DIR/torus.tris). Primitives of about a third of
// the mesh's size at N random poses (default 2000) around it, about half of them touching it; the
// same poses for every library. Each round times every library once, in turn; the medians of the
// rounds are printed. FCL has no tolerance query: its column there is its distance query (what
// FCL users call). The meshed primitives are surfaces (a triangle inside one does not touch it):
// a UV sphere of 1520 triangles, the capsule the same stretched, the box 12 triangles.
#include <pqp/pqp.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../c_tests/fcl_util.hpp"
#include "workloads.hpp"

using bench::Mesh;
using bench::Pose;
using bench::Rng;

namespace {

[[noreturn]] void die(const std::string& msg) {
    std::fprintf(stderr, "primitive_bench: %s\n", msg.c_str());
    std::exit(1);
}

Mesh load_tris(const std::string& path) {
    std::ifstream in(path);
    if (!in) die("cannot open " + path);
    long n = 0;
    in >> n;
    Mesh m(static_cast<size_t>(n));
    for (auto& t : m)
        for (double& x : t) in >> x;
    if (!in) die("bad .tris file " + path);
    return m;
}

pqp_model* our_mesh(const Mesh& m) {
    pqp_model* p = pqp_model_create();
    pqp_model_begin(p, static_cast<int>(m.size()));
    for (size_t i = 0; i < m.size(); ++i) pqp_model_add_tri(p, &m[i][0], &m[i][3], &m[i][6], static_cast<int>(i));
    if (pqp_model_end(p) != PQP_OK) die("build failed");
    return p;
}

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> fcl_mesh(const Mesh& m) { return fclu::mesh_of_flat<fcl::OBBRSSd>(m); }

fcl::Transform3d fcl_tf(const Pose& p) { return fclu::transform(p.R.data(), p.T.data()); }

/// The primitive as triangles: a UV sphere, stretched along z for the capsule, or the box's faces.
Mesh meshed(int kind, double a, double b, double c) {
    if (kind == 2) {
        Mesh m;
        const double h[3] = {a / 2, b / 2, c / 2};
        for (int k = 0; k < 3; ++k)
            for (int s = -1; s <= 1; s += 2) {
                const int u = (k + 1) % 3, v = (k + 2) % 3;
                auto corner = [&](int su, int sv, double* out) {
                    out[k] = s * h[k];
                    out[u] = su * h[u];
                    out[v] = sv * h[v];
                };
                bench::Tri t1, t2;
                corner(-1, -1, &t1[0]), corner(1, -1, &t1[3]), corner(1, 1, &t1[6]);
                corner(-1, -1, &t2[0]), corner(1, 1, &t2[3]), corner(-1, 1, &t2[6]);
                m.push_back(t1);
                m.push_back(t2);
            }
        return m;
    }
    Mesh m = bench::uv_sphere(a, 20, 40);
    if (kind == 1)
        for (auto& t : m)
            for (int i = 2; i < 9; i += 3) t[i] += t[i] > 0 ? b / 2 : t[i] < 0 ? -b / 2 : 0.0;
    return m;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = PQP_BENCH_MODELS_DIR;
    int queries = 2000, rounds = 5;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--models")) dir = argv[i + 1];
        else if (!std::strcmp(argv[i], "--queries")) queries = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--rounds")) rounds = std::atoi(argv[i + 1]);
        else die(std::string("unknown option ") + argv[i]);
    }
    const char* kinds[3] = {"sphere", "capsule", "box"};
    std::printf("| mesh | primitive | query | pqp-rs primitive (us) | FCL shape (us) | pqp-rs meshed (us) | FCL / ours | meshed / ours |\n");
    std::printf("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |\n");
    for (const char* name : {"bunny", "torus"}) {
        const Mesh mesh = load_tris(dir + "/" + name + ".tris");
        double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
        for (const auto& t : mesh)
            for (int i = 0; i < 9; ++i) lo[i % 3] = std::min(lo[i % 3], t[i]), hi[i % 3] = std::max(hi[i % 3], t[i]);
        double size = 0, centre[3];
        for (int i = 0; i < 3; ++i) size = std::max(size, hi[i] - lo[i]), centre[i] = 0.5 * (lo[i] + hi[i]);
        pqp_model* om = our_mesh(mesh);
        auto fm = fcl_mesh(mesh);
        for (int kind = 0; kind < 3; ++kind) {
            const double a = (kind == 0 ? 0.15 : kind == 1 ? 0.08 : 0.25) * size, b = 0.3 * size, c = 0.1 * size;
            pqp_model* prim = pqp_model_create();
            if ((kind == 0 ? pqp_model_set_sphere(prim, a)
                 : kind == 1 ? pqp_model_set_capsule(prim, a, b)
                             : pqp_model_set_box(prim, a, b, c)) != PQP_OK)
                die("set primitive");
            pqp_model* tri_prim = our_mesh(meshed(kind, a, b, c));
            std::shared_ptr<fcl::CollisionGeometryd> shape;
            if (kind == 0) shape = std::make_shared<fcl::Sphered>(a);
            else if (kind == 1) shape = std::make_shared<fcl::Capsuled>(a, b);
            else shape = std::make_shared<fcl::Boxd>(a, b, c);
            // Poses: the mesh fixed, the primitive around its centre.
            Rng rng(2026 + kind);
            std::vector<Pose> poses(static_cast<size_t>(queries));
            for (auto& p : poses) {
                p.R = bench::random_rotation(rng);
                for (int i = 0; i < 3; ++i) p.T[i] = centre[i] + (rng.uniform() - 0.5) * 1.1 * size;
            }
            const Pose id = {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};
            pqp_distance_result* dr = pqp_distance_result_create();
            pqp_collide_result* cr = pqp_collide_result_create();
            pqp_tolerance_result* tr = pqp_tolerance_result_create();
            const double tol = 0.02 * size;
            fcl::CollisionObjectd fo_mesh(fm, fcl_tf(id));
            fcl::CollisionObjectd fo_shape(shape, fcl_tf(id));
            double checksum = 0;
            // One timed pass of one library on one query: seconds per query.
            auto ours = [&](const pqp_model* m, int q) {
                const double t0 = now();
                for (const Pose& p : poses) {
                    if (q == 0) {
                        pqp_distance(dr, p.R.data(), p.T.data(), m, id.R.data(), id.T.data(), om, 0, 0, 2);
                        checksum += pqp_distance_result_distance(dr);
                    } else if (q == 1) {
                        pqp_collide(cr, p.R.data(), p.T.data(), m, id.R.data(), id.T.data(), om, PQP_FIRST_CONTACT);
                        checksum += pqp_collide_result_colliding(cr);
                    } else {
                        pqp_tolerance(tr, p.R.data(), p.T.data(), m, id.R.data(), id.T.data(), om, tol, 2);
                        checksum += pqp_tolerance_result_closer_than_tolerance(tr);
                    }
                }
                return (now() - t0) / queries;
            };
            auto theirs = [&](int q) {
                const double t0 = now();
                for (const Pose& p : poses) {
                    fo_shape.setTransform(fcl_tf(p));
                    if (q == 1) {
                        fcl::CollisionRequestd req;
                        fcl::CollisionResultd res;
                        fcl::collide(&fo_shape, &fo_mesh, req, res);
                        checksum += res.isCollision();
                    } else {
                        fcl::DistanceRequestd req(true);
                        fcl::DistanceResultd res;
                        fcl::distance(&fo_shape, &fo_mesh, req, res);
                        checksum += res.min_distance;
                    }
                }
                return (now() - t0) / queries;
            };
            const char* qname[3] = {"distance", "collision", "tolerance"};
            for (int q = 0; q < 3; ++q) {
                std::vector<double> t_ours, t_fcl, t_meshed;
                for (int r = 0; r < rounds; ++r) {
                    t_ours.push_back(ours(prim, q));
                    t_fcl.push_back(theirs(q));
                    t_meshed.push_back(ours(tri_prim, q));
                }
                const double o = median(t_ours), f = median(t_fcl), m = median(t_meshed);
                std::printf("| %s | %s | %s | %.2f | %.2f | %.2f | %.2fx | %.2fx |\n", name, kinds[kind], qname[q], o * 1e6,
                            f * 1e6, m * 1e6, f / o, m / o);
                std::fflush(stdout);
            }
            if (checksum == 12345.678) std::printf(" ");
            pqp_tolerance_result_destroy(tr);
            pqp_collide_result_destroy(cr);
            pqp_distance_result_destroy(dr);
            pqp_model_destroy(tri_prim);
            pqp_model_destroy(prim);
        }
        pqp_model_destroy(om);
    }
    return 0;
}
