// model_internals.cpp -- PQP 1.3 programs read PQP_Model's internals: build_state, the triangle
// array tris, the bounding-volume hierarchy b (through child(n)), their counts, last_tri, and the BV
// record's members and functions (Leaf, GetSize, FitToTris, BV_Overlap, BV_Distance). pqp-rs
// presents them as a view built on first use. This program checks that the view has PQP 1.3's
// layout and meaning, against brute force (bf.hpp, long double):
//
//  - the counters and pointers through the build (fresh, begun, built, rebuilt);
//  - tris: the triangles in the order added, with their ids, coordinates bit-identical;
//  - b: a binary tree in PQP's layout (root 0, children at first_child and first_child + 1 after
//    their parent, leaves holding triangle -first_child - 1, each triangle in one leaf), with
//    parent-relative frames which, composed down the tree, give volumes (rectangle swept sphere and
//    oriented box) containing every vertex of every triangle below them;
//  - one-triangle and degenerate models; MemUsage before and after the view exists; the same view
//    read by 4 threads at once;
//  - BV::FitToTris, BV_Overlap and BV_Distance on random input against a brute-force fit check, a
//    separating-axis test and a brute-force rectangle distance written here.
// C++11.
#include "PQP.h"
#include "bf.hpp"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <limits>
#include <random>
#include <thread>
#include <vector>

typedef long double LD;
typedef bf::V<LD> LV;

static int failures = 0;
static char context[200] = "setup";  // the case being checked, printed with each failure

#define EXPECT(cond)                                                                         \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            failures++;                                                                      \
            if (failures <= 200)                                                             \
                fprintf(stderr, "%s:%d: expected %s [%s]\n", __FILE__, __LINE__, #cond,      \
                        context);                                                            \
        }                                                                                    \
    } while (0)

static std::mt19937_64 rng(77001);

static double uniform(double lo, double hi)
{
    return std::uniform_real_distribution<double>(lo, hi)(rng);
}

static Tri make_tri(const double a[3], const double b[3], const double c[3], int id)
{
    Tri t;
    for (int i = 0; i < 3; i++) {
        t.p1[i] = a[i];
        t.p2[i] = b[i];
        t.p3[i] = c[i];
    }
    t.id = id;
    return t;
}

// n random triangles of size up to `size` scattered in [-spread, spread]^3; ids 5000 - 13k (some
// negative: PQP ids are any int).
static std::vector<Tri> random_soup(int n, double spread, double size)
{
    std::vector<Tri> out;
    for (int k = 0; k < n; k++) {
        double c[3], p[3][3];
        for (int i = 0; i < 3; i++) c[i] = uniform(-spread, spread);
        for (int v = 0; v < 3; v++)
            for (int i = 0; i < 3; i++) p[v][i] = c[i] + uniform(-size, size);
        out.push_back(make_tri(p[0], p[1], p[2], 5000 - 13 * k));
    }
    return out;
}

// A latitude-longitude sphere of radius ~2 centred at (1, -1, 0.5), ids 70000 + 2k.
static std::vector<Tri> bumpy_sphere(int nlat, int nlon)
{
    const double pi = 3.14159265358979323846;
    std::vector<std::vector<double> > v;
    for (int i = 0; i <= nlat; i++)
        for (int j = 0; j <= nlon; j++) {
            double th = pi * i / nlat, ph = 2 * pi * j / nlon, r = 2 + uniform(-0.1, 0.1);
            v.push_back({1 + r * sin(th) * cos(ph), -1 + r * sin(th) * sin(ph), 0.5 + r * cos(th)});
        }
    std::vector<Tri> out;
    int k = 0;
    for (int i = 0; i < nlat; i++)
        for (int j = 0; j < nlon; j++) {
            int a = i * (nlon + 1) + j, b = a + 1, c = a + nlon + 1, d = c + 1;
            // Near the poles these triangles are slivers (the pole vertices differ only in radius).
            out.push_back(make_tri(v[a].data(), v[c].data(), v[d].data(), 70000 + 2 * k++));
            out.push_back(make_tri(v[a].data(), v[d].data(), v[b].data(), 70000 + 2 * k++));
        }
    return out;
}

static LV lv(const PQP_REAL p[3])
{
    return LV{p[0], p[1], p[2]};
}

// ---------------------------------------------------------------------------------------------
// Frames and volumes (long double)

struct Frame {
    LD R[3][3];  // columns: the axes, in the model frame
    LD Tr[3];    // rectangle corner
    LD To[3];    // box centre
};

// Coordinates of model point p in the frame (R, origin): R^T (p - origin).
static LV to_local(const LD R[3][3], const LD origin[3], const LV &p)
{
    LD d[3] = {p.x - origin[0], p.y - origin[1], p.z - origin[2]};
    LD out[3];
    for (int i = 0; i < 3; i++) out[i] = R[0][i] * d[0] + R[1][i] * d[1] + R[2][i] * d[2];
    return LV{out[0], out[1], out[2]};
}

