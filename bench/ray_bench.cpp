// Ray casting: pqp-rs (pqp_ray_cast, pqp_ray_cast_batch) against Embree 3 (rtcIntersect1), same
// meshes, same rays, same process. See BENCHMARKS.md, "Ray casting".
//
//   ray_bench [--models DIR] [--rays N] [--big-rays N] [--big SLICES] [--reps N]
//
// Meshes: the bunny (DIR/bunny.tris) and a bumpy sphere of 2 * SLICES * SLICES / 2 triangles
// (default SLICES 1000: a million triangles), built by this program. Rays: from random points on a
// sphere of 2.5 model radii around the model, aimed at random points of the ball of 0.8 radii
// (most hit), one in five in a random direction (most miss); max_t infinite.
//
// Timing: each form casts every ray `reps` times (default 3) and keeps its fastest pass (the
// machine is shared; the minimum is the least noisy estimate). One-thread forms are timed in the
// thread's CPU time (CLOCK_THREAD_CPUTIME_ID), the batch on two threads in wall time. Embree runs on a device limited to
// one thread, with its default (not robust) intersection and its default build; it works in single
// precision, so its hits are compared with ours rather than required to be identical.

#include <pqp/pqp.h>

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <time.h>
#include <vector>

#ifndef PQP_BENCH_MODELS_DIR
#define PQP_BENCH_MODELS_DIR "/work/shared/models"
#endif

namespace {

using Clock = std::chrono::steady_clock;

struct Mesh {
    std::string name;
    std::vector<double> tris;  // 9 per triangle
    size_t count() const { return tris.size() / 9; }
};

// SplitMix64, as the tests' generator.
struct Rng {
    uint64_t s;
    uint64_t next()
    {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double unit() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); }
    double signed_unit() { return 2.0 * unit() - 1.0; }
    void direction(double d[3])
    {
        for (;;) {
            for (int k = 0; k < 3; k++) d[k] = signed_unit();
            double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (n > 0.1 && n <= 1.0) {
                for (int k = 0; k < 3; k++) d[k] /= n;
                return;
            }
        }
    }
};

Mesh load(const std::string &path)
{
    std::ifstream f(path);
    Mesh m;
    m.name = path.substr(path.find_last_of('/') + 1);
    size_t n = 0;
    if (!(f >> n)) {
        std::fprintf(stderr, "cannot read %s\n", path.c_str());
        std::exit(1);
    }
    m.tris.resize(9 * n);
    for (double &v : m.tris) f >> v;
    return m;
}

// A closed bumpy sphere: latitude-longitude grid, radius 1 + 0.05 sin(13 th) sin(17 ph).
Mesh bumpy_sphere(int slices)
{
    const int stacks = slices / 2;
    const double pi = 3.14159265358979323846;
    auto pt = [&](int i, int j, double *out) {
        double th = pi * i / stacks, ph = 2 * pi * (j % slices) / slices;
        double r = 1.0 + 0.05 * std::sin(13 * th) * std::sin(17 * ph);
        double s = (i == 0 || i == stacks) ? 0.0 : std::sin(th);
        out[0] = r * s * std::cos(ph);
        out[1] = r * s * std::sin(ph);
        out[2] = r * (i == 0 ? 1.0 : i == stacks ? -1.0 : std::cos(th));
    };
    Mesh m;
    m.name = "bumpy sphere";
    m.tris.reserve((size_t)18 * slices * stacks);
    for (int i = 0; i < stacks; i++) {
        for (int j = 0; j < slices; j++) {
            double a[3], b[3], c[3], d[3];
            pt(i, j, a);
            pt(i + 1, j, b);
            pt(i + 1, j + 1, c);
            pt(i, j + 1, d);
            if (i != 0) m.tris.insert(m.tris.end(), {a[0], a[1], a[2], b[0], b[1], b[2], d[0], d[1], d[2]});
            if (i != stacks - 1)
                m.tris.insert(m.tris.end(), {b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]});
        }
    }
    return m;
}

