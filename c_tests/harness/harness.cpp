#include "harness.hpp"

// The seeding generator, shared with every C and C++ test.
#include "../../c_api_tests/check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>

namespace ht {

// ---------------------------------------------------------------------------------------------------

Rng::Rng(uint64_t seed) {
    for (auto &s : s_) s = check_splitmix64(&seed);
}

static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

uint64_t Rng::next() {
    const uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
}

double Rng::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
double Rng::uniform(double a, double b) { return a + (b - a) * uniform(); }
double Rng::log_uniform(double a, double b) { return std::exp(uniform(std::log(a), std::log(b))); }
int Rng::below(int n) { return static_cast<int>(uniform() * n) % n; }
double Rng::normal() {
    double u = uniform();
    while (u <= 0) u = uniform();
    return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * uniform());
}

// ---------------------------------------------------------------------------------------------------
double Mesh::radius() const {
    double r = 0;
    for (const Tri &t : tris)
        for (const auto &p : t.p) r = std::max(r, std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]));
    return r;
}

static Tri tri_of(const double *a, const double *b, const double *c) {
    Tri t;
    for (int k = 0; k < 3; ++k) {
        t.p[0][k] = a[k];
        t.p[1][k] = b[k];
        t.p[2][k] = c[k];
    }
    return t;
}

Mesh make_sphere(double r, int nlat, int nlon) {
    // Vertex table first so that shared vertices are bit-identical.
    std::vector<std::array<double, 3>> v;
    auto idx = [&](int i, int j) { return static_cast<size_t>(i) * nlon + static_cast<size_t>(j % nlon); };
    for (int i = 0; i <= nlat; ++i)
        for (int j = 0; j < nlon; ++j) {
            const double th = M_PI * i / nlat, ph = 2 * M_PI * j / nlon;
            if (i == 0 || i == nlat) v.push_back({0, 0, i == 0 ? r : -r});
            else v.push_back({r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
        }
    Mesh m;
    m.name = fmt("sphere%dx%d", nlat, nlon);
    for (int i = 0; i < nlat; ++i)
        for (int j = 0; j < nlon; ++j) {
            const double *a = v[idx(i, j)].data(), *b = v[idx(i + 1, j)].data();
            const double *c = v[idx(i + 1, j + 1)].data(), *d = v[idx(i, j + 1)].data();
            if (i != nlat - 1) m.tris.push_back(tri_of(a, b, c));
            if (i != 0) m.tris.push_back(tri_of(a, c, d));
        }
    return m;
}

Mesh make_torus(double R, double r, int nu, int nv) {
    std::vector<std::array<double, 3>> v;
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * M_PI * i / nu, w = 2 * M_PI * j / nv;
            v.push_back({(R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w)});
        }
    auto at = [&](int i, int j) { return v[static_cast<size_t>(i % nu) * nv + static_cast<size_t>(j % nv)].data(); };
    Mesh m;
    m.name = fmt("torus%dx%d", nu, nv);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            m.tris.push_back(tri_of(at(i, j), at(i + 1, j), at(i + 1, j + 1)));
            m.tris.push_back(tri_of(at(i, j), at(i + 1, j + 1), at(i, j + 1)));
        }
    return m;
}

Mesh make_soup(Rng &rng, int n, double box, double size) {
    Mesh m;
    m.name = fmt("soup%d", n);
    for (int k = 0; k < n; ++k) {
        double c[3], p[3][3];
        for (double &x : c) x = rng.uniform(-box, box);
        for (auto &q : p)
            for (int i = 0; i < 3; ++i) q[i] = c[i] + size * rng.uniform(-1, 1);
        m.tris.push_back(tri_of(p[0], p[1], p[2]));
    }
    return m;
}