// Distance from local point q to the rectangle [0, l0] x [0, l1] of the xy-plane.
static LD point_rectangle(const LV &q, LD l0, LD l1)
{
    LD x = std::min(std::max(q.x, LD(0)), l0), y = std::min(std::max(q.y, LD(0)), l1);
    return sqrtl((q.x - x) * (q.x - x) + (q.y - y) * (q.y - y) + q.z * q.z);
}

// Whether the swept sphere (R, Tr, l, r) and the box (R, To, d) of a volume whose absolute frame is
// f both contain model point p, to tol.
static bool rss_contains(const Frame &f, const BV &bv, const LV &p, LD tol)
{
    return point_rectangle(to_local(f.R, f.Tr, p), bv.l[0], bv.l[1]) <= (LD)bv.r + tol;
}

static bool obb_contains(const Frame &f, const BV &bv, const LV &p, LD tol)
{
    LV q = to_local(f.R, f.To, p);
    return fabsl(q.x) <= bv.d[0] + tol && fabsl(q.y) <= bv.d[1] + tol && fabsl(q.z) <= bv.d[2] + tol;
}

static bool orthonormal(const LD R[3][3], LD tol)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            LD s = R[0][i] * R[0][j] + R[1][i] * R[1][j] + R[2][i] * R[2][j];
            if (fabsl(s - (i == j ? 1 : 0)) > tol) return false;
        }
    return true;
}

// ---------------------------------------------------------------------------------------------
// A built model against the triangles it was given

static LD model_scale(const std::vector<Tri> &input)
{
    LD s = 1;
    for (size_t k = 0; k < input.size(); k++)
        for (int i = 0; i < 3; i++)
            s = std::max(s, std::max(fabsl(input[k].p1[i]),
                                     std::max(fabsl(input[k].p2[i]), fabsl(input[k].p3[i]))));
    return s;
}

#ifndef PQP_PQP_H
static bool id_less(const Tri *a, const Tri *b) { return a->id < b->id; }

// Pointers to n triangles, sorted by id.
static std::vector<const Tri *> by_id(const Tri *t, int n)
{
    std::vector<const Tri *> out(n);
    for (int k = 0; k < n; k++) out[k] = &t[k];
    std::stable_sort(out.begin(), out.end(), id_less);
    return out;
}
#endif