struct Rays {
    std::vector<double> o, d;  // 3 per ray
    size_t count() const { return o.size() / 3; }
};

Rays make_rays(const Mesh &m, size_t n, uint64_t seed)
{
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (size_t i = 0; i < m.tris.size(); i++) {
        lo[i % 3] = std::min(lo[i % 3], m.tris[i]);
        hi[i % 3] = std::max(hi[i % 3], m.tris[i]);
    }
    double c[3], r = 0;
    for (int k = 0; k < 3; k++) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        r = std::max(r, 0.5 * (hi[k] - lo[k]));
    }
    Rng rng{seed};
    Rays rays;
    for (size_t i = 0; i < n; i++) {
        double u[3], v[3];
        rng.direction(u);
        for (int k = 0; k < 3; k++) rays.o.push_back(c[k] + 2.5 * r * u[k]);
        if (i % 5 == 4) {
            rng.direction(v);
            for (int k = 0; k < 3; k++) rays.d.push_back(v[k]);
        } else {
            rng.direction(v);
            double s = 0.8 * r * std::cbrt(rng.unit());
            for (int k = 0; k < 3; k++) rays.d.push_back(c[k] + s * v[k] - rays.o[3 * i + k]);
        }
    }
    return rays;
}

// The calling thread's CPU time: what one-thread forms are timed with, so that time the thread
// spends descheduled on the shared machine is not counted.
double thread_seconds()
{
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double wall_seconds() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

// The fastest of `reps` runs of `f`, by the clock `now`.
double best_of(int reps, double (*now)(), const std::function<void()> &f)
{
    double best = 1e300;
    for (int r = 0; r < reps; r++) {
        double t0 = now();
        f();
        best = std::min(best, now() - t0);
    }
    return best;
}

const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
const double T0[3] = {0, 0, 0};

void run(const Mesh &mesh, size_t nrays, int reps, RTCDevice dev)
{
    const size_t nt = mesh.count();
    // Ours.
    auto b0 = Clock::now();
    pqp_model *m = pqp_model_create();
    pqp_model_begin(m, (int)nt);
    for (size_t i = 0; i < nt; i++) {
        const double *t = &mesh.tris[9 * i];
        if (pqp_model_add_tri(m, t, t + 3, t + 6, (int)i) != PQP_OK) std::exit(1);
    }
    if (pqp_model_end(m) != PQP_OK) std::exit(1);
    double ours_build = std::chrono::duration<double>(Clock::now() - b0).count();

    // Embree: float vertices, one per corner.
    b0 = Clock::now();
    RTCScene scene = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = (float *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                 3 * sizeof(float), 3 * nt);
    unsigned *ib = (unsigned *)rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0,
                                                       RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt);
    for (size_t i = 0; i < 9 * nt; i++) vb[i] = (float)mesh.tris[i];
    for (size_t i = 0; i < 3 * nt; i++) ib[i] = (unsigned)i;
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    double embree_build = std::chrono::duration<double>(Clock::now() - b0).count();

    Rays rays = make_rays(mesh, nrays, 0x5eed + nt);
    const size_t n = rays.count();
    std::vector<pqp_ray_hit> single(n), batch(n);
    std::vector<RTCRayHit> eh(n);

    double t_single = best_of(reps, thread_seconds, [&] {
        for (size_t i = 0; i < n; i++)
            pqp_ray_cast(&single[i], I, T0, m, &rays.o[3 * i], &rays.d[3 * i], INFINITY);
    });
    double t_batch = best_of(reps, wall_seconds, [&] {
        pqp_ray_cast_batch(batch.data(), n, I, T0, m, rays.o.data(), rays.d.data(), INFINITY, 2);
    });
    double t_embree = best_of(reps, thread_seconds, [&] {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (size_t i = 0; i < n; i++) {
            RTCRayHit &h = eh[i];
            h.ray.org_x = (float)rays.o[3 * i];
            h.ray.org_y = (float)rays.o[3 * i + 1];
            h.ray.org_z = (float)rays.o[3 * i + 2];
            h.ray.dir_x = (float)rays.d[3 * i];
            h.ray.dir_y = (float)rays.d[3 * i + 1];
            h.ray.dir_z = (float)rays.d[3 * i + 2];
            h.ray.tnear = 0.0f;
            h.ray.tfar = std::numeric_limits<float>::infinity();
            h.ray.mask = 0xFFFFFFFFu;
            h.ray.flags = 0;
            h.ray.time = 0.0f;
            h.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            h.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(scene, &ctx, &h);
        }
    });

    // Agreement.
    size_t hits = 0, same_tri = 0, same_miss = 0, differ = 0, batch_differ = 0;
    double max_rel_t = 0;
    for (size_t i = 0; i < n; i++) {
        bool ours = single[i].triangle >= 0, theirs = eh[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
        hits += ours;
        if (ours && theirs && (unsigned)single[i].triangle == eh[i].hit.primID) {
            same_tri++;
            max_rel_t = std::max(max_rel_t, std::fabs(single[i].t - eh[i].ray.tfar) / single[i].t);
        } else if (!ours && !theirs) {
            same_miss++;
        } else {
            differ++;
        }
        batch_differ += std::memcmp(&single[i].t, &batch[i].t, sizeof(double)) != 0 ||
                        single[i].triangle != batch[i].triangle;
    }
    std::printf("| %s | %zu | %zu | %.0f%% | %.2f | %.2f | %.2f | %.2fx | %.2fx | %.3f / %.3f |\n",
                mesh.name.c_str(), nt, n, 100.0 * hits / n, n / t_single / 1e6, n / t_batch / 1e6,
                n / t_embree / 1e6, t_single / t_embree, t_batch / t_embree, ours_build,
                embree_build);
    std::printf("\n    %s: same triangle %zu, both miss %zu, differ %zu (of %zu); largest relative t "
                "difference on the same triangle %.2g; batch vs single: %zu differ\n\n",
                mesh.name.c_str(), same_tri, same_miss, differ, n, max_rel_t, batch_differ);
    std::fflush(stdout);
    rtcReleaseScene(scene);
    pqp_model_destroy(m);
}

}  // namespace

