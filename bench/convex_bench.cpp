// Benchmark: convex polyhedra, pqp-rs V-Clip (pqp_convex_*) against libccd 2.1 (GJK and MPR
// intersection) and FCL 0.7 (fcl::Convex distance), in one run. Run by hand; never a test.
//
//   (a) coherent motion: model 2 circles model 1, turning a little each frame, in and out of
//       contact; per-frame times for V-Clip warm (one pqp_convex_cache), V-Clip cold, libccd
//       ccdGJKIntersect and ccdMPRIntersect, FCL distance. Reports median / p90 / p99 and the median
//       per block of frames (near-constant with warm start).
//   (b) random poses: the same queries at independent random poses.
// Each method runs over all frames in its own pass (so each is timed hot). Checksums (intersecting
// counts, sum of distances over separated frames) must agree between methods.
// Output: Markdown.
#include <ccd/ccd.h>
#include <ccd/vec3.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <pqp/pqp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../c_tests/fcl_util.hpp"

namespace {

using Clock = std::chrono::steady_clock;

struct Rng {
    uint64_t s;
    uint64_t next() {
        s += 0x9e3779b97f4a7c15ull;
        uint64_t z = s;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double normal() {
        const double u = uniform() + 1e-300, v = uniform();
        return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
    }
};

struct Pose {
    double R[9];
    double T[3];
};

void axis_angle(const double a[3], double t, double R[9]) {
    const double c = std::cos(t), s = std::sin(t), C = 1 - c;
    const double x = a[0], y = a[1], z = a[2];
    const double m[9] = {c + x * x * C,     x * y * C - z * s, x * z * C + y * s, y * x * C + z * s, c + y * y * C,
                         y * z * C - x * s, z * x * C - y * s, z * y * C + x * s, c + z * z * C};
    std::memcpy(R, m, sizeof m);
}

void random_rotation(Rng &rng, double R[9]) {
    double a[3] = {rng.normal(), rng.normal(), rng.normal()};
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (double &x : a) x /= l;
    axis_angle(a, 2 * M_PI * rng.uniform(), R);
}

void mul(const double A[9], const double B[9], double C[9]) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

struct Hull {
    pqp_convex_model *m = nullptr;
    std::vector<double> v;  ///< hull vertices (model frame)
    std::shared_ptr<fcl::Convexd> fcl;
    double radius = 0;
    int nf = 0;
    ~Hull() { pqp_convex_model_destroy(m); }
};

/// Points on an ellipsoid with semi-axes (1, 0.8, 0.6): all on the hull.
void make_hull(Rng &rng, int n, Hull &h) {
    std::vector<double> p;
    for (int i = 0; i < n; ++i) {
        double d[3] = {rng.normal(), rng.normal(), rng.normal()};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        p.push_back(d[0] / l), p.push_back(0.8 * d[1] / l), p.push_back(0.6 * d[2] / l);
    }
    if (pqp_convex_model_from_points(&h.m, p.data(), n) != PQP_OK) std::abort();
    const int nv = pqp_convex_model_num_vertices(h.m);
    h.nf = pqp_convex_model_num_faces(h.m);
    h.v.resize(3 * static_cast<size_t>(nv));
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
    for (int i = 0; i < nv; ++i) {
        double *q = &h.v[3 * static_cast<size_t>(i)];
        pqp_convex_model_vertex(h.m, i, q);
        verts->emplace_back(q[0], q[1], q[2]);
        h.radius = std::max(h.radius, std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]));
    }
    auto faces = std::make_shared<std::vector<int>>();
    for (int f = 0; f < h.nf; ++f) {
        const int k = pqp_convex_model_face_num_vertices(h.m, f);
        std::vector<int> fv(static_cast<size_t>(k));
        pqp_convex_model_face(h.m, f, fv.data());
        faces->push_back(k);
        faces->insert(faces->end(), fv.begin(), fv.end());
    }
    h.fcl = std::make_shared<fcl::Convexd>(verts, h.nf, faces);
}

/// A posed hull for libccd: the support function maps the direction into the model's frame, scans
/// the vertices and maps the answer back (what a libccd user with a vertex list does).
struct CcdObj {
    const Hull *h;
    const Pose *p;
};