static void check_built_model(PQP_Model &m, const std::vector<Tri> &input, const char *name)
{
    snprintf(context, sizeof context, "%s (%zu triangles)", name, input.size());
    const int n = static_cast<int>(input.size());

    // Counters, as PQP 1.3 left them after EndModel.
    EXPECT(m.build_state == 2);
    EXPECT(m.num_tris == n);
    EXPECT(m.num_tris_alloced == n);
    EXPECT(m.num_bvs == 2 * n - 1);
    EXPECT(m.num_bvs_alloced == 2 * n - 1);

    // tris: in the order added, ids kept, coordinates bit-identical. Reading it again gives the same
    // pointer; last_tri is its first triangle.
    Tri *tris = m.tris;
    EXPECT(tris != NULL);
    if (tris == NULL) return;
    EXPECT(static_cast<Tri *>(m.tris) == tris);
    EXPECT(static_cast<Tri *>(m.last_tri) == tris);
#ifdef PQP_PQP_H
    // pqp-rs (PQP_PQP_H, its C header's guard, is defined by its PQP.h) keeps the order added.
    std::vector<const Tri *> got(n), want(n);
    for (int k = 0; k < n; k++) got[k] = &tris[k], want[k] = &input[k];
#else
    // PQP 1.3 reorders tris while it builds: compare as sets, in the order of (distinct) ids.
    std::vector<const Tri *> got = by_id(tris, n), want = by_id(&input[0], n);
#endif
    for (int k = 0; k < n && k < m.num_tris; k++) {
        EXPECT(got[k]->id == want[k]->id);
        EXPECT(memcmp(got[k]->p1, want[k]->p1, sizeof got[k]->p1) == 0);
        EXPECT(memcmp(got[k]->p2, want[k]->p2, sizeof got[k]->p2) == 0);
        EXPECT(memcmp(got[k]->p3, want[k]->p3, sizeof got[k]->p3) == 0);
    }

    // b and child(k) == &b[k].
    BV *b = m.b;
    EXPECT(b != NULL);
    if (b == NULL || m.num_bvs != 2 * n - 1) return;
    const int nb = m.num_bvs;
    for (int k = 0; k < nb; k++) EXPECT(m.child(k) == b + k);

    // Tree layout: children after their parent, every volume but the root a child exactly once,
    // every triangle in exactly one leaf.
    std::vector<int> parent(nb, -1), leaf_of(n, -1);
    int leaves = 0;
    bool layout_ok = true;
    for (int k = 0; k < nb; k++) {
        BV &v = b[k];  // not const: PQP 1.3's Leaf() and GetSize() are not const members
        EXPECT(v.Leaf() == (v.first_child < 0 ? 1 : 0));
        if (v.first_child < 0) {
            leaves++;
            int t = -v.first_child - 1;
            EXPECT(t >= 0 && t < n);
            if (t < 0 || t >= n) {
                layout_ok = false;
                continue;
            }
            EXPECT(leaf_of[t] == -1);
            leaf_of[t] = k;
        } else {
            int c = v.first_child;
            EXPECT(c > k && c + 1 < nb);
            if (c <= k || c + 1 >= nb) {
                layout_ok = false;
                continue;
            }
            for (int ch = c; ch <= c + 1; ch++) {
                EXPECT(parent[ch] == -1);
                if (parent[ch] != -1) layout_ok = false;
                parent[ch] = k;
            }
        }
        // Sizes as PQP 1.3's GetSize (default PQP_BV_TYPE: rectangle diagonal plus diameter), and
        // non-negative extents.
        double size = sqrt((double)v.l[0] * v.l[0] + (double)v.l[1] * v.l[1]) + 2.0 * v.r;
        EXPECT(fabs(v.GetSize() - size) <= 1e-14 * (1 + size));
        EXPECT(v.l[0] >= 0 && v.l[1] >= 0 && v.r >= 0);
        EXPECT(v.d[0] >= 0 && v.d[1] >= 0 && v.d[2] >= 0);
    }
    EXPECT(leaves == n);
    EXPECT(parent[0] == -1);
    for (int k = 1; k < nb; k++) {
        EXPECT(parent[k] != -1);
        if (parent[k] == -1) layout_ok = false;
    }
    for (int t = 0; t < n; t++) {
        EXPECT(leaf_of[t] != -1);
        if (leaf_of[t] == -1) layout_ok = false;
    }
    if (!layout_ok) return;

    // Absolute frames: the root's are in the model frame; a child's R, Tr, To are relative to its
    // parent's (R = Rp Rc, Tr = Rp Trc + Trp, To = Rp Toc + Top). Parents come first in the array,
    // so one pass in index order composes them.
    std::vector<Frame> abs(nb);
    for (int k = 0; k < nb; k++) {
        const BV &v = b[k];
        Frame &f = abs[k];
        if (k == 0) {
            for (int i = 0; i < 3; i++) {
                for (int j = 0; j < 3; j++) f.R[i][j] = v.R[i][j];
                f.Tr[i] = v.Tr[i];
                f.To[i] = v.To[i];
            }
        } else {
            const Frame &p = abs[parent[k]];
            for (int i = 0; i < 3; i++) {
                for (int j = 0; j < 3; j++)
                    f.R[i][j] = p.R[i][0] * v.R[0][j] + p.R[i][1] * v.R[1][j] + p.R[i][2] * v.R[2][j];
                f.Tr[i] = p.R[i][0] * v.Tr[0] + p.R[i][1] * v.Tr[1] + p.R[i][2] * v.Tr[2] + p.Tr[i];
                f.To[i] = p.R[i][0] * v.To[0] + p.R[i][1] * v.To[1] + p.R[i][2] * v.To[2] + p.To[i];
            }
        }
        EXPECT(orthonormal(f.R, 1e-9L));
    }

    // Every vertex of every triangle lies in its leaf's volumes and in each ancestor's: walk up
    // from each triangle's leaf to the root.
    const LD tol = 1e-9L * model_scale(input);
    int rss_misses = 0, obb_misses = 0, bad_volume = -1, bad_triangle = -1;
    for (int t = 0; t < n; t++) {
        // The leaf indexes the model's tris (the order added in pqp-rs, PQP 1.3's own order).
        LV vs[3] = {lv(tris[t].p1), lv(tris[t].p2), lv(tris[t].p3)};
        for (int k = leaf_of[t]; k != -1; k = parent[k])
            for (int i = 0; i < 3; i++) {
                bool in_rss = rss_contains(abs[k], b[k], vs[i], tol);
                bool in_obb = obb_contains(abs[k], b[k], vs[i], tol);
                if (!in_rss) rss_misses++;
                if (!in_obb) obb_misses++;
                if ((!in_rss || !in_obb) && bad_volume < 0) {
                    bad_volume = k;
                    bad_triangle = t;
                }
            }
    }
    if (rss_misses || obb_misses)
        fprintf(stderr, "%s: first vertex outside: volume %d, triangle %d\n", name, bad_volume,
                bad_triangle);
    EXPECT(rss_misses == 0);
    EXPECT(obb_misses == 0);
}