Mesh make_thin(Rng &rng, int n, double box, double size) {
    Mesh m;
    m.name = fmt("thin%d", n);
    for (int k = 0; k < n; ++k) {
        double a[3], b[3], c[3];
        for (int i = 0; i < 3; ++i) {
            a[i] = rng.uniform(-box, box);
            b[i] = a[i] + size * rng.uniform(-1, 1);
        }
        const double eps = size * rng.log_uniform(1e-9, 1e-3);
        switch (k % 6) {
        case 0:  // sliver: apex close to the middle of the base
            for (int i = 0; i < 3; ++i) c[i] = 0.5 * (a[i] + b[i]) + eps * rng.uniform(-1, 1);
            break;
        case 1:  // needle: two vertices nearly equal
            for (int i = 0; i < 3; ++i) c[i] = b[i] + eps * rng.uniform(-1, 1);
            break;
        case 2:  // collinear (up to rounding of the midpoint)
            for (int i = 0; i < 3; ++i) c[i] = a[i] + 0.25 * (b[i] - a[i]);
            break;
        case 3:  // segment: repeated vertex
            std::memcpy(c, a, sizeof c);
            break;
        case 4:  // point
            std::memcpy(b, a, sizeof b);
            std::memcpy(c, a, sizeof c);
            break;
        default:  // ordinary
            for (int i = 0; i < 3; ++i) c[i] = a[i] + size * rng.uniform(-1, 1);
        }
        m.tris.push_back(tri_of(a, b, c));
    }
    return m;
}

Mesh make_flat(Rng &rng, int n, double extent) {
    Mesh m;
    m.name = fmt("flat%d", n);
    for (int k = 0; k < n; ++k) {
        double a[3] = {rng.uniform(-extent, extent), rng.uniform(-extent, extent), 0}, b[3], c[3];
        const double size = rng.log_uniform(1e-3, 0.5), eps = size * rng.log_uniform(1e-9, 1e-3);
        b[0] = a[0] + size * rng.uniform(-1, 1);
        b[1] = a[1] + size * rng.uniform(-1, 1);
        b[2] = 0;
        switch (k % 5) {
        case 0:  // point
            std::memcpy(b, a, sizeof b);
            std::memcpy(c, a, sizeof c);
            break;
        case 1:  // segment
            std::memcpy(c, b, sizeof c);
            break;
        case 2:  // collinear up to rounding
            for (int i = 0; i < 3; ++i) c[i] = a[i] + 0.75 * (b[i] - a[i]);
            break;
        case 3:  // sliver
            c[0] = 0.5 * (a[0] + b[0]) + eps * rng.uniform(-1, 1);
            c[1] = 0.5 * (a[1] + b[1]) + eps * rng.uniform(-1, 1);
            c[2] = 0;
            break;
        default:  // ordinary
            c[0] = a[0] + size * rng.uniform(-1, 1);
            c[1] = a[1] + size * rng.uniform(-1, 1);
            c[2] = 0;
        }
        m.tris.push_back(tri_of(a, b, c));
    }
    return m;
}

Mesh make_grid(int nx, int ny) {
    Mesh m;
    m.name = fmt("grid%dx%d", nx, ny);
    m.exact = true;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const double a[3] = {double(i), double(j), 0}, b[3] = {double(i + 1), double(j), 0};
            const double c[3] = {double(i + 1), double(j + 1), 0}, d[3] = {double(i), double(j + 1), 0};
            m.tris.push_back(tri_of(a, b, c));
            m.tris.push_back(tri_of(a, c, d));
        }
    return m;
}

Mesh make_cube() {
    Mesh m;
    m.name = "cube";
    m.exact = true;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            double q[4][3];
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const int su[4] = {-1, 1, 1, -1}, sw[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                q[k][axis] = side;
                q[k][u] = su[k];
                q[k][w] = sw[k];
            }
            m.tris.push_back(tri_of(q[0], q[1], q[2]));
            m.tris.push_back(tri_of(q[0], q[2], q[3]));
        }
    return m;
}

Mesh make_box(int nsub) {
    Mesh m;
    m.name = fmt("box%d", nsub);
    auto c = [&](int i) { return -1.0 + 2.0 * i / nsub; };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            for (int i = 0; i < nsub; ++i)
                for (int j = 0; j < nsub; ++j) {
                    double q[4][3];
                    const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
                    for (int k = 0; k < 4; ++k) {
                        q[k][axis] = side;
                        q[k][u] = c(i + di[k]);
                        q[k][w] = c(j + dj[k]);
                    }
                    m.tris.push_back(tri_of(q[0], q[1], q[2]));
                    m.tris.push_back(tri_of(q[0], q[2], q[3]));
                }
        }
    return m;
}