void support(const void *obj, const ccd_vec3_t *dir, ccd_vec3_t *out) {
    const CcdObj *o = static_cast<const CcdObj *>(obj);
    const double *R = o->p->R;
    const double d[3] = {R[0] * ccdVec3X(dir) + R[3] * ccdVec3Y(dir) + R[6] * ccdVec3Z(dir),
                         R[1] * ccdVec3X(dir) + R[4] * ccdVec3Y(dir) + R[7] * ccdVec3Z(dir),
                         R[2] * ccdVec3X(dir) + R[5] * ccdVec3Y(dir) + R[8] * ccdVec3Z(dir)};
    const std::vector<double> &v = o->h->v;
    size_t best = 0;
    double bd = -INFINITY;
    for (size_t i = 0; i < v.size(); i += 3) {
        const double x = v[i] * d[0] + v[i + 1] * d[1] + v[i + 2] * d[2];
        if (x > bd) bd = x, best = i;
    }
    const double *q = &v[best];
    ccdVec3Set(out, R[0] * q[0] + R[1] * q[1] + R[2] * q[2] + o->p->T[0], R[3] * q[0] + R[4] * q[1] + R[5] * q[2] + o->p->T[1],
               R[6] * q[0] + R[7] * q[1] + R[8] * q[2] + o->p->T[2]);
}

void center(const void *obj, ccd_vec3_t *out) {
    const CcdObj *o = static_cast<const CcdObj *>(obj);
    ccdVec3Set(out, o->p->T[0], o->p->T[1], o->p->T[2]);  // the model origins are inside the hulls
}

fcl::Transform3d tf(const Pose &p) { return fclu::transform(p.R, p.T); }

struct Run {
    std::string name;
    std::vector<double> ns;  ///< per query
    long intersecting = 0;
    double dist_sum = 0;  ///< over frames the method reports separated
    long separated = 0;
};