// Builds m from input, checking the counters and the view while it is being built.
static void build_checking_progress(PQP_Model &m, const std::vector<Tri> &input, int hint,
                                    const char *name)
{
    snprintf(context, sizeof context, "%s, during the build", name);
    int rc = m.BeginModel(hint);
    EXPECT(rc == PQP_OK || rc == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
    EXPECT(m.build_state == 1);
    EXPECT(m.num_tris == 0);
    EXPECT(m.num_tris_alloced == (hint > 0 ? hint : 8));
    for (size_t k = 0; k < input.size(); k++) {
        EXPECT(m.AddTri(input[k].p1, input[k].p2, input[k].p3, input[k].id) == PQP_OK);
        const int added = static_cast<int>(k) + 1;
        EXPECT(m.build_state == 1);
        EXPECT(m.num_tris == added);
        // PQP 1.3's capacity: the hint, doubled whenever full.
        int cap = hint > 0 ? hint : 8;
        while (cap < added) cap *= 2;
        EXPECT(m.num_tris_alloced == cap);
        // No hierarchy before EndModel.
        EXPECT(static_cast<BV *>(m.b) == NULL);
        EXPECT(m.child(0) == NULL);
        EXPECT(m.num_bvs == 0);
        EXPECT(static_cast<Tri *>(m.last_tri) == NULL);
        // The triangles so far, read at a few points of the build (the view must follow AddTri).
        if (added == 1 || added == 5 || added == static_cast<int>(input.size()) / 2) {
            Tri *t = m.tris;
            EXPECT(t != NULL);
            for (int j = 0; t != NULL && j < added; j++) {
                EXPECT(t[j].id == input[j].id);
                EXPECT(memcmp(t[j].p1, input[j].p1, sizeof t[j].p1) == 0);
                EXPECT(memcmp(t[j].p3, input[j].p3, sizeof t[j].p3) == 0);
            }
        }
    }
    EXPECT(m.EndModel() == PQP_OK);
}

// ---------------------------------------------------------------------------------------------
// The view read from 4 threads at once, on a model nobody has read yet

struct Seen {
    Tri *tris;
    BV *b;
    Tri *last_tri;
    BV *first, *last;
    uint64_t hash;  // FNV-1a over the bytes of tris[0..num_tris) and b[0..num_bvs)
};

static uint64_t fnv(uint64_t h, const void *data, size_t bytes)
{
    const unsigned char *p = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < bytes; i++) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static Seen read_view(PQP_Model &m)  // not const: PQP 1.3's child() is not a const member
{
    Seen s;
    s.tris = m.tris;
    s.b = m.b;
    s.last_tri = m.last_tri;
    s.first = m.child(0);
    s.last = m.child(m.num_bvs - 1);
    s.hash = 14695981039346656037ull;
    if (s.tris != NULL) s.hash = fnv(s.hash, s.tris, sizeof(Tri) * m.num_tris);
    if (s.b != NULL) s.hash = fnv(s.hash, s.b, sizeof(BV) * m.num_bvs);
    return s;
}

static void check_threads(int rounds)
{
    for (int round = 0; round < rounds; round++) {
        snprintf(context, sizeof context, "4 threads reading the view, round %d", round);
        std::vector<Tri> input = random_soup(50 + 37 * round, 3.0, 0.5);
        PQP_Model m;
        EXPECT(m.BeginModel() == PQP_OK);
        for (size_t k = 0; k < input.size(); k++)
            EXPECT(m.AddTri(input[k].p1, input[k].p2, input[k].p3, input[k].id) == PQP_OK);
        EXPECT(m.EndModel() == PQP_OK);

        std::atomic<int> ready(0);
        std::atomic<bool> go(false);
        Seen seen[4];
        std::vector<std::thread> threads;
        for (int i = 0; i < 4; i++)
            threads.push_back(std::thread([&m, &ready, &go, &seen, i]() {
                ready++;
                while (!go.load()) {
                }
                seen[i] = read_view(m);
            }));
        while (ready.load() < 4) {
        }
        go = true;
        for (size_t i = 0; i < threads.size(); i++) threads[i].join();

        Seen now = read_view(m);
        EXPECT(now.tris != NULL && now.b != NULL);
        for (int i = 0; i < 4; i++) {
            EXPECT(seen[i].tris == now.tris && seen[i].b == now.b);
            EXPECT(seen[i].last_tri == now.last_tri && seen[i].last_tri == now.tris);
            EXPECT(seen[i].first == now.b && seen[i].last == now.b + m.num_bvs - 1);
            EXPECT(seen[i].hash == now.hash);
        }
        check_built_model(m, input, "model read by 4 threads");
    }
}

// ---------------------------------------------------------------------------------------------
// BV::FitToTris, BV_Overlap, BV_Distance

static void random_rotation(PQP_REAL R[3][3])
{
    std::normal_distribution<double> g(0.0, 1.0);
    double w, x, y, z, n;
    do {
        w = g(rng);
        x = g(rng);
        y = g(rng);
        z = g(rng);
        n = sqrt(w * w + x * x + y * y + z * z);
    } while (n < 1e-3);
    w /= n;
    x /= n;
    y /= n;
    z /= n;
    R[0][0] = 1 - 2 * (y * y + z * z);
    R[0][1] = 2 * (x * y - w * z);
    R[0][2] = 2 * (x * z + w * y);
    R[1][0] = 2 * (x * y + w * z);
    R[1][1] = 1 - 2 * (x * x + z * z);
    R[1][2] = 2 * (y * z - w * x);
    R[2][0] = 2 * (x * z - w * y);
    R[2][1] = 2 * (y * z + w * x);
    R[2][2] = 1 - 2 * (x * x + y * y);
}

// A random rotation that maps axes to axes (a signed permutation of determinant 1); with
// keep_z, z maps to +-z.
static void random_axis_rotation(PQP_REAL R[3][3], bool keep_z)
{
    int perm[3] = {0, 1, 2};
    if (!keep_z) std::shuffle(perm, perm + 3, rng);
    else if (uniform(0, 1) < 0.5) std::swap(perm[0], perm[1]);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) R[i][j] = 0;
    for (int j = 0; j < 3; j++) R[perm[j]][j] = uniform(0, 1) < 0.5 ? -1 : 1;
    // Fix the determinant by flipping the last column if needed.
    double det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) -
                 R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
                 R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
    if (det < 0)
        for (int i = 0; i < 3; i++) R[i][2] = -R[i][2];
}

