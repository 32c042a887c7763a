// Point queries: pqp_closest_point and pqp_signed_distance per query against brute force over all
// triangles and against FCL 0.7's distance between the mesh and a zero-radius sphere, in one run
// (see BENCHMARKS.md, "Point queries"). Run by hand; never a test.
//
//   point_bench [--models DIR] [--queries N] [--big N]
//
// Models: the bunny (DIR/bunny.tris) and, with --big N (default 1000000, 0 to skip), a UV sphere
// of about N triangles with smooth bumps (a closed, non-convex mesh). Points: N
// (default 20000) uniform in the model's bounding box grown by half its size on each side, the
// same for every library; poses random. Every answer is compared between the libraries.
#include <pqp/pqp.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
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

#include "brute.hpp"
#include "workloads.hpp"

using bench::Mesh;
using bench::Pose;
using bench::Rng;

namespace {

[[noreturn]] void die(const std::string& msg) {
    std::fprintf(stderr, "point_bench: %s\n", msg.c_str());
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

// A closed UV sphere of radius about 1 with smooth bumps (radius 1 + 0.2 sin(3 theta) cos(4 phi)),
// vertices shared exactly (so the surface has no crack); 2 * nlon * (nlat - 1) triangles.
Mesh lumpy_sphere(int nlat, int nlon) {
    std::vector<std::array<double, 3>> v;
    auto push = [&](double th, double ph) {
        const double s = 1.0 + 0.2 * std::sin(3.0 * th) * std::cos(4.0 * ph);
        v.push_back({s * std::sin(th) * std::cos(ph), s * std::sin(th) * std::sin(ph), s * std::cos(th)});
    };
    push(0.0, 0.0);
    for (int i = 1; i < nlat; ++i)
        for (int j = 0; j < nlon; ++j) push(bench::kPi * i / nlat, 2.0 * bench::kPi * j / nlon);
    push(bench::kPi, 0.0);
    const int south = static_cast<int>(v.size()) - 1;
    auto at = [&](int i, int j) { return i == 0 ? 0 : i == nlat ? south : 1 + (i - 1) * nlon + j % nlon; };
    auto tri = [&](int a, int b, int c) {
        return bench::Tri{v[a][0], v[a][1], v[a][2], v[b][0], v[b][1], v[b][2], v[c][0], v[c][1], v[c][2]};
    };
    Mesh m;
    for (int i = 0; i < nlat; ++i)
        for (int j = 0; j < nlon; ++j) {
            const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i + 1 < nlat) m.push_back(tri(a, b, c));
            if (i > 0) m.push_back(tri(a, c, d));
        }
    return m;
}

double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> build_fcl(const Mesh& mesh) {
    auto m = std::make_shared<fcl::BVHModel<BV>>();
    const int n = static_cast<int>(mesh.size());
    if (m->beginModel(n, 3 * n) != fcl::BVH_OK) die("FCL beginModel failed");
    for (const auto& t : mesh)
        m->addTriangle(fcl::Vector3d(t[0], t[1], t[2]), fcl::Vector3d(t[3], t[4], t[5]),
                       fcl::Vector3d(t[6], t[7], t[8]));
    if (m->endModel() != fcl::BVH_OK) die("FCL endModel failed");
    return m;
}

fcl::Transform3d to_fcl(const Pose& p) {
    fcl::Matrix3d R;
    R << p.R[0], p.R[1], p.R[2], p.R[3], p.R[4], p.R[5], p.R[6], p.R[7], p.R[8];
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(p.T[0], p.T[1], p.T[2]);
    return tf;
}

struct Query {
    Pose pose;
    std::array<double, 3> point;
};

// Per-query times of one method, microseconds.
struct Timing {
    double median = NAN, mean = NAN;
};

Timing time_each(size_t n, const std::function<void(size_t)>& f) {
    std::vector<double> t(n);
    for (size_t i = 0; i < n; ++i) {
        const double t0 = now();
        f(i);
        t[i] = (now() - t0) * 1e6;
    }
    Timing r;
    double sum = 0;
    for (double x : t) sum += x;
    r.mean = sum / static_cast<double>(n);
    std::nth_element(t.begin(), t.begin() + static_cast<long>(n / 2), t.end());
    r.median = t[n / 2];
    return r;
}

template <class BV>
Timing time_fcl(const Mesh& mesh, const std::vector<Query>& qs, const std::vector<double>& ours,
                const char* name) {
    const double t0 = now();
    auto model = build_fcl<BV>(mesh);
    const double build = now() - t0;
    auto sphere = std::make_shared<fcl::Sphered>(0.0);
    std::vector<fcl::Transform3d> poses;
    for (const auto& q : qs) poses.push_back(to_fcl(q.pose));
    fcl::DistanceRequestd req;
    req.enable_nearest_points = true;
    double worst = 0;
    std::vector<double> got(qs.size());
    Timing t = time_each(qs.size(), [&](size_t i) {
        fcl::Transform3d at = fcl::Transform3d::Identity();
        at.translation() = fcl::Vector3d(qs[i].point[0], qs[i].point[1], qs[i].point[2]);
        fcl::DistanceResultd res;
        fcl::distance(model.get(), poses[i], sphere.get(), at, req, res);
        got[i] = res.min_distance;
    });
    for (size_t i = 0; i < qs.size(); ++i) worst = std::max(worst, std::fabs(got[i] - ours[i]));
    std::printf("| FCL distance to a zero-radius sphere, BVHModel<%s> | %.2f | %.2f | largest difference %.1e; build %.0f ms |\n",
                name, t.median, t.mean, worst, build * 1e3);
    return t;
}

void run(const std::string& name, const Mesh& mesh, size_t nq, size_t nbrute, Rng& rng) {
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& t : mesh)
        for (int k = 0; k < 9; ++k) {
            lo[k % 3] = std::min(lo[k % 3], t[k]);
            hi[k % 3] = std::max(hi[k % 3], t[k]);
        }
    const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    std::vector<Query> qs(nq);
    for (auto& q : qs) {
        q.pose.R = bench::random_rotation(rng);
        for (double& x : q.pose.T) x = 2.0 * rng.uniform() - 1.0;
        std::array<double, 3> m;  // in the model's frame, then posed
        for (int k = 0; k < 3; ++k) m[k] = lo[k] - 0.5 * size + 2.0 * size * rng.uniform();
        for (int r = 0; r < 3; ++r)
            q.point[r] = q.pose.R[3 * r] * m[0] + q.pose.R[3 * r + 1] * m[1] + q.pose.R[3 * r + 2] * m[2] + q.pose.T[r];
    }
    std::printf("\n### %s: %zu triangles, %zu queries\n\n", name.c_str(), mesh.size(), nq);
    std::printf("| method | median us/query | mean us/query | notes |\n| --- | --- | --- | --- |\n");