double pct(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

/// Runs every method over the poses (model 1 at the identity).
std::vector<Run> run_all(const Hull &a, const Hull &b, const std::vector<Pose> &poses, bool with_warm) {
    std::vector<Run> runs;
    const Pose id = {{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};
    pqp_convex_result *r = pqp_convex_result_create();
    auto timed = [&](const char *name, const std::function<void(const Pose &, Run &)> &q) {
        Run run;
        run.name = name;
        run.ns.reserve(poses.size());
        for (const Pose &p : poses) {
            const auto t0 = Clock::now();
            q(p, run);
            run.ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count());
        }
        runs.push_back(run);
    };
    auto ours = [&](pqp_convex_cache *cache) {
        return [&, cache](const Pose &p, Run &run) {
            pqp_convex_distance(r, id.R, id.T, a.m, p.R, p.T, b.m, cache);
            if (pqp_convex_result_intersecting(r)) ++run.intersecting;
            else run.dist_sum += pqp_convex_result_distance(r), ++run.separated;
        };
    };
    pqp_convex_cache *cache = pqp_convex_cache_create();
    if (with_warm) timed("pqp-rs V-Clip, warm (cache)", ours(cache));
    timed("pqp-rs V-Clip, cold", ours(nullptr));
    ccd_t ccd;
    CCD_INIT(&ccd);
    ccd.support1 = ccd.support2 = support;
    ccd.center1 = ccd.center2 = center;
    ccd.max_iterations = 1000;
    timed("libccd ccdGJKIntersect", [&](const Pose &p, Run &run) {
        CcdObj o1{&a, &id}, o2{&b, &p};
        if (ccdGJKIntersect(&o1, &o2, &ccd)) ++run.intersecting;
    });
    timed("libccd ccdMPRIntersect", [&](const Pose &p, Run &run) {
        CcdObj o1{&a, &id}, o2{&b, &p};
        if (ccdMPRIntersect(&o1, &o2, &ccd)) ++run.intersecting;
    });
    fcl::CollisionObjectd oa(a.fcl, tf(id)), ob(b.fcl, tf(id));
    timed("FCL 0.7 Convex distance", [&](const Pose &p, Run &run) {
        ob.setTransform(tf(p));
        fcl::DistanceRequestd req;
        fcl::DistanceResultd res;
        fcl::distance(&oa, &ob, req, res);
        if (res.min_distance <= 0) ++run.intersecting;
        else run.dist_sum += res.min_distance, ++run.separated;
    });
    pqp_convex_cache_destroy(cache);
    pqp_convex_result_destroy(r);
    return runs;
}

void table(const std::vector<Run> &runs, const Run &ref) {
    const double ref_med = pct(ref.ns, 0.5);
    std::printf("| method | median (us) | p90 (us) | p99 (us) | mean (us) | median ratio to %s | intersecting | separated: sum of distances |\n",
                ref.name.c_str());
    std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (const Run &r : runs) {
        double mean = 0;
        for (double x : r.ns) mean += x;
        mean /= static_cast<double>(r.ns.size());
        const bool has_d = r.separated > 0;
        std::printf("| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %ld | %s |\n", r.name.c_str(), pct(r.ns, 0.5) / 1e3,
                    pct(r.ns, 0.9) / 1e3, pct(r.ns, 0.99) / 1e3, mean / 1e3, pct(r.ns, 0.5) / ref_med, r.intersecting,
                    has_d ? (std::to_string(r.separated) + ": " + std::to_string(r.dist_sum)).c_str() : "-");
    }
    std::printf("\n");
}

void coherent(Rng &rng, int n, int frames) {
    Hull a, b;
    make_hull(rng, n, a);
    make_hull(rng, n, b);
    std::printf("### Coherent motion, %d + %d points (hulls of %d and %d vertices), %d frames\n\n", n, n,
                static_cast<int>(a.v.size() / 3), static_cast<int>(b.v.size() / 3), frames);
    double axis[3] = {0.3, 0.5, 0.81};
    const double l = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double &x : axis) x /= l;
    double R0[9];
    random_rotation(rng, R0);
    std::vector<Pose> poses(static_cast<size_t>(frames));
    const double rr = a.radius + b.radius;
    for (int f = 0; f < frames; ++f) {
        Pose &p = poses[static_cast<size_t>(f)];
        double Rt[9];
        axis_angle(axis, 0.01 * f, Rt);  // 0.01 rad per frame
        mul(Rt, R0, p.R);
        const double t = 2 * M_PI * f / 2000.0;  // one orbit per 2000 frames
        const double r = rr * (0.75 + 0.35 * std::cos(3 * t));  // in and out of contact
        p.T[0] = r * std::cos(t), p.T[1] = r * std::sin(t), p.T[2] = 0.2 * std::sin(5 * t);
    }
    std::vector<Run> runs = run_all(a, b, poses, true);
    table(runs, runs[0]);
    // Per-block medians: warm start stays flat across the path.
    const int blocks = 10, per = frames / blocks;
    std::printf("Median per block of %d frames (us):\n\n| method |", per);
    for (int k = 0; k < blocks; ++k) std::printf(" %d |", k);
    std::printf("\n| --- |");
    for (int k = 0; k < blocks; ++k) std::printf(" ---: |");
    std::printf("\n");
    for (const Run &r : runs) {
        std::printf("| %s |", r.name.c_str());
        for (int k = 0; k < blocks; ++k) {
            std::vector<double> blk(r.ns.begin() + k * per, r.ns.begin() + (k + 1) * per);
            std::printf(" %.2f |", pct(blk, 0.5) / 1e3);
        }
        std::printf("\n");
    }
    std::printf("\n");
}

void random_poses(Rng &rng, int n, int count) {
    Hull a, b;
    make_hull(rng, n, a);
    make_hull(rng, n, b);
    std::printf("### Random poses, %d + %d points (hulls of %d and %d vertices), %d poses\n\n", n, n,
                static_cast<int>(a.v.size() / 3), static_cast<int>(b.v.size() / 3), count);
    std::vector<Pose> poses(static_cast<size_t>(count));
    const double rr = a.radius + b.radius;
    for (Pose &p : poses) {
        random_rotation(rng, p.R);
        double d[3] = {rng.normal(), rng.normal(), rng.normal()};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double k = rr * (0.4 + 1.0 * rng.uniform());
        for (int i = 0; i < 3; ++i) p.T[i] = d[i] / l * k;
    }
    std::vector<Run> runs = run_all(a, b, poses, false);
    table(runs, runs[0]);
}

}  // namespace

int main(int argc, char **argv) {
    int frames = 5000, count = 3000;
    for (int i = 1; i + 1 < argc; ++i) {
        if (!std::strcmp(argv[i], "--frames")) frames = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--poses")) count = std::atoi(argv[++i]);
    }
    Rng rng{20240611};
    std::printf("## Convex polyhedra: V-Clip against libccd and FCL\n\n");
    std::printf("Times per query (steady_clock around each call, ~20-30 ns of it is the clock). "
                "FCL and libccd use a support function scanning the hull's vertices.\n\n");
    for (int n : {100, 1000}) coherent(rng, n, frames);
    for (int n : {100, 1000}) random_poses(rng, n, count);
    return 0;
}