bool load_tris(const std::string &path, Mesh *out) {
    std::ifstream in(path);
    if (!in) return false;
    long n = 0;
    if (!(in >> n) || n <= 0 || n > 10000000) return false;
    Mesh m;
    m.tris.resize(static_cast<size_t>(n));
    for (Tri &t : m.tris)
        for (auto &p : t.p)
            for (double &x : p)
                if (!(in >> x)) return false;
    const size_t slash = path.find_last_of('/');
    m.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
    *out = std::move(m);
    return true;
}

std::string find_model(const Options &o, const std::string &file) {
    for (const std::string &d : o.models_dirs) {
        const std::string p = d + "/" + file;
        if (FILE *f = std::fopen(p.c_str(), "r")) {
            std::fclose(f);
            return p;
        }
    }
    return "";
}

Mesh load_or(const Options &o, const std::string &file, const Mesh &fallback) {
    Mesh m;
    const std::string p = find_model(o, file);
    if (!p.empty() && load_tris(p, &m)) return m;
    std::printf("note: %s not found in [%s], using a generated %s instead\n", file.c_str(), join(o.models_dirs).c_str(),
                fallback.name.c_str());
    return fallback;
}

Mesh normalized(const Mesh &m) {
    if (m.exact || m.tris.empty()) return m;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const Tri &t : m.tris)
        for (const auto &p : t.p)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], p[k]);
                hi[k] = std::max(hi[k], p[k]);
            }
    double c[3], r = 0;
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        r = std::max(r, 0.5 * (hi[k] - lo[k]));
    }
    Mesh out = m;
    const double s = r > 0 ? 1.0 / r : 1.0;
    for (Tri &t : out.tris)
        for (auto &p : t.p)
            for (int k = 0; k < 3; ++k) p[k] = (p[k] - c[k]) * s;
    return out;
}

// ---------------------------------------------------------------------------------------------------
Pose identity_pose() {
    Pose p{};
    p.R[0] = p.R[4] = p.R[8] = 1;
    return p;
}