// A BV whose every member holds junk, so that a test reading a member it should not reveals it.
static BV junk_bv()
{
    BV v;
    random_rotation(v.R);
    for (int i = 0; i < 3; i++) {
        v.Tr[i] = uniform(-5, 5);
        v.To[i] = uniform(-5, 5);
        v.d[i] = uniform(0, 3);
    }
    v.l[0] = uniform(0, 3);
    v.l[1] = uniform(0, 3);
    v.r = uniform(0, 1);
    v.first_child = -7;
    return v;
}

static void check_fit_to_tris(int trials)
{
    for (int trial = 0; trial < trials; trial++) {
        snprintf(context, sizeof context, "FitToTris trial %d", trial);
        const int n = 1 + static_cast<int>(uniform(0, 30));
        const double scale = trial % 3 == 0 ? 1e-3 : trial % 3 == 1 ? 1.0 : 1e3;
        std::vector<Tri> tris = random_soup(n, 2 * scale, scale);
        if (trial % 10 == 5) {  // a degenerate set: every vertex on one line through the origin
            double u[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
            for (int k = 0; k < n; k++) {
                double s = uniform(-1, 1) * scale;
                for (int i = 0; i < 3; i++) {
                    tris[k].p1[i] = s * u[i];
                    tris[k].p2[i] = 2 * s * u[i];
                    tris[k].p3[i] = -s * u[i];
                }
            }
        }
        PQP_REAL O[3][3];
        if (trial % 5 == 0) random_axis_rotation(O, false);
        else random_rotation(O);

        BV v = junk_bv();
        v.first_child = 4242;
        v.FitToTris(O, tris.data(), n);

        // R = O; first_child untouched.
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) EXPECT(v.R[i][j] == O[i][j]);
        EXPECT(v.first_child == 4242);

        // Every vertex inside both volumes (the fit is in the triangles' frame: the volume's
        // absolute frame is (R, Tr, To) as stored).
        Frame f;
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) f.R[i][j] = v.R[i][j];
            f.Tr[i] = v.Tr[i];
            f.To[i] = v.To[i];
        }
        const LD tol = 1e-9L * (LD)scale * 4;
        LD lo[3] = {1e300L, 1e300L, 1e300L}, hi[3] = {-1e300L, -1e300L, -1e300L};
        for (int k = 0; k < n; k++) {
            const PQP_REAL *ps[3] = {tris[k].p1, tris[k].p2, tris[k].p3};
            for (int i = 0; i < 3; i++) {
                LV p = lv(ps[i]);
                EXPECT(rss_contains(f, v, p, tol));
                EXPECT(obb_contains(f, v, p, tol));
                // Extent along O's axes (relative to To).
                LV q = to_local(f.R, f.To, p);
                LD c[3] = {q.x, q.y, q.z};
                for (int a = 0; a < 3; a++) {
                    lo[a] = std::min(lo[a], c[a]);
                    hi[a] = std::max(hi[a], c[a]);
                }
            }
        }
        // The box is the bounding box on O's axes, as PQP 1.3 fitted it: no looser than the
        // vertices' extent. The swept sphere is no larger than that box.
        LD diag2 = 0;
        for (int a = 0; a < 3; a++) {
            EXPECT(hi[a] >= v.d[a] - tol && lo[a] <= -v.d[a] + tol);
            diag2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
        }
        EXPECT(v.l[0] <= hi[0] - lo[0] + tol && v.l[1] <= hi[1] - lo[1] + tol);
        EXPECT(v.r >= 0 && v.r <= 0.5L * sqrtl(diag2) + tol);

        // Nothing changes for no triangles or NULL.
        BV kept = v;
        v.FitToTris(O, tris.data(), 0);
        EXPECT(memcmp(&kept, &v, sizeof v) == 0);
        v.FitToTris(O, NULL, n);
        EXPECT(memcmp(&kept, &v, sizeof v) == 0);
    }
}

