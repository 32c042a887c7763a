// PQP 1.3 programs keep models and results in containers and copy them: std::vector<PQP_Model>
// with push_back(model), copy construction and assignment. PQP 1.3's copies shared the arrays and
// freed them twice; pqp-rs's are deep and independent. This program checks independence (a copy
// outlives, and is rebuilt apart from, its original) and that every copy answers as the original
// did and as brute force does. Compiles as C++98 (copies) and C++11 and later (copies and moves);
// the brute-force referee (bf.hpp) is C++11, so C++98 builds compare with the original's answers.
#include "PQP.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <vector>
#if __cplusplus >= 201103L
#include <utility>

#include "bf.hpp"
#endif

static int failures = 0;

#define EXPECT(cond)                                                               \
    do {                                                                           \
        if (!(cond)) {                                                             \
            fprintf(stderr, "%s:%d: expected %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                                            \
        }                                                                          \
    } while (0)

// A deterministic pseudo-random number in [0, 1) (a 32-bit congruential generator: C++98 has no
// 64-bit integer type).
static double uniform(unsigned int &state)
{
    state = state * 1664525u + 1013904223u;
    return state / 4294967296.0;
}

// A mesh of n random triangles in the cube [-1, 1]^3 around `centre`, ids 1000 + k.
struct Mesh
{
    std::vector<double> v; // 9 per triangle
    int n;
};

static Mesh random_mesh(int n, double centre, unsigned int seed)
{
    Mesh m;
    m.n = n;
    for (int k = 0; k < 9 * n; k++) m.v.push_back(centre + 2.0 * uniform(seed) - 1.0);
    return m;
}

static void add_all(PQP_Model &model, const Mesh &mesh, int from, int to)
{
    for (int k = from; k < to; k++) {
        PQP_REAL p[3][3];
        for (int i = 0; i < 9; i++) p[i / 3][i % 3] = mesh.v[9 * k + i];
        EXPECT(model.AddTri(p[0], p[1], p[2], 1000 + k) == PQP_OK);
    }
}

static void build(PQP_Model &model, const Mesh &mesh)
{
    EXPECT(model.BeginModel() == PQP_OK || model.build_state == 1);
    add_all(model, mesh, 0, mesh.n);
    EXPECT(model.EndModel() == PQP_OK);
}

static PQP_REAL I3[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static PQP_REAL ZERO[3] = {0, 0, 0};

// The exact distance of `model` (at the identity) to `other` translated by (offset, 0, 0).
static double distance(PQP_Model &model, PQP_Model &other, double offset)
{
    PQP_REAL T[3] = {(PQP_REAL)offset, 0, 0};
    PQP_DistanceResult r;
    EXPECT(PQP_Distance(&r, I3, ZERO, &model, I3, T, &other, 0, 0) == PQP_OK);
    return r.distance;
}

// The number of colliding pairs of `model` and `other` translated by (offset, 0, 0).
static int pairs(PQP_Model &model, PQP_Model &other, double offset)
{
    PQP_REAL T[3] = {(PQP_REAL)offset, 0, 0};
    PQP_CollideResult r;
    EXPECT(PQP_Collide(&r, I3, ZERO, &model, I3, T, &other) == PQP_OK);
    return r.num_pairs;
}

#if __cplusplus >= 201103L
// Brute force: the distance between the meshes, b translated by (offset, 0, 0), over all pairs.
static double brute_distance(const Mesh &a, const Mesh &b, double offset)
{
    typedef bf::V<long double> V;
    long double best = INFINITY;
    for (int i = 0; i < a.n; i++)
        for (int j = 0; j < b.n; j++) {
            const double *p = &a.v[9 * i], *q = &b.v[9 * j];
            V s[3] = {{p[0], p[1], p[2]}, {p[3], p[4], p[5]}, {p[6], p[7], p[8]}};
            V t[3] = {{q[0] + offset, q[1], q[2]}, {q[3] + offset, q[4], q[5]},
                      {q[6] + offset, q[7], q[8]}};
            best = std::min(best, bf::triangle_triangle(s, t).dist);
        }
    return (double)best;
}
#endif

int main()
{
    const Mesh ma = random_mesh(60, 0.0, 1), mb = random_mesh(50, 0.0, 2);
    PQP_Model other;
    build(other, mb);
    const double offsets[3] = {0.5, 2.5, 4.0};

    // The original's answers, recorded before it goes away.
    double d0[3];
    int c0[3];
    std::vector<PQP_Model> kept;
    PQP_Model assigned;
    {
        PQP_Model original;
        build(original, ma);
        for (int k = 0; k < 3; k++) {
            d0[k] = distance(original, other, offsets[k]);
            c0[k] = pairs(original, other, offsets[k]);
        }
        kept.push_back(original);          // copy into a container
        kept.push_back(original);
        PQP_Model copied(original);        // copy construction
        kept.push_back(copied);
        assigned = original;               // copy assignment onto a fresh model
        assigned = assigned;               // self-assignment keeps it
        EXPECT(&kept[0].tris[0] != &original.tris[0]);
        EXPECT(kept[0].num_tris == ma.n && kept[0].build_state == 2);
        EXPECT(kept[0].tris[5].id == original.tris[5].id);
        EXPECT(kept[0].tris[5].p2[1] == original.tris[5].p2[1]);
    } // the original is destroyed here; PQP 1.3's copies would now point at freed memory

    for (size_t m = 0; m < kept.size(); m++)
        for (int k = 0; k < 3; k++) {
            EXPECT(distance(kept[m], other, offsets[k]) == d0[k]);
            EXPECT(pairs(kept[m], other, offsets[k]) == c0[k]);
        }
    for (int k = 0; k < 3; k++) EXPECT(distance(assigned, other, offsets[k]) == d0[k]);
#if __cplusplus >= 201103L
    for (int k = 0; k < 3; k++) {
        double bf = brute_distance(ma, mb, offsets[k]);
        EXPECT(fabs(d0[k] - bf) <= 1e-12 * (1.0 + bf));
    }
    EXPECT(c0[0] > 0 && c0[2] == 0);
#endif

    // Rebuilding one copy with other triangles leaves the others as they were.
    build(kept[1], mb);
    EXPECT(kept[1].num_tris == mb.n && kept[0].num_tris == ma.n);
    EXPECT(kept[1].tris[0].id == 1000 && kept[1].tris[0].p1[0] == mb.v[0]);
    EXPECT(kept[0].tris[0].p1[0] == ma.v[0]);
    for (int k = 0; k < 3; k++) EXPECT(distance(kept[0], other, offsets[k]) == d0[k]);

    // A model copied while being built: each copy goes on on its own.
    {
        PQP_Model half;
        EXPECT(half.BeginModel() == PQP_OK);
        add_all(half, ma, 0, 30);
        PQP_Model twin(half);
        EXPECT(twin.build_state == 1 && twin.num_tris == 30);
        add_all(twin, ma, 30, ma.n);
        EXPECT(half.num_tris == 30 && twin.num_tris == ma.n);
        EXPECT(twin.EndModel() == PQP_OK && half.EndModel() == PQP_OK);
        EXPECT(twin.num_tris == ma.n && half.num_tris == 30);
        for (int k = 0; k < 3; k++) EXPECT(distance(twin, other, offsets[k]) == d0[k]);
        EXPECT(distance(half, other, offsets[0]) >= d0[0]);
    }

    // Results copy too; a collide result's pairs are its own.
    {
        PQP_REAL T[3] = {(PQP_REAL)offsets[0], 0, 0};
        PQP_CollideResult r;
        EXPECT(PQP_Collide(&r, I3, ZERO, &kept[0], I3, T, &other) == PQP_OK);
        PQP_CollideResult s(r);
        std::vector<PQP_CollideResult> list(2, r);
        EXPECT(s.num_pairs == c0[0] && list[1].num_pairs == c0[0] && s.pairs != r.pairs);
        r.FreePairsList();
        EXPECT(r.num_pairs == 0 && s.num_pairs == c0[0]);
        for (int k = 0; k < s.num_pairs; k++) EXPECT(s.Id1(k) == list[0].Id1(k));
        PQP_DistanceResult d;
        EXPECT(PQP_Distance(&d, I3, ZERO, &kept[0], I3, T, &other, 0, 0) == PQP_OK);
        std::vector<PQP_DistanceResult> ds(3, d);
        EXPECT(ds[2].distance == d.distance && ds[2].p1[0] == d.p1[0] && ds[2].qsize == 2);
    }

#if __cplusplus >= 201103L
    // Moves: growing a vector moves its models; a moved-from model is empty and reusable.
    {
        std::vector<PQP_Model> grown;
        for (int k = 0; k < 9; k++) {
            grown.emplace_back();
            build(grown.back(), k % 2 ? ma : mb);
        }
        for (int k = 0; k < 9; k++) EXPECT(grown[k].num_tris == (k % 2 ? ma.n : mb.n));
        EXPECT(distance(grown[1], other, offsets[1]) == d0[1]);
        PQP_Model moved(std::move(grown[1]));
        EXPECT(distance(moved, other, offsets[1]) == d0[1]);
        EXPECT(grown[1].num_tris == 0 && grown[1].build_state == 0);
        build(grown[1], ma);
        EXPECT(distance(grown[1], other, offsets[2]) == d0[2]);
        PQP_Model target;
        target = std::move(moved);
        EXPECT(distance(target, other, offsets[0]) == d0[0]);
    }
#endif

    if (failures != 0) return 1;
    printf("all checks passed\n");
    return 0;
}