    double t0 = now();
    pqp_model* m = pqp_model_create();
    if (pqp_model_begin(m, static_cast<int>(mesh.size())) != PQP_OK) die("begin");
    for (size_t i = 0; i < mesh.size(); ++i)
        if (pqp_model_add_tri(m, &mesh[i][0], &mesh[i][3], &mesh[i][6], static_cast<int>(i)) != PQP_OK) die("add");
    if (pqp_model_end(m) != PQP_OK) die("end");
    const double build = now() - t0;
    const double mem_before = static_cast<double>(pqp_model_memory_usage(m));

    std::vector<double> dist(nq), sd(nq);
    Timing tc = time_each(nq, [&](size_t i) {
        pqp_point_result r;
        if (pqp_closest_point(&r, qs[i].pose.R.data(), qs[i].pose.T.data(), m, qs[i].point.data(), INFINITY) != PQP_OK)
            die("pqp_closest_point");
        dist[i] = r.distance;
    });
    std::printf("| pqp_closest_point | %.2f | %.2f | build %.0f ms, %.0f B/triangle |\n", tc.median, tc.mean,
                build * 1e3, mem_before / static_cast<double>(mesh.size()));

    t0 = now();
    double first;
    if (pqp_signed_distance(&first, qs[0].pose.R.data(), qs[0].pose.T.data(), m, qs[0].point.data()) != PQP_OK)
        die("pqp_signed_distance");
    const double first_call = now() - t0;
    const double mem_after = static_cast<double>(pqp_model_memory_usage(m));
    int inside = 0;
    Timing ts = time_each(nq, [&](size_t i) {
        if (pqp_signed_distance(&sd[i], qs[i].pose.R.data(), qs[i].pose.T.data(), m, qs[i].point.data()) != PQP_OK)
            die("pqp_signed_distance");
        inside += sd[i] < 0;
    });
    double worst = 0;
    for (size_t i = 0; i < nq; ++i) worst = std::max(worst, std::fabs(std::fabs(sd[i]) - dist[i]));
    std::printf("| pqp_signed_distance | %.2f | %.2f | %d of %zu inside; first call (builds the boundary edges) %.1f ms, then %.0f B/triangle (+%.0f); |sd| - distance <= %.1e |\n",
                ts.median, ts.mean, inside, nq, first_call * 1e3, mem_after / static_cast<double>(mesh.size()),
                (mem_after - mem_before) / static_cast<double>(mesh.size()), worst);