// Box overlap by the 15 separating axes, in long double: the largest gap between the projections
// of box 1 (half extents d1, at the origin, axes e0 e1 e2) and box 2 (half extents d2, axes the
// columns of R, centre T) over the candidate axes; > 0 apart, < 0 overlapping.
static LD box_gap(const PQP_REAL R[3][3], const PQP_REAL T[3], const PQP_REAL d1[3],
                  const PQP_REAL d2[3])
{
    LV e[3] = {LV{1, 0, 0}, LV{0, 1, 0}, LV{0, 0, 1}};
    LV f[3];
    for (int j = 0; j < 3; j++) f[j] = LV{R[0][j], R[1][j], R[2][j]};
    LV axes[15];
    int n = 0;
    for (int i = 0; i < 3; i++) axes[n++] = e[i];
    for (int j = 0; j < 3; j++) axes[n++] = f[j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) axes[n++] = bf::cross(e[i], f[j]);
    LV t = lv(T);
    LD gap = -std::numeric_limits<LD>::infinity();
    for (int k = 0; k < n; k++) {
        LD len2 = bf::norm2(axes[k]);
        if (len2 < 1e-20L) continue;  // parallel edges: the face axes decide
        LV u = axes[k] * (1 / sqrtl(len2));
        LD r1 = 0, r2 = 0;
        for (int i = 0; i < 3; i++) {
            r1 += d1[i] * fabsl(bf::dot(e[i], u));
            r2 += d2[i] * fabsl(bf::dot(f[i], u));
        }
        gap = std::max(gap, fabsl(bf::dot(t, u)) - r1 - r2);
    }
    return gap;
}

static void check_bv_overlap(int trials, int *skipped)
{
    for (int trial = 0; trial < trials; trial++) {
        snprintf(context, sizeof context, "BV_Overlap trial %d", trial);
        BV b1 = junk_bv(), b2 = junk_bv();
        for (int i = 0; i < 3; i++) {
            b1.d[i] = uniform(0, 1) < 0.1 ? 0 : uniform(0, 2);
            b2.d[i] = uniform(0, 1) < 0.1 ? 0 : uniform(0, 2);
        }
        PQP_REAL R[3][3], T[3];
        if (trial % 4 == 0) random_axis_rotation(R, false);
        else random_rotation(R);
        for (int i = 0; i < 3; i++) T[i] = uniform(-4, 4);
        LD gap = box_gap(R, T, b1.d, b2.d);
        if (fabsl(gap) <= 1e-9L) {
            (*skipped)++;
            continue;
        }
        EXPECT(BV_Overlap(R, T, &b1, &b2) == (gap < 0 ? 1 : 0));
    }
    // NULL arguments: "cannot be shown apart".
    snprintf(context, sizeof context, "BV_Overlap with NULL");
    BV b = junk_bv();
    PQP_REAL R[3][3], T[3] = {100, 0, 0};
    random_rotation(R);
    EXPECT(BV_Overlap(R, T, &b, NULL) == 1);
    EXPECT(BV_Overlap(R, NULL, &b, &b) == 1);
}

// Distance from segment [a, b] to the rectangle [0, l0] x [0, l1] of the xy-plane (the points in
// the rectangle's frame): 0 if the segment crosses the rectangle, else the nearest of its
// endpoints to the rectangle and of the segment to the rectangle's four edges.
static LD segment_rectangle(const LV &a, const LV &b, LD l0, LD l1)
{
    if ((a.z > 0 && b.z < 0) || (a.z < 0 && b.z > 0)) {
        LV p = a + (b - a) * (a.z / (a.z - b.z));
        if (p.x >= 0 && p.x <= l0 && p.y >= 0 && p.y <= l1) return 0;
    }
    LD best = std::min(point_rectangle(a, l0, l1), point_rectangle(b, l0, l1));
    LV c[4] = {LV{0, 0, 0}, LV{l0, 0, 0}, LV{l0, l1, 0}, LV{0, l1, 0}};
    for (int i = 0; i < 4; i++)
        best = std::min(best, sqrtl(bf::segment_segment(a, b, c[i], c[(i + 1) % 4]).d2));
    return best;
}