void random_rotation(Rng &rng, double R[9]) {
    double q[4], n = 0;
    do {
        n = 0;
        for (double &x : q) {
            x = rng.normal();
            n += x * x;
        }
    } while (n < 1e-6);
    n = std::sqrt(n);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    const double M[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                         2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                         2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
    std::memcpy(R, M, sizeof M);
}

Pose random_pose(Rng &rng, double tscale) {
    Pose p{};
    random_rotation(rng, p.R);
    for (double &t : p.T) t = tscale * rng.uniform(-1, 1);
    return p;
}

LV rand_dir(Rng &rng) {
    double v[3], n;
    do {
        n = 0;
        for (double &x : v) {
            x = rng.normal();
            n += x * x;
        }
    } while (n < 1e-12);
    n = std::sqrt(n);
    return {v[0] / n, v[1] / n, v[2] / n};
}

static void set_t(Pose &p, const LV &base, const LV &dir, L s) {
    p.T[0] = static_cast<double>(base.x + dir.x * s);
    p.T[1] = static_cast<double>(base.y + dir.y * s);
    p.T[2] = static_cast<double>(base.z + dir.z * s);
}

PosePair random_pair(Rng &rng, double ra, double rb, double lo, double hi, const char *kind) {
    PosePair pp;
    pp.kind = kind;
    pp.a = random_pose(rng, 0.5);
    pp.b = random_pose(rng, 0);
    const LV base{pp.a.T[0], pp.a.T[1], pp.a.T[2]};
    set_t(pp.b, base, rand_dir(rng), (ra + rb) * rng.uniform(lo, hi));
    return pp;
}

void add_offset(Rng &rng, PosePair &pp) {
    const double mag = std::pow(10.0, rng.uniform(0, 6));
    const LV d = rand_dir(rng);
    const double o[3] = {double(d.x) * mag, double(d.y) * mag, double(d.z) * mag};
    for (int k = 0; k < 3; ++k) {
        pp.a.T[k] += o[k];
        pp.b.T[k] += o[k];
    }
    pp.kind += fmt(" +offset %.0e", mag);
}

PosePair near_pair(Rng &rng, const Mesh &A, const Mesh &B, double ra, double rb, double gap,
                   const std::function<std::pair<int, int>(const PosePair &)> &closest) {
    PosePair pp = random_pair(rng, ra, rb, 1.05, 1.3, "near");
    pp.kind = fmt("near(gap %.1e)", gap);
    for (int iter = 0; iter < 6; ++iter) {
        const std::pair<int, int> c = closest(pp);
        if (c.first < 0 || c.second < 0 || c.first >= int(A.tris.size()) || c.second >= int(B.tris.size())) break;
        LV ta[3], tb[3];
        for (int k = 0; k < 3; ++k) {
            ta[k] = to_world(pp.a.R, pp.a.T, A.tris[size_t(c.first)].p[k]);
            tb[k] = to_world(pp.b.R, pp.b.T, B.tris[size_t(c.second)].p[k]);
        }
        const bf::TriTri<L> r = bf::triangle_triangle(ta, tb);
        const LV base{pp.b.T[0], pp.b.T[1], pp.b.T[2]};
        if (!(r.dist > 0)) {  // aimed into contact: back off and retry
            set_t(pp.b, base, rand_dir(rng), 0.2 * (ra + rb));
            continue;
        }
        set_t(pp.b, base, (r.pb - r.pa) * (1 / r.dist), gap - r.dist);
        if (std::fabs(static_cast<double>(r.dist) - gap) < 1e-3 * gap) break;
    }
    return pp;
}

static void matmul(const double *A, const double *B, double *C) {
    double t[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
    std::memcpy(C, t, sizeof t);
}

static void axis_rotation(const LV &axis, double angle, double *R) {
    const double x = double(axis.x), y = double(axis.y), z = double(axis.z);
    const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const double M[9] = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
                         t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    std::memcpy(R, M, sizeof M);
}

double contact_gap(Rng &rng) {
    if (rng.uniform() < 0.1) return 0;
    return (rng.uniform() < 0.5 ? -1 : 1) * std::pow(10.0, rng.uniform(-12, -2));
}

double contact_tilt(Rng &rng) {
    static const double tilts[4] = {0, 1e-9, 1e-6, 1e-3};
    return tilts[rng.below(4)];
}

PosePair contact_pair(Rng &rng, const Mesh &B, int type, double gap, double tilt) {
    static const char *names[3] = {"face", "edge", "vertex"};
    double Rrel[9], M[9];
    if (type == 2) {
        random_rotation(rng, Rrel);
    } else {
        axis_rotation({0, 0, 1}, rng.uniform(0, 2 * M_PI), Rrel);
        if (type == 1) {
            axis_rotation({1, 0, 0}, M_PI / 4, M);
            matmul(Rrel, M, Rrel);
        }
    }
    if (tilt != 0) {
        const double a = rng.uniform(0, 2 * M_PI);
        axis_rotation({std::cos(a), std::sin(a), 0}, tilt, M);
        matmul(M, Rrel, Rrel);
    }
    double zmin = 1e300;
    for (const Tri &t : B.tris)
        for (const auto &p : t.p) zmin = std::min(zmin, Rrel[6] * p[0] + Rrel[7] * p[1] + Rrel[8] * p[2]);
    const double Trel[3] = {rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2), 1 + gap - zmin};
    PosePair pp;
    pp.a = rng.uniform() < 0.25 ? identity_pose() : random_pose(rng, 1.0);
    matmul(pp.a.R, Rrel, pp.b.R);
    for (int i = 0; i < 3; ++i)
        pp.b.T[i] = pp.a.R[3 * i] * Trel[0] + pp.a.R[3 * i + 1] * Trel[1] + pp.a.R[3 * i + 2] * Trel[2] + pp.a.T[i];
    pp.kind = fmt("contact %s gap %.1e tilt %.0e", names[type], gap, tilt);
    return pp;
}

void orthonormalize(double R[9]) {
    double *r0 = R, *r1 = R + 3, *r2 = R + 6;
    auto normalize = [](double *v) {
        const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (int k = 0; k < 3; ++k) v[k] /= n;
    };
    normalize(r0);
    const double d = r0[0] * r1[0] + r0[1] * r1[1] + r0[2] * r1[2];
    for (int k = 0; k < 3; ++k) r1[k] -= d * r0[k];
    normalize(r1);
    r2[0] = r0[1] * r1[2] - r0[2] * r1[1];
    r2[1] = r0[2] * r1[0] - r0[0] * r1[2];
    r2[2] = r0[0] * r1[1] - r0[1] * r1[0];
}

LV to_world(const double *R, const double *T, const double *x) {
    LV w;
    L *o[3] = {&w.x, &w.y, &w.z};
    for (int i = 0; i < 3; ++i)
        *o[i] = static_cast<L>(R[3 * i]) * x[0] + static_cast<L>(R[3 * i + 1]) * x[1] +
                static_cast<L>(R[3 * i + 2]) * x[2] + static_cast<L>(T[i]);
    return w;
}

World to_world(const Mesh &m, const Pose &p) {
    World w;
    w.v.reserve(3 * m.tris.size());
    w.lo.reserve(m.tris.size());
    w.hi.reserve(m.tris.size());
    L s = 0;
    for (const Tri &t : m.tris) {
        LV lo{0, 0, 0}, hi{0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            const LV x = to_world(p.R, p.T, t.p[k]);
            w.v.push_back(x);
            if (k == 0) lo = hi = x;
            lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
            hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
            s = std::max({s, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
        }
        w.lo.push_back(lo);
        w.hi.push_back(hi);
    }
    w.scale = static_cast<double>(s);
    return w;
}

L point_triangle_distance(const LV &p, const LV *tri) { return std::sqrt(bf::point_triangle(p, tri).d2); }

void box_pairs(const World &A, const World &B, L margin, const std::function<void(int, int)> &f) {
    const int nb = B.size();
    std::vector<int> order(static_cast<size_t>(nb));
    L wmax = 0;
    for (int j = 0; j < nb; ++j) {
        order[static_cast<size_t>(j)] = j;
        wmax = std::max(wmax, B.hi[static_cast<size_t>(j)].x - B.lo[static_cast<size_t>(j)].x);
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) { return B.lo[size_t(a)].x < B.lo[size_t(b)].x; });
    std::vector<L> keys(static_cast<size_t>(nb));
    for (int k = 0; k < nb; ++k) keys[size_t(k)] = B.lo[size_t(order[size_t(k)])].x;
    for (int i = 0; i < A.size(); ++i) {
        const LV &alo = A.lo[size_t(i)], &ahi = A.hi[size_t(i)];
        auto first = std::lower_bound(keys.begin(), keys.end(), alo.x - margin - wmax);
        for (auto it = first; it != keys.end() && *it <= ahi.x + margin; ++it) {
            const int j = order[size_t(it - keys.begin())];
            const LV &blo = B.lo[size_t(j)], &bhi = B.hi[size_t(j)];
            if (bhi.x < alo.x - margin || blo.y > ahi.y + margin || bhi.y < alo.y - margin ||
                blo.z > ahi.z + margin || bhi.z < alo.z - margin)
                continue;
            f(i, j);
        }
    }
}

L box_distance(const World &A, int i, const World &B, int j) {
    const LV &alo = A.lo[size_t(i)], &ahi = A.hi[size_t(i)], &blo = B.lo[size_t(j)], &bhi = B.hi[size_t(j)];
    const L dx = std::max<L>({L(0), blo.x - ahi.x, alo.x - bhi.x});
    const L dy = std::max<L>({L(0), blo.y - ahi.y, alo.y - bhi.y});
    const L dz = std::max<L>({L(0), blo.z - ahi.z, alo.z - bhi.z});
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

const char *truth_name(Truth t) {
    switch (t) {
    case Truth::Separated: return "separated";
    case Truth::Intersecting: return "intersecting";
    default: return "borderline";
    }
}

double band_for(const World &A, const World &B) { return 1e-12 * std::max({1.0, A.scale, B.scale}); }

PairTruth pair_truth(const World &A, int i, const World &B, int j, double band, bool exact) {
    const bf::TriTri<L> r = bf::triangle_triangle(A.tri(i), B.tri(j));
    PairTruth t{r.dist, r.depth, Truth::Borderline, r.pa, r.pb};
    if (r.dist > band) t.truth = Truth::Separated;
    else if (exact || r.depth > band) t.truth = Truth::Intersecting;
    return t;
}

CollideTruth collide_truth(const World &A, const World &B, double band, bool exact) {
    CollideTruth ct;
    box_pairs(A, B, band, [&](int i, int j) {
        ++ct.pairs_tested;
        const PairTruth t = pair_truth(A, i, B, j, band, exact);
        if (t.truth == Truth::Intersecting) ct.intersecting.emplace_back(i, j);
        else if (t.truth == Truth::Borderline) ct.borderline.emplace_back(i, j);
    });
    return ct;
}

DistanceTruth distance_truth(const World &A, const World &B, const std::vector<std::pair<int, int>> &hints) {
    DistanceTruth dt;
    dt.dist = std::numeric_limits<L>::infinity();
    auto consider = [&](int i, int j) {
        ++dt.pairs_tested;
        const bf::TriTri<L> r = bf::triangle_triangle(A.tri(i), B.tri(j));
        if (r.dist < dt.dist) {
            dt.dist = r.dist;
            dt.i = i;
            dt.j = j;
        }
    };
    for (const auto &h : hints)
        if (h.first >= 0 && h.first < A.size() && h.second >= 0 && h.second < B.size()) consider(h.first, h.second);
    if (dt.i < 0) consider(0, 0);
    // Any pair closer than the bound has boxes within the bound; visit them by increasing box distance
    // and stop once the box distance (a lower bound) exceeds the best pair distance.
    struct Cand {
        L box;
        int i, j;
    };
    std::vector<Cand> cands;
    const L bound = dt.dist;
    box_pairs(A, B, bound, [&](int i, int j) {
        const L b = box_distance(A, i, B, j);
        if (b <= bound) cands.push_back({b, i, j});
    });
    std::sort(cands.begin(), cands.end(), [](const Cand &x, const Cand &y) { return x.box < y.box; });
    for (const Cand &c : cands) {
        if (c.box > dt.dist) break;
        consider(c.i, c.j);
    }
    return dt;
}

// ---------------------------------------------------------------------------------------------------
OurModel::OurModel(const Mesh &mesh) : m_(pqp_model_create()) {
    if (!m_) {
        build_rc = PQP_ERR_MODEL_OUT_OF_MEMORY;
        return;
    }
    auto note = [&](int rc) {
        if (rc != PQP_OK && build_rc == PQP_OK) build_rc = rc;
    };
    note(pqp_model_begin(m_, static_cast<int>(mesh.tris.size())));
    int id = 0;
    for (const Tri &t : mesh.tris) note(pqp_model_add_tri(m_, t.p[0], t.p[1], t.p[2], id++));
    note(pqp_model_end(m_));
}

OurModel::~OurModel() { pqp_model_destroy(m_); }

static void split_pose(const PosePair &pp, const double **R1, const double **T1, const double **R2, const double **T2) {
    *R1 = pp.a.R;
    *T1 = pp.a.T;
    *R2 = pp.b.R;
    *T2 = pp.b.T;
}

CollideOut our_collide(pqp_collide_result *r, const PosePair &pp, const OurModel &a, const OurModel &b, int flag) {
    const double *R1, *T1, *R2, *T2;
    split_pose(pp, &R1, &T1, &R2, &T2);
    CollideOut o;
    o.rc = pqp_collide(r, R1, T1, a.get(), R2, T2, b.get(), flag);
    if (o.rc != PQP_OK) return o;
    o.colliding = pqp_collide_result_colliding(r) != 0;
    const int n = pqp_collide_result_num_pairs(r);
    const pqp_contact_pair *pairs = pqp_collide_result_pairs(r);
    for (int k = 0; k < n; ++k) {
        const int i1 = pqp_collide_result_id1(r, k), i2 = pqp_collide_result_id2(r, k);
        // The array and the indexed accessors must agree; a mismatch shows as an invalid pair.
        if (!pairs || pairs[k].id1 != i1 || pairs[k].id2 != i2) o.pairs.emplace_back(-2, -2);
        else o.pairs.emplace_back(i1, i2);
    }
    return o;
}

DistanceOut our_distance(pqp_distance_result *r, const PosePair &pp, const OurModel &a, const OurModel &b,
                         double rel, double abs, int qsize) {
    const double *R1, *T1, *R2, *T2;
    split_pose(pp, &R1, &T1, &R2, &T2);
    DistanceOut o;
    o.rc = pqp_distance(r, R1, T1, a.get(), R2, T2, b.get(), rel, abs, qsize);
    if (o.rc != PQP_OK) return o;
    o.d = pqp_distance_result_distance(r);
    const double *p1 = pqp_distance_result_p1(r), *p2 = pqp_distance_result_p2(r);
    for (int k = 0; k < 3; ++k) {
        o.p1[k] = p1 ? p1[k] : NAN;
        o.p2[k] = p2 ? p2[k] : NAN;
    }
    o.id1 = pqp_distance_result_id1(r);
    o.id2 = pqp_distance_result_id2(r);
    o.overlap = pqp_distance_result_overlap(r);
    return o;
}

ToleranceOut our_tolerance(pqp_tolerance_result *r, const PosePair &pp, const OurModel &a, const OurModel &b,
                           double t, int qsize) {
    const double *R1, *T1, *R2, *T2;
    split_pose(pp, &R1, &T1, &R2, &T2);
    ToleranceOut o;
    o.rc = pqp_tolerance(r, R1, T1, a.get(), R2, T2, b.get(), t, qsize);
    if (o.rc != PQP_OK) return o;
    o.closer = pqp_tolerance_result_closer_than_tolerance(r) != 0;
    o.d = pqp_tolerance_result_distance(r);
    o.t = pqp_tolerance_result_tolerance(r);
    const double *p1 = pqp_tolerance_result_p1(r), *p2 = pqp_tolerance_result_p2(r);
    for (int k = 0; k < 3; ++k) {
        o.p1[k] = p1 ? p1[k] : NAN;
        o.p2[k] = p2 ? p2[k] : NAN;
    }
    return o;
}

PqpHModel::PqpHModel(const Mesh &mesh) {
    auto note = [&](int rc) {
        if (rc != PQP_OK && build_rc == PQP_OK) build_rc = rc;
    };
    note(m.BeginModel(static_cast<int>(mesh.tris.size())));
    int id = 0;
    for (const Tri &t : mesh.tris) note(m.AddTri(t.p[0], t.p[1], t.p[2], id++));
    note(m.EndModel());
}

struct Legacy {
    PQP_REAL R1[3][3], T1[3], R2[3][3], T2[3];
    explicit Legacy(const PosePair &pp) {
        for (int i = 0; i < 3; ++i) {
            T1[i] = pp.a.T[i];
            T2[i] = pp.b.T[i];
            for (int j = 0; j < 3; ++j) {
                R1[i][j] = pp.a.R[3 * i + j];
                R2[i][j] = pp.b.R[3 * i + j];
            }
        }
    }
};

CollideOut pqph_collide(PQP_CollideResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, int flag) {
    Legacy p(pp);
    CollideOut o;
    o.rc = PQP_Collide(r, p.R1, p.T1, &a.m, p.R2, p.T2, &b.m, flag);
    if (o.rc != PQP_OK) return o;
    o.colliding = r->Colliding() != 0;
    for (int k = 0; k < r->NumPairs(); ++k) o.pairs.emplace_back(r->Id1(k), r->Id2(k));
    return o;
}

DistanceOut pqph_distance(PQP_DistanceResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, double rel,
                          double abs, int qsize) {
    Legacy p(pp);
    DistanceOut o;
    o.rc = PQP_Distance(r, p.R1, p.T1, &a.m, p.R2, p.T2, &b.m, rel, abs, qsize);
    if (o.rc != PQP_OK) return o;
    o.d = r->Distance();
    for (int k = 0; k < 3; ++k) {
        o.p1[k] = r->P1()[k];
        o.p2[k] = r->P2()[k];
    }
    return o;
}

ToleranceOut pqph_tolerance(PQP_ToleranceResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, double t,
                            int qsize) {
    Legacy p(pp);
    ToleranceOut o;
    o.rc = PQP_Tolerance(r, p.R1, p.T1, &a.m, p.R2, p.T2, &b.m, t, qsize);
    if (o.rc != PQP_OK) return o;
    o.closer = r->CloserThanTolerance() != 0;
    o.d = r->Distance();
    o.t = t;
    for (int k = 0; k < 3; ++k) {
        o.p1[k] = r->P1()[k];
        o.p2[k] = r->P2()[k];
    }
    return o;
}

// ---------------------------------------------------------------------------------------------------
bool Report::check(bool ok, const std::string &what) {
    if (ok) {
        ++passed_;
        return true;
    }
    ++failed_;
    std::printf("FAIL [%s] %s\n", ctx_.c_str(), what.c_str());
    return false;
}

void Report::disagreement(const std::string &peer, const std::string &category, bool we_wrong,
                          const std::string &detail) {
    const std::string key = peer + ": " + category + (cls_.empty() ? "" : " [" + cls_ + "]") +
                            (we_wrong ? "  -> WE are wrong" : "  -> we are right");
    Cat &c = cats_[key];
    ++c.count;
    c.we_wrong = we_wrong;
    if (we_wrong) {
        ++failed_;
        std::printf("FAIL [%s] %s disagreement, %s: %s\n", ctx_.c_str(), peer.c_str(), category.c_str(),
                    detail.c_str());
    } else {
        ++passed_;
        if (c.examples.size() < 1) c.examples.push_back("[" + ctx_ + "] " + detail);
    }
}

int Report::finish(double seconds) {
    std::printf("\n==== %s summary ====\n", program_.c_str());
    for (const auto &kv : counters_) std::printf("  %-52s %ld\n", kv.first.c_str(), kv.second);
    if (cats_.empty()) std::printf("  no disagreements with peers\n");
    else std::printf("  disagreements (decided by brute force in long double):\n");
    for (const auto &kv : cats_) {
        std::printf("    %-80s %ld\n", kv.first.c_str(), kv.second.count);
        for (const auto &e : kv.second.examples) std::printf("        e.g. %s\n", e.c_str());
    }
    std::printf("  time %.1f s\n", seconds);
    std::printf("%ld passed, %ld failed\n", passed_, failed_);
    return failed_ == 0 ? 0 : 1;
}

std::string fmt(const char *f, ...) {
    char buf[1024];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}

std::string join(const std::vector<std::string> &v) {
    std::string s;
    for (const std::string &x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
}

std::string pose_str(const PosePair &pp) {
    return fmt("%s T1=(%.17g %.17g %.17g) T2=(%.17g %.17g %.17g)", pp.kind.c_str(), pp.a.T[0], pp.a.T[1], pp.a.T[2],
               pp.b.T[0], pp.b.T[1], pp.b.T[2]);
}

std::string pose_class(const PosePair &pp) {
    const std::string &k = pp.kind;
    std::string cls;
    auto starts = [&](const char *p) { return k.rfind(p, 0) == 0; };
    if (starts("contact")) cls = k.substr(0, k.find(' ', 8));
    else if (starts("near")) cls = "near";
    else if (starts("exact")) cls = "exact";
    else if (starts("path")) cls = "path";
    else cls = k.substr(0, k.find(" +offset"));
    if (k.find("+offset") != std::string::npos) cls += " +offset";
    return cls;
}

void announce(const char *program, const Options &o) {
    std::printf("%s: seed %llu, scale %g, models [%s]\n", program, static_cast<unsigned long long>(o.seed), o.scale,
                join(o.models_dirs).c_str());
}

Options parse_options(int argc, char **argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto val = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "missing value for %s\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--seed") o.seed = std::strtoull(val().c_str(), nullptr, 0);
        else if (a == "--scale") o.scale = std::strtod(val().c_str(), nullptr);
        else if (a == "--models") {
            const std::string d = val();
            if (!d.empty()) o.models_dirs.push_back(d);
        }
        else if (a == "--only") o.only = val();
        else {
            std::fprintf(stderr, "usage: %s [--seed N] [--scale X] [--models DIR]... [--only NAME-PART]\n", argv[0]);
            std::exit(2);
        }
    }
    return o;
}

int scaled(const Options &o, int n) { return std::max(1, static_cast<int>(std::lround(n * o.scale))); }

}  // namespace ht