    // Brute force over all triangles (and the O(n) winding sum), on the first nbrute queries.
    const size_t nb = std::min(nbrute, nq);
    std::vector<brute::WTri> placed;
    double worst_brute = 0, worst_sign = 0;
    Timing tb = time_each(nb, [&](size_t i) {
        placed = brute::place(mesh, qs[i].pose);
        double d = INFINITY;
        const brute::V p = qs[i].point;
        for (const auto& t : placed) d = std::min(d, brute::point_triangle(p, t.v[0], t.v[1], t.v[2]));
        worst_brute = std::max(worst_brute, std::fabs(d - dist[i]));
    });
    std::printf("| brute force: every triangle (posed each query) | %.2f | %.2f | %zu queries; largest difference %.1e |\n",
                tb.median, tb.mean, nb, worst_brute);
    Timing tw = time_each(nb, [&](size_t i) {
        placed = brute::place(mesh, qs[i].pose);
        const brute::V p = qs[i].point;
        double w = 0, d = INFINITY;
        for (const auto& t : placed) {
            d = std::min(d, brute::point_triangle(p, t.v[0], t.v[1], t.v[2]));
            const brute::V a = brute::sub(t.v[0], p), b = brute::sub(t.v[1], p), c = brute::sub(t.v[2], p);
            const double la = brute::norm(a), lb = brute::norm(b), lc = brute::norm(c);
            const double det = brute::dot(a, brute::cross(b, c));
            const double den = la * lb * lc + brute::dot(a, b) * lc + brute::dot(a, c) * lb + brute::dot(b, c) * la;
            w += 2.0 * std::atan2(det, den);
        }
        w /= 4.0 * bench::kPi;
        const double s = std::fabs(w) >= 0.5 ? -d : d;
        if ((s < 0) != (sd[i] < 0) && d > 1e-9) worst_sign = std::max(worst_sign, d);
    });
    std::printf("| brute force: signed (distance and winding sum over every triangle) | %.2f | %.2f | %zu queries; sign disagreements %s |\n",
                tw.median, tw.mean, nb, worst_sign > 0 ? "found" : "none");

    time_fcl<fcl::RSSd>(mesh, qs, dist, "RSS");
    time_fcl<fcl::OBBRSSd>(mesh, qs, dist, "OBBRSS");
    pqp_model_destroy(m);
}

}  // namespace

int main(int argc, char** argv) {
    std::string dir = PQP_BENCH_MODELS_DIR;
    size_t nq = 20000, big = 1000000;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--models" && i + 1 < argc) dir = argv[++i];
        else if (a == "--queries" && i + 1 < argc) nq = std::strtoul(argv[++i], nullptr, 10);
        else if (a == "--big" && i + 1 < argc) big = std::strtoul(argv[++i], nullptr, 10);
        else die("usage: point_bench [--models DIR] [--queries N] [--big N]");
    }
    Rng rng(22);
    run("bunny", load_tris(dir + "/bunny.tris"), nq, nq / 10, rng);
    if (big > 0) {
        const int nlat = static_cast<int>(std::sqrt(static_cast<double>(big) / 4.0));
        run("bumpy sphere", lumpy_sphere(nlat, 2 * nlat), nq / 4, 20, rng);
    }
    return 0;
}