// Distance between rectangle 1 ([0, a0] x [0, a1] at the origin) and rectangle 2 ([0, b0] x
// [0, b1] placed by R, T): two intersecting rectangles have an edge of one meeting the other, so
// the minimum over the 8 edge-rectangle distances is exact.
static LD rectangle_distance(const PQP_REAL R[3][3], const PQP_REAL T[3], LD a0, LD a1, LD b0,
                             LD b1)
{
    LV ca[4] = {LV{0, 0, 0}, LV{a0, 0, 0}, LV{a0, a1, 0}, LV{0, a1, 0}};
    LV cb[4] = {LV{0, 0, 0}, LV{b0, 0, 0}, LV{b0, b1, 0}, LV{0, b1, 0}};
    LD Rl[3][3], Tl[3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) Rl[i][j] = R[i][j];
        Tl[i] = T[i];
    }
    LV b_in_1[4], a_in_2[4];
    for (int k = 0; k < 4; k++) {
        LD p[3] = {cb[k].x, cb[k].y, cb[k].z}, q[3];
        for (int i = 0; i < 3; i++) q[i] = Rl[i][0] * p[0] + Rl[i][1] * p[1] + Rl[i][2] * p[2] + Tl[i];
        b_in_1[k] = LV{q[0], q[1], q[2]};
        a_in_2[k] = to_local(Rl, Tl, ca[k]);
    }
    LD best = std::numeric_limits<LD>::infinity();
    for (int k = 0; k < 4; k++) {
        best = std::min(best, segment_rectangle(b_in_1[k], b_in_1[(k + 1) % 4], a0, a1));
        best = std::min(best, segment_rectangle(a_in_2[k], a_in_2[(k + 1) % 4], b0, b1));
    }
    return best;
}

static void check_bv_distance(int trials)
{
    for (int trial = 0; trial < trials; trial++) {
        snprintf(context, sizeof context, "BV_Distance trial %d", trial);
        BV b1 = junk_bv(), b2 = junk_bv();
        for (int i = 0; i < 2; i++) {
            b1.l[i] = uniform(0, 1) < 0.1 ? 0 : uniform(0, 2);
            b2.l[i] = uniform(0, 1) < 0.1 ? 0 : uniform(0, 2);
        }
        b1.r = uniform(0, 0.5);
        b2.r = uniform(0, 0.5);
        PQP_REAL R[3][3], T[3];
        const int kind = trial % 5;
        if (kind == 0) random_axis_rotation(R, false);
        else if (kind == 1) random_axis_rotation(R, true);  // parallel planes
        else random_rotation(R);
        const double reach = trial % 3 == 0 ? 0.7 : 3.0;  // near ones intersect often
        for (int i = 0; i < 3; i++) T[i] = uniform(-reach, reach);
        if (kind == 1 && trial % 2 == 0) T[2] = 0;  // coplanar rectangles
        LD expected = rectangle_distance(R, T, b1.l[0], b1.l[1], b2.l[0], b2.l[1]) - b1.r - b2.r;
        PQP_REAL got = BV_Distance(R, T, &b1, &b2);
        EXPECT(fabsl((LD)got - expected) <= 1e-9L);
    }
    snprintf(context, sizeof context, "BV_Distance with NULL");
    BV b = junk_bv();
    PQP_REAL R[3][3], T[3] = {0, 0, 0};
    random_rotation(R);
    EXPECT(BV_Distance(R, T, NULL, &b) != BV_Distance(R, T, NULL, &b));  // NaN
}

// ---------------------------------------------------------------------------------------------