int main(int argc, char **argv)
{
    std::string dir = PQP_BENCH_MODELS_DIR;
    size_t nrays = 200000, big_rays = 200000;
    int reps = 3, slices = 1000;
    for (int i = 1; i < argc; i++) {
        std::string a = argv[i];
        auto next = [&]() -> const char * {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--models") dir = next();
        else if (a == "--rays") nrays = std::strtoull(next(), nullptr, 10);
        else if (a == "--big-rays") big_rays = std::strtoull(next(), nullptr, 10);
        else if (a == "--big") slices = std::atoi(next());
        else if (a == "--reps") reps = std::atoi(next());
        else {
            std::fprintf(stderr, "unknown option %s\n", a.c_str());
            return 2;
        }
    }
    RTCDevice dev = rtcNewDevice("threads=1");
    if (!dev) {
        std::fprintf(stderr, "rtcNewDevice failed\n");
        return 1;
    }
    std::printf("| mesh | triangles | rays | hit | ours, 1 thread (Mrays/s) | ours, batch on 2 threads "
                "(Mrays/s) | Embree rtcIntersect1, 1 thread (Mrays/s) | ours 1 thread / Embree "
                "(time) | ours batch / Embree (time) | build, ours / Embree (s) |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    run(load(dir + "/bunny.tris"), nrays, reps, dev);
    if (slices > 0) run(bumpy_sphere(slices), big_rays, reps, dev);
    rtcReleaseDevice(dev);
    return 0;
}
