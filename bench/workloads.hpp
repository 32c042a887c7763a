// Deterministic meshes and poses for the benchmark workloads.
//
// The generator is deliberately simple and written out in full so that
// examples/bvtt_efficiency.rs can reproduce workload 1 bit for bit: a SplitMix64 stream, uniform
// doubles from its top 53 bits, rotations from unit quaternions (Shoemake's subgroup method), and UV
// spheres from sin/cos of `pi * i / n`. Only +, -, *, /, sqrt, sin and cos are used, in the order
// written, so the same libm gives the same bits in C++ and Rust (do not build with -ffast-math or
// with FMA contraction enabled).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64 (Steele, Lea and Flood 2014).
class Rng {
public:
    explicit Rng(uint64_t seed) : state_(seed) {}
    uint64_t next_u64() {
        state_ += 0x9E3779B97F4A7C15ULL;
        uint64_t z = state_;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    // Uniform in [0, 1).
    double uniform() { return static_cast<double>(next_u64() >> 11) * (1.0 / 9007199254740992.0); }

private:
    uint64_t state_;
};

// A pose as PQP takes it: R row-major (columns are the model's axes in world coordinates), T.
struct Pose {
    std::array<double, 9> R;
    std::array<double, 3> T;
};

using Tri = std::array<double, 9>;  // x1 y1 z1 x2 y2 z2 x3 y3 z3
using Mesh = std::vector<Tri>;

// A uniformly distributed rotation: three uniforms in this order u1, u2, u3; quaternion
// (w, x, y, z) = (sqrt(u1) cos(2 pi u3), sqrt(1-u1) sin(2 pi u2), sqrt(1-u1) cos(2 pi u2),
// sqrt(u1) sin(2 pi u3)); then the usual unit-quaternion matrix.
inline std::array<double, 9> random_rotation(Rng& rng) {
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const double u3 = rng.uniform();
    const double s1 = std::sqrt(1.0 - u1);
    const double s2 = std::sqrt(u1);
    const double a = 2.0 * kPi * u2;
    const double b = 2.0 * kPi * u3;
    const double w = s2 * std::cos(b);
    const double x = s1 * std::sin(a);
    const double y = s1 * std::cos(a);
    const double z = s2 * std::sin(b);
    return {1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z),       2.0 * (x * z + w * y),
            2.0 * (x * y + w * z),       1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x),
            2.0 * (x * z - w * y),       2.0 * (y * z + w * x),       1.0 - 2.0 * (x * x + y * y)};
}

// A uniformly distributed unit vector: z = 2 u1 - 1, phi = 2 pi u2.
inline std::array<double, 3> random_direction(Rng& rng) {
    const double z = 2.0 * rng.uniform() - 1.0;
    const double phi = 2.0 * kPi * rng.uniform();
    const double r = std::sqrt(1.0 - z * z);
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// A UV sphere: vertex (i, j) at polar angle pi*i/nlat (i = 0..nlat) and azimuth 2*pi*j/nlon, on the
// sphere of the given radius (so the mesh is inscribed). The cap bands (i = 0 and i = nlat-1) have
// one triangle per slice, the others two: 2 * nlon * (nlat - 1) triangles, ids in order.
inline Mesh uv_sphere(double radius, int nlat, int nlon) {
    auto vertex = [&](int i, int j) {
        const double theta = kPi * static_cast<double>(i) / static_cast<double>(nlat);
        const double phi = 2.0 * kPi * static_cast<double>(j) / static_cast<double>(nlon);
        const double st = std::sin(theta);
        return std::array<double, 3>{radius * st * std::cos(phi), radius * st * std::sin(phi),
                                     radius * std::cos(theta)};
    };
    auto tri = [](const std::array<double, 3>& a, const std::array<double, 3>& b,
                  const std::array<double, 3>& c) {
        return Tri{a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2]};
    };
    Mesh m;
    m.reserve(static_cast<size_t>(2 * nlon * (nlat - 1)));
    for (int i = 0; i < nlat; ++i) {
        for (int j = 0; j < nlon; ++j) {
            const int j1 = (j + 1) % nlon;
            if (i == 0) {
                m.push_back(tri(vertex(0, j), vertex(1, j), vertex(1, j1)));
            } else if (i == nlat - 1) {
                m.push_back(tri(vertex(i, j), vertex(nlat, j), vertex(i, j1)));
            } else {
                m.push_back(tri(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j1)));
                m.push_back(tri(vertex(i, j), vertex(i + 1, j1), vertex(i, j1)));
            }
        }
    }
    return m;
}

// Workload 1 ("spheres-distance"): seed 1; 400 poses, 100 for each gap in {0.001, 0.01, 0.1, 1} in
// that order. Per pose: R1 = random_rotation, R2 = random_rotation, dir = random_direction;
// T1 = 0, T2 = dir * (2 + gap), so the two unit spheres' surfaces are `gap` apart.
struct SpherePose {
    Pose p1, p2;
    double gap;
};

inline std::vector<SpherePose> spheres_poses(int per_gap = 100) {
    Rng rng(1);
    const double gaps[4] = {0.001, 0.01, 0.1, 1.0};
    std::vector<SpherePose> out;
    for (double gap : gaps) {
        for (int k = 0; k < per_gap; ++k) {
            SpherePose sp;
            sp.gap = gap;
            sp.p1.R = random_rotation(rng);
            sp.p2.R = random_rotation(rng);
            const auto dir = random_direction(rng);
            sp.p1.T = {0.0, 0.0, 0.0};
            const double c = 2.0 + gap;
            sp.p2.T = {dir[0] * c, dir[1] * c, dir[2] * c};
            out.push_back(sp);
        }
    }
    return out;
}

// UV sphere resolution giving 40,000 triangles (2 * 200 * 100).
constexpr int kSphereLat = 101;
constexpr int kSphereLon = 200;

}  // namespace bench