int main()
{
    const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    // A fresh model: empty, no arrays.
    {
        snprintf(context, sizeof context, "fresh model");
        PQP_Model m;
        EXPECT(m.build_state == 0);
        EXPECT(m.num_tris == 0 && m.num_tris_alloced == 0);
        EXPECT(m.num_bvs == 0 && m.num_bvs_alloced == 0);
        EXPECT(static_cast<Tri *>(m.tris) == NULL);
        EXPECT(static_cast<BV *>(m.b) == NULL);
        EXPECT(static_cast<Tri *>(m.last_tri) == NULL);
        EXPECT(m.child(0) == NULL);
    }

    // A sphere plus a random soup (overlapping, some degenerate pole triangles), built with a small
    // hint so the capacity doubles; checked during and after the build.
    std::vector<Tri> mixed = bumpy_sphere(9, 14);
    std::vector<Tri> soup = random_soup(90, 4.0, 0.8);
    mixed.insert(mixed.end(), soup.begin(), soup.end());
    PQP_Model m;
    build_checking_progress(m, mixed, 10, "sphere and soup");
    check_built_model(m, mixed, "sphere and soup");

    // Rebuilt with other triangles: BeginModel clears it (PQP 1.3's code for a built model), the
    // hierarchy is gone until EndModel, and then the view shows the new triangles and tree.
    {
        std::vector<Tri> other = random_soup(57, 1.0, 0.3);
        snprintf(context, sizeof context, "rebuild");
        EXPECT(m.BeginModel(3) == PQP_ERR_BUILD_OUT_OF_SEQUENCE);
        EXPECT(m.build_state == 1 && m.num_tris == 0 && m.num_bvs == 0);
        EXPECT(static_cast<BV *>(m.b) == NULL);
        build_checking_progress(m, other, 3, "rebuilt model");
        check_built_model(m, other, "rebuilt model");
    }

    // One triangle: one volume, a leaf holding triangle 0.
    {
        const double a[3] = {1, 2, 3}, b[3] = {4, -1, 0}, c[3] = {0, 0, 7};
        std::vector<Tri> one(1, make_tri(a, b, c, 99));
        PQP_Model m1;
        build_checking_progress(m1, one, 0, "one triangle");
        check_built_model(m1, one, "one triangle");
        EXPECT(m1.num_bvs == 1);
        BV *root = m1.b;
        EXPECT(root != NULL && root->first_child == -1 && root->Leaf() == 1);
    }

    // Degenerate models: collinear and point triangles mixed with ordinary ones, all collinear,
    // all one point, and a flat grid (every volume flat).
    {
        std::vector<Tri> mix = random_soup(20, 2.0, 0.5);
        for (int k = 0; k < 12; k++) {
            double p[3] = {0.1 * k, -0.2 * k, 0.3}, q[3] = {0.1 * k + 1, -0.2 * k + 2, 0.3 + 3};
            double mid[3] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
            mix.push_back(make_tri(p, q, mid, -1000 - k));   // collinear
            mix.push_back(make_tri(p, p, p, -2000 - k));     // a point
            mix.push_back(make_tri(p, q, q, -3000 - k));     // two equal vertices
        }
        PQP_Model md;
        build_checking_progress(md, mix, 8, "degenerate mix");
        check_built_model(md, mix, "degenerate mix");

        std::vector<Tri> line, point, flat;
        for (int k = 0; k < 25; k++) {
            double a[3] = {(double)k, 0, 0}, b[3] = {k + 0.5, 0, 0}, c[3] = {k + 1.0, 0, 0};
            line.push_back(make_tri(a, b, c, k));
            double s[3] = {1, 2, 3};
            point.push_back(make_tri(s, s, s, 100 + k));
            double f0[3] = {(double)(k % 5), (double)(k / 5), 0}, f1[3] = {k % 5 + 1.0, (double)(k / 5), 0},
                   f2[3] = {(double)(k % 5), k / 5 + 1.0, 0};
            flat.push_back(make_tri(f0, f1, f2, 200 + k));
        }
        PQP_Model ml, mp, mf;
        build_checking_progress(ml, line, 25, "all collinear");
        check_built_model(ml, line, "all collinear");
        build_checking_progress(mp, point, 4, "all one point");
        check_built_model(mp, point, "all one point");
        build_checking_progress(mf, flat, 1, "flat grid");
        check_built_model(mf, flat, "flat grid");
    }

    // MemUsage: the view is built on first use, so the model's memory grows once tris and b have
    // been read.
    {
        snprintf(context, sizeof context, "MemUsage");
        std::vector<Tri> input = random_soup(500, 5.0, 0.5);
        PQP_Model mm;
        EXPECT(mm.BeginModel() == PQP_OK);
        for (size_t k = 0; k < input.size(); k++)
            EXPECT(mm.AddTri(input[k].p1, input[k].p2, input[k].p3, input[k].id) == PQP_OK);
        EXPECT(mm.EndModel() == PQP_OK);
        int before = mm.MemUsage(0);
        Tri *t = mm.tris;
        int after_tris = mm.MemUsage(0);
        BV *b = mm.b;
        int after_b = mm.MemUsage(0);
        EXPECT(t != NULL && b != NULL);
        EXPECT(before > 0 && after_tris >= before && after_b > before);
        EXPECT(mm.MemUsage(1) == after_b);
        printf("model_internals: MemUsage of a built 500-triangle model: %d bytes before reading "
               "its internals, %d after reading tris, %d after reading b\n",
               before, after_tris, after_b);
    }

    // 4 threads reading the view of a model at once (the first read builds it).
    check_threads(12);

    // The BV functions.
    const int kFits = 600, kOverlaps = 5000, kDistances = 5000;
    int overlap_skipped = 0;
    check_fit_to_tris(kFits);
    check_bv_overlap(kOverlaps, &overlap_skipped);
    check_bv_distance(kDistances);

    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    printf("model_internals: 7 models checked, 12 rounds of 4 threads, %d FitToTris, %d BV_Overlap "
           "(%d near-touching skipped), %d BV_Distance cases in %.1f s\n",
           kFits, kOverlaps, overlap_skipped, kDistances, secs);
    if (failures) {
        fprintf(stderr, "model_internals: %d check(s) failed\n", failures);
        return 1;
    }
    printf("model_internals: all checks passed\n");
    return 0;
}
