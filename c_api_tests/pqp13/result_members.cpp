// result_members.cpp -- PQP 1.3 programs read the query results' public data members directly
// (res.distance, res.p1, res.pairs[k].id1, res.closer_than_tolerance, res.R, ...), not only the
// accessor functions. This program checks every member of PQP_CollideResult, PQP_DistanceResult and
// PQP_ToleranceResult, after many queries on two irregular meshes in random poses, against a
// brute-force referee (bf.hpp, long double) run on the posed triangles, independently of the library:
//
//  - collide (ALL and FIRST): the pair list equals the set of overlapping triangle pairs (by id);
//  - distance (exact and approximate): the distance is the true one (or within the error bounds),
//    p1 lies on model 1 (in its frame) and p2 on model 2 (in its frame), R1 p1 + T1 and R2 p2 + T2
//    are `distance` apart;
//  - tolerance: the closer flag is (true distance <= tolerance), the distance and points agree;
//  - R and T are model 2's frame in model 1's, R1^T R2 and R1^T (T2 - T1);
//  - the accessors return the members, the statistics are sane, the arguments are echoed;
//  - a query that fails (NaN pose, negative error bound, ...) returns its code and leaves every
//    member as it was.
//
// Triangle pairs whose overlap or distance is within 1e-9 of the decision (touching to rounding) are
// allowed either answer. C++11.
#include "PQP.h"
#include "bf.hpp"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

typedef long double LD;
typedef bf::V<LD> LV;

static int failures = 0;
// The case being checked, printed with every failure (the pose index reproduces it: the poses come
// from a fixed seed).
static char context[200] = "setup";

#define EXPECT(cond)                                                                         \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            failures++;                                                                      \
            if (failures <= 200)                                                             \
                fprintf(stderr, "%s:%d: expected %s [%s]\n", __FILE__, __LINE__, #cond,      \
                        context);                                                            \
        }                                                                                    \
    } while (0)

// ---------------------------------------------------------------------------------------------
// Meshes

struct Mesh {
    std::vector<Tri> tris;        // model frame, in the order added; Tri from Tri.h
    std::map<int, int> index_of;  // id -> index in tris
};

static void add_triangle(Mesh &m, const double a[3], const double b[3], const double c[3], int id)
{
    Tri t;
    for (int i = 0; i < 3; i++) {
        t.p1[i] = a[i];
        t.p2[i] = b[i];
        t.p3[i] = c[i];
    }
    t.id = id;
    m.index_of[id] = static_cast<int>(m.tris.size());
    m.tris.push_back(t);
}

// A latitude-longitude sphere of radius 1 whose vertices are moved radially by up to 6%:
// 2 * nlon * (nlat - 1) triangles, ids 1000 + 3k (never the index).
static Mesh perturbed_sphere(int nlat, int nlon, std::mt19937_64 &rng)
{
    std::uniform_real_distribution<double> wobble(-0.06, 0.06);
    std::vector<std::vector<double> > v;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= nlat; i++) {
        int count = (i == 0 || i == nlat) ? 1 : nlon;
        for (int j = 0; j < count; j++) {
            double th = pi * i / nlat, ph = 2 * pi * j / nlon, r = 1 + wobble(rng);
            v.push_back({r * sin(th) * cos(ph), r * sin(th) * sin(ph), r * cos(th)});
        }
    }
    const int north = 0, south = static_cast<int>(v.size()) - 1;
    // Vertex j of ring i (1 <= i <= nlat - 1).
    auto ring = [&](int i, int j) { return 1 + (i - 1) * nlon + (j % nlon); };
    Mesh m;
    int k = 0;
    auto tri = [&](int a, int b, int c) {
        add_triangle(m, v[a].data(), v[b].data(), v[c].data(), 1000 + 3 * k);
        k++;
    };
    for (int j = 0; j < nlon; j++) tri(north, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < nlat - 1; i++)
        for (int j = 0; j < nlon; j++) {
            tri(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
            tri(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
        }
    for (int j = 0; j < nlon; j++) tri(south, ring(nlat - 1, j + 1), ring(nlat - 1, j));
    return m;
}

// A torus (radii 0.8 and 0.3, vertices moved by up to 0.02): 2 * nu * nv triangles, ids
// 100000 - 7k.
static Mesh perturbed_torus(int nu, int nv, std::mt19937_64 &rng)
{
    std::uniform_real_distribution<double> wobble(-0.02, 0.02);
    const double pi = 3.14159265358979323846;
    std::vector<std::vector<double> > v;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            double u = 2 * pi * i / nu, w = 2 * pi * j / nv, r = 0.3 + wobble(rng);
            v.push_back({(0.8 + r * cos(w)) * cos(u), (0.8 + r * cos(w)) * sin(u), r * sin(w)});
        }
    auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
    Mesh m;
    int k = 0;
    for (int i = 0; i < nu; i++)
        for (int j = 0; j < nv; j++) {
            add_triangle(m, v[at(i, j)].data(), v[at(i + 1, j)].data(), v[at(i + 1, j + 1)].data(),
                         100000 - 7 * k);
            k++;
            add_triangle(m, v[at(i, j)].data(), v[at(i + 1, j + 1)].data(), v[at(i, j + 1)].data(),
                         100000 - 7 * k);
            k++;
        }
    return m;
}

static void build_model(PQP_Model &model, const Mesh &mesh)
{
    EXPECT(model.BeginModel(static_cast<int>(mesh.tris.size())) == PQP_OK);
    for (size_t k = 0; k < mesh.tris.size(); k++) {
        const Tri &t = mesh.tris[k];
        EXPECT(model.AddTri(t.p1, t.p2, t.p3, t.id) == PQP_OK);
    }
    EXPECT(model.EndModel() == PQP_OK);
}

// ---------------------------------------------------------------------------------------------
// Poses and the brute-force referee

struct Pose {
    PQP_REAL R[3][3];
    PQP_REAL T[3];
};

// The rotation of a random unit quaternion (uniform over rotations).
static void random_rotation(PQP_REAL R[3][3], std::mt19937_64 &rng)
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

static LV lv(const PQP_REAL p[3])
{
    return LV{p[0], p[1], p[2]};
}

// R p + T in long double.
static LV apply(const Pose &pose, const LV &p)
{
    LD out[3];
    for (int i = 0; i < 3; i++)
        out[i] = (LD)pose.R[i][0] * p.x + (LD)pose.R[i][1] * p.y + (LD)pose.R[i][2] * p.z +
                 (LD)pose.T[i];
    return LV{out[0], out[1], out[2]};
}

struct Posed {
    LV v[3];
    LV centre;  // centroid
    LD radius;  // bounding radius about the centroid
};

static std::vector<Posed> pose_mesh(const Mesh &mesh, const Pose &pose)
{
    std::vector<Posed> out(mesh.tris.size());
    for (size_t k = 0; k < mesh.tris.size(); k++) {
        Posed &p = out[k];
        p.v[0] = apply(pose, lv(mesh.tris[k].p1));
        p.v[1] = apply(pose, lv(mesh.tris[k].p2));
        p.v[2] = apply(pose, lv(mesh.tris[k].p3));
        p.centre = (p.v[0] + p.v[1] + p.v[2]) * (LD(1) / 3);
        p.radius = 0;
        for (int i = 0; i < 3; i++) {
            LD r = sqrtl(bf::norm2(p.v[i] - p.centre));
            if (r > p.radius) p.radius = r;
        }
        p.radius = p.radius * (1 + 1e-12L) + 1e-15L;
    }
    return out;
}

// Pairs closer than this (or crossing less deeply than this) may be reported either way.
static const LD kAmbiguous = 1e-9L;

struct Brute {
    LD distance;                            // the models' distance (0 when some pair crosses)
    LV closest1, closest2;                  // a closest pair of points (world frame)
    std::set<std::pair<int, int> > overlap;  // index pairs that certainly collide
    std::set<std::pair<int, int> > maybe;    // index pairs within kAmbiguous of touching
};

// Every triangle pair by bf::triangle_triangle. A pair is skipped only when the bounding spheres of
// its two triangles prove it farther apart than both kAmbiguous and the best distance so far (it can
// then neither collide nor be the closest pair): the answer is that of all pairs.
static Brute brute_force(const std::vector<Posed> &a, const std::vector<Posed> &b)
{
    Brute out;
    out.distance = std::numeric_limits<LD>::infinity();
    for (size_t i = 0; i < a.size(); i++)
        for (size_t j = 0; j < b.size(); j++) {
            LD lower = sqrtl(bf::norm2(a[i].centre - b[j].centre)) - a[i].radius - b[j].radius;
            if (lower > kAmbiguous && lower > out.distance) continue;
            bf::TriTri<LD> tt = bf::triangle_triangle(a[i].v, b[j].v);
            std::pair<int, int> ij(static_cast<int>(i), static_cast<int>(j));
            if (tt.crossing) {
                if (tt.depth > kAmbiguous) out.overlap.insert(ij);
                else out.maybe.insert(ij);
            } else if (tt.dist <= kAmbiguous) {
                out.maybe.insert(ij);
            }
            if (tt.dist < out.distance) {
                out.distance = tt.dist;
                out.closest1 = tt.pa;
                out.closest2 = tt.pb;
            }
        }
    return out;
}

// Distance from p (model frame) to the nearest triangle of the mesh.
static LD distance_to_mesh(const Mesh &mesh, const PQP_REAL p[3])
{
    LD best = std::numeric_limits<LD>::infinity();
    LV q = lv(p);
    for (size_t k = 0; k < mesh.tris.size(); k++) {
        LV t[3] = {lv(mesh.tris[k].p1), lv(mesh.tris[k].p2), lv(mesh.tris[k].p3)};
        LD d2 = bf::point_triangle(q, t).d2;
        if (d2 < best) best = d2;
    }
    return sqrtl(best);
}

// ---------------------------------------------------------------------------------------------
// Checks shared by the three queries

struct Case {
    Mesh *mesh1, *mesh2;
    PQP_Model *model1, *model2;
    Pose pose1, pose2;
    Brute brute;
};

// R = R1^T R2 and T = R1^T (T2 - T1), to 1e-12.
static void check_relative_pose(const PQP_REAL R[3][3], const PQP_REAL T[3], const Case &c)
{
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            LD s = 0;
            for (int k = 0; k < 3; k++) s += (LD)c.pose1.R[k][i] * c.pose2.R[k][j];
            EXPECT(fabsl(R[i][j] - s) <= 1e-12L);
        }
        LD t = 0;
        for (int k = 0; k < 3; k++) t += (LD)c.pose1.R[k][i] * ((LD)c.pose2.T[k] - c.pose1.T[k]);
        EXPECT(fabsl(T[i] - t) <= 1e-12L);
    }
}

// The queue size echoed in the result: PQP 1.3 stores qsize only when it is above 2 (its queue
// search); pqp-rs always stores it (PQP_PQP_H, its C header's guard, is defined by its PQP.h).
static void check_qsize(int stored, int qsize, bool default_qsize)
{
    const int asked = default_qsize ? 2 : qsize;
#ifdef PQP_PQP_H
    EXPECT(stored == asked);
#else
    if (asked > 2) EXPECT(stored == asked);
#endif
}

// p1 on model 1 (its frame), p2 on model 2 (its frame), and their world images `distance` apart.
static void check_points(const PQP_REAL p1[3], const PQP_REAL p2[3], PQP_REAL distance,
                         const Case &c)
{
    EXPECT(distance_to_mesh(*c.mesh1, p1) <= 1e-9L);
    EXPECT(distance_to_mesh(*c.mesh2, p2) <= 1e-9L);
    LV w1 = apply(c.pose1, lv(p1)), w2 = apply(c.pose2, lv(p2));
    EXPECT(fabsl(sqrtl(bf::norm2(w1 - w2)) - distance) <= 1e-9L);
}

// Statistics: non-negative and what the accessors return.
template <class Result> static void check_stats(Result &res)
{
    EXPECT(res.num_bv_tests >= 0 && res.num_bv_tests == res.NumBVTests());
    EXPECT(res.num_tri_tests >= 0 && res.num_tri_tests == res.NumTriTests());
    EXPECT(res.query_time_secs >= 0.0 && res.query_time_secs == res.QueryTimeSecs());
}

static int collide_queries = 0, distance_queries = 0, tolerance_queries = 0, error_queries = 0;

// ---------------------------------------------------------------------------------------------
// PQP_Collide

static void check_collide(PQP_CollideResult &res, Case &c, int flag, bool default_flag)
{
    int rc = default_flag ? PQP_Collide(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                        c.pose2.T, c.model2)
                          : PQP_Collide(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                        c.pose2.T, c.model2, flag);
    collide_queries++;
    EXPECT(rc == PQP_OK);
    if (rc != PQP_OK) return;
    check_stats(res);
    check_relative_pose(res.R, res.T, c);
    EXPECT(res.NumPairs() == res.num_pairs);
    EXPECT(res.Colliding() == (res.num_pairs > 0 ? 1 : 0));
    EXPECT(res.num_pairs >= 0 && res.num_pairs_alloced >= res.num_pairs);
    EXPECT(res.num_pairs == 0 || res.pairs != NULL);

    // The reported pairs, as index pairs; each must be a known id pair, reported once, and a pair
    // that collides (or might, to rounding).
    std::set<std::pair<int, int> > seen;
    for (int k = 0; k < res.num_pairs; k++) {
        EXPECT(res.Id1(k) == res.pairs[k].id1 && res.Id2(k) == res.pairs[k].id2);
        std::map<int, int>::const_iterator i1 = c.mesh1->index_of.find(res.pairs[k].id1);
        std::map<int, int>::const_iterator i2 = c.mesh2->index_of.find(res.pairs[k].id2);
        EXPECT(i1 != c.mesh1->index_of.end() && i2 != c.mesh2->index_of.end());
        if (i1 == c.mesh1->index_of.end() || i2 == c.mesh2->index_of.end()) continue;
        std::pair<int, int> ij(i1->second, i2->second);
        EXPECT(seen.insert(ij).second);
        EXPECT(c.brute.overlap.count(ij) == 1 || c.brute.maybe.count(ij) == 1);
    }
    if (flag == PQP_ALL_CONTACTS) {
        // Every certainly colliding pair is reported.
        for (std::set<std::pair<int, int> >::const_iterator it = c.brute.overlap.begin();
             it != c.brute.overlap.end(); ++it)
            EXPECT(seen.count(*it) == 1);
    } else {
        // Exactly one pair when the models certainly collide, none when they certainly do not.
        if (!c.brute.overlap.empty()) EXPECT(res.num_pairs == 1);
        else if (c.brute.maybe.empty()) EXPECT(res.num_pairs == 0);
        else EXPECT(res.num_pairs <= 1);
    }
}

// ---------------------------------------------------------------------------------------------
// PQP_Distance

static void check_distance(PQP_DistanceResult &res, Case &c, PQP_REAL rel, PQP_REAL abs,
                           int qsize, bool default_qsize)
{
    int rc = default_qsize ? PQP_Distance(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                          c.pose2.T, c.model2, rel, abs)
                           : PQP_Distance(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                          c.pose2.T, c.model2, rel, abs, qsize);
    distance_queries++;
    EXPECT(rc == PQP_OK);
    if (rc != PQP_OK) return;
    check_stats(res);
    check_relative_pose(res.R, res.T, c);
    // The arguments, echoed (qsize 2 is the default).
    EXPECT(res.rel_err == rel && res.abs_err == abs);
    check_qsize(res.qsize, qsize, default_qsize);
    // Accessors.
    EXPECT(res.Distance() == res.distance);
    EXPECT(res.P1() == res.p1 && res.P2() == res.p2);

    const LD truth = c.brute.distance, d = res.distance;
    const LD slack = 1e-10L * (truth > 1 ? truth : 1);
    // Never below the true distance; at most min(true (1 + rel), true + abs); exact when abs = 0.
    LD upper = truth * (1 + (LD)rel);
    if (truth + (LD)abs < upper) upper = truth + (LD)abs;
    EXPECT(d >= truth - slack);
    EXPECT(d <= upper + slack);
    if (abs == 0) EXPECT(fabsl(d - truth) <= slack);
    // Certainly colliding models are at distance 0 exactly.
    if (!c.brute.overlap.empty()) EXPECT(res.distance == 0);
    check_points(res.p1, res.p2, res.distance, c);
}

// ---------------------------------------------------------------------------------------------
// PQP_Tolerance

static void check_tolerance(PQP_ToleranceResult &res, Case &c, PQP_REAL tolerance, int qsize,
                            bool default_qsize)
{
    int rc = default_qsize ? PQP_Tolerance(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                           c.pose2.T, c.model2, tolerance)
                           : PQP_Tolerance(&res, c.pose1.R, c.pose1.T, c.model1, c.pose2.R,
                                           c.pose2.T, c.model2, tolerance, qsize);
    tolerance_queries++;
    EXPECT(rc == PQP_OK);
    if (rc != PQP_OK) return;
    check_stats(res);
    check_relative_pose(res.R, res.T, c);
    EXPECT(res.tolerance == tolerance);
    check_qsize(res.qsize, qsize, default_qsize);
    EXPECT(res.CloserThanTolerance() == res.closer_than_tolerance);
    EXPECT(res.Distance() == res.distance);
    EXPECT(res.P1() == res.p1 && res.P2() == res.p2);
    EXPECT(res.closer_than_tolerance == 0 || res.closer_than_tolerance == 1);

    const LD truth = c.brute.distance;
    const LD slack = 1e-10L * (truth > 1 ? truth : 1);
    // The flag is the truth, except within 1e-9 of the threshold.
    if (fabsl(truth - (LD)tolerance) > 1e-9L)
        EXPECT(res.closer_than_tolerance == (truth <= (LD)tolerance ? 1 : 0));
    if (res.closer_than_tolerance) {
        // A triangle pair within the tolerance: its distance and points.
        EXPECT(res.distance <= tolerance);
        EXPECT(res.distance >= truth - slack);
        check_points(res.p1, res.p2, res.distance, c);
    } else {
#ifdef PQP_PQP_H
        // pqp-rs documents a lower bound on the distance, above the tolerance (PQP 1.3 leaves the
        // distance unspecified when not closer).
        EXPECT(res.distance > tolerance);
        EXPECT(res.distance <= truth + slack);
#endif
    }
}

// ---------------------------------------------------------------------------------------------
// Failing queries leave every member as it was

struct CollideSnapshot {
    int num_bv_tests, num_tri_tests, num_pairs_alloced, num_pairs;
    double query_time_secs;
    PQP_REAL R[3][3], T[3];
    CollisionPair *pairs;
    std::vector<CollisionPair> content;
    explicit CollideSnapshot(const PQP_CollideResult &r)
        : num_bv_tests(r.num_bv_tests), num_tri_tests(r.num_tri_tests),
          num_pairs_alloced(r.num_pairs_alloced), num_pairs(r.num_pairs),
          query_time_secs(r.query_time_secs), pairs(r.pairs),
          content(r.pairs, r.pairs + r.num_pairs)
    {
        memcpy(R, r.R, sizeof R);
        memcpy(T, r.T, sizeof T);
    }
    bool same(const PQP_CollideResult &r) const
    {
        if (r.num_bv_tests != num_bv_tests || r.num_tri_tests != num_tri_tests ||
            r.num_pairs_alloced != num_pairs_alloced || r.num_pairs != num_pairs ||
            r.query_time_secs != query_time_secs || r.pairs != pairs)
            return false;
        if (memcmp(R, r.R, sizeof R) != 0 || memcmp(T, r.T, sizeof T) != 0) return false;
        for (int k = 0; k < num_pairs; k++)
            if (r.pairs[k].id1 != content[k].id1 || r.pairs[k].id2 != content[k].id2) return false;
        return true;
    }
};

// Distance and tolerance results have only scalars and arrays: compare member by member, bitwise.
#define SAME_MEMBER(a, b, m) (memcmp(&(a).m, &(b).m, sizeof((a).m)) == 0)

static bool same_distance(const PQP_DistanceResult &a, const PQP_DistanceResult &b)
{
    return SAME_MEMBER(a, b, num_bv_tests) && SAME_MEMBER(a, b, num_tri_tests) &&
           SAME_MEMBER(a, b, query_time_secs) && SAME_MEMBER(a, b, R) && SAME_MEMBER(a, b, T) &&
           SAME_MEMBER(a, b, rel_err) && SAME_MEMBER(a, b, abs_err) &&
           SAME_MEMBER(a, b, distance) && SAME_MEMBER(a, b, p1) && SAME_MEMBER(a, b, p2) &&
           SAME_MEMBER(a, b, qsize);
}

static bool same_tolerance(const PQP_ToleranceResult &a, const PQP_ToleranceResult &b)
{
    return SAME_MEMBER(a, b, num_bv_tests) && SAME_MEMBER(a, b, num_tri_tests) &&
           SAME_MEMBER(a, b, query_time_secs) && SAME_MEMBER(a, b, R) && SAME_MEMBER(a, b, T) &&
           SAME_MEMBER(a, b, closer_than_tolerance) && SAME_MEMBER(a, b, tolerance) &&
           SAME_MEMBER(a, b, distance) && SAME_MEMBER(a, b, p1) && SAME_MEMBER(a, b, p2) &&
           SAME_MEMBER(a, b, qsize);
}

// The codes for NaN poses, negative bounds, qsize 0 and unknown flags are pqp-rs's (PQP_PQP_H, its
// C header's guard, is defined by its PQP.h): PQP 1.3 has none and runs such queries, so they are
// checked against pqp-rs only, and the program also builds against PQP 1.3.
static void check_failing_queries(Case &c, PQP_Model *unbuilt)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    Pose bad_T = c.pose2, bad_R = c.pose1;
    bad_T.T[1] = nan;
    bad_R.R[2][0] = inf;
    Pose &p1 = c.pose1, &p2 = c.pose2;

    // Collide: first a successful query (so there is an answer to keep), then failing ones.
    snprintf(context, sizeof context, "failing collide queries");
    PQP_CollideResult cres;
    EXPECT(PQP_Collide(&cres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2) == PQP_OK);
    CollideSnapshot before(cres);
#ifdef PQP_PQP_H
    EXPECT(PQP_Collide(&cres, p1.R, p1.T, c.model1, bad_T.R, bad_T.T, c.model2) ==
           PQP_ERR_NONFINITE_POSE);
    EXPECT(before.same(cres));
    EXPECT(PQP_Collide(&cres, bad_R.R, bad_R.T, c.model1, p2.R, p2.T, c.model2,
                       PQP_FIRST_CONTACT) == PQP_ERR_NONFINITE_POSE);
    EXPECT(before.same(cres));
    EXPECT(PQP_Collide(&cres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 7) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(before.same(cres));
#endif
    EXPECT(PQP_Collide(&cres, p1.R, p1.T, c.model1, p2.R, p2.T, unbuilt) ==
           PQP_ERR_UNPROCESSED_MODEL);
    EXPECT(before.same(cres));
    error_queries += 4;

    snprintf(context, sizeof context, "failing distance queries");
    PQP_DistanceResult dres;
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 0.1, 0.01, 5) ==
           PQP_OK);
    const PQP_DistanceResult dkept = dres;  // a copy of the members (copies are deep)
    EXPECT(same_distance(dkept, dres));
#ifdef PQP_PQP_H
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, -1, 0) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_distance(dkept, dres));
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 0, -1) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_distance(dkept, dres));
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, nan, 0) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_distance(dkept, dres));
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 0, 0, 0) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_distance(dkept, dres));
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, c.model1, bad_T.R, bad_T.T, c.model2, 0, 0) ==
           PQP_ERR_NONFINITE_POSE);
    EXPECT(same_distance(dkept, dres));
    EXPECT(PQP_Distance(&dres, bad_R.R, bad_R.T, c.model1, p2.R, p2.T, c.model2, 0, 0) ==
           PQP_ERR_NONFINITE_POSE);
    EXPECT(same_distance(dkept, dres));
#endif
    EXPECT(PQP_Distance(&dres, p1.R, p1.T, unbuilt, p2.R, p2.T, c.model2, 0, 0) ==
           PQP_ERR_UNPROCESSED_MODEL);
    EXPECT(same_distance(dkept, dres));
    error_queries += 7;

    snprintf(context, sizeof context, "failing tolerance queries");
    PQP_ToleranceResult tres;
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 0.5, 4) == PQP_OK);
    const PQP_ToleranceResult tkept = tres;
    EXPECT(same_tolerance(tkept, tres));
#ifdef PQP_PQP_H
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, -1) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_tolerance(tkept, tres));
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, nan) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_tolerance(tkept, tres));
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, c.model1, p2.R, p2.T, c.model2, 0.5, 0) ==
           PQP_ERR_INVALID_ARGUMENT);
    EXPECT(same_tolerance(tkept, tres));
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, c.model1, bad_T.R, bad_T.T, c.model2, 0.5) ==
           PQP_ERR_NONFINITE_POSE);
    EXPECT(same_tolerance(tkept, tres));
#endif
    EXPECT(PQP_Tolerance(&tres, p1.R, p1.T, unbuilt, p2.R, p2.T, c.model2, 0.5) ==
           PQP_ERR_UNPROCESSED_MODEL);
    EXPECT(same_tolerance(tkept, tres));
    error_queries += 5;
}

// ---------------------------------------------------------------------------------------------

int main()
{
    std::mt19937_64 rng(20240611);
    Mesh sphere = perturbed_sphere(8, 16, rng);  // 224 triangles
    Mesh torus = perturbed_torus(16, 7, rng);    // 224 triangles
    PQP_Model sphere_model, torus_model;
    build_model(sphere_model, sphere);
    build_model(torus_model, torus);
    EXPECT(sphere_model.num_tris == 224 && torus_model.num_tris == 224);

    // Results reused across every pose (as programs do; pqp-rs keeps caches in them), and fresh
    // ones for some queries.
    PQP_CollideResult collide_all, collide_first;
    PQP_DistanceResult distance_reused;
    PQP_ToleranceResult tolerance_reused;

    const int kPoses = 240;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> g(0.0, 1.0);
    int colliding = 0, within = 0, farther = 0;
    for (int n = 0; n < kPoses; n++) {
        // Model 1 is the sphere or the torus, model 2 the other one or the same model (self
        // queries, as a model against a moved copy of itself).
        Case c;
        const int kind = n % 3;
        c.mesh1 = kind == 1 ? &torus : &sphere;
        c.mesh2 = kind == 0 ? &torus : &sphere;
        c.model1 = kind == 1 ? &torus_model : &sphere_model;
        c.model2 = kind == 0 ? &torus_model : &sphere_model;

        random_rotation(c.pose1.R, rng);
        random_rotation(c.pose2.R, rng);
        // Centres apart by s along a random direction: 0..1.2 (overlapping), 1.2..2 (touching),
        // 2..2.6 (then moved to within 1e-6..0.1, below), 2.6..8 (far).
        double s;
        switch (n % 4) {
        case 0: s = 1.2 * unit(rng); break;
        case 1: s = 1.2 + 0.8 * unit(rng); break;
        case 2: s = 2.0 + 0.6 * unit(rng); break;
        default: s = 2.6 + 5.4 * unit(rng); break;
        }
        double dir[3] = {g(rng), g(rng), g(rng)};
        double dn = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        for (int i = 0; i < 3; i++) {
            c.pose1.T[i] = 4 * unit(rng) - 2;
            c.pose2.T[i] = c.pose1.T[i] + s * dir[i] / dn;
        }

        c.brute = brute_force(pose_mesh(*c.mesh1, c.pose1), pose_mesh(*c.mesh2, c.pose2));
        if (n % 4 == 2 && c.brute.distance > 0) {
            // A near pose: model 2 moved along the closest points' direction until they are g
            // apart, g from 1e-6 to 0.1 (the models' distance is then at most g).
            const LD gap = c.brute.distance, g = powl(10.0L, -6 + 5 * unit(rng));
            const LV towards = (c.brute.closest1 - c.brute.closest2) * ((gap - g) / gap);
            c.pose2.T[0] += (double)towards.x;
            c.pose2.T[1] += (double)towards.y;
            c.pose2.T[2] += (double)towards.z;
            c.brute = brute_force(pose_mesh(*c.mesh1, c.pose1), pose_mesh(*c.mesh2, c.pose2));
        }
        const LD truth = c.brute.distance;
        if (!c.brute.overlap.empty()) colliding++;
        else if (truth < 0.1L) within++;
        else farther++;
        snprintf(context, sizeof context, "pose %d: true distance %.12Lg, %zu pairs collide", n,
                 truth, c.brute.overlap.size());

        // Collide: ALL with the default flag and explicitly, FIRST, on reused and fresh results.
        check_collide(collide_all, c, PQP_ALL_CONTACTS, n % 2 == 0);
        check_collide(collide_first, c, PQP_FIRST_CONTACT, false);
        {
            PQP_CollideResult fresh;
            check_collide(fresh, c, PQP_ALL_CONTACTS, false);
        }

        // Distance: exact (fresh and reused result, default and explicit queue size), then with
        // error bounds (abs_err 0 keeps it exact whatever rel_err is).
        {
            PQP_DistanceResult fresh;
            check_distance(fresh, c, 0.0, 0.0, 2, true);
        }
        check_distance(distance_reused, c, 0.0, 0.0, 2, true);
        check_distance(distance_reused, c, 0.0, 0.0, 20, false);
        check_distance(distance_reused, c, 0.1, 0.0, 2, true);
        check_distance(distance_reused, c, 0.1, 0.05, 2, true);
        check_distance(distance_reused, c, 0.1, 1e9, 10, false);
        check_distance(distance_reused, c, 0.5, 0.2, 3, false);

        // Tolerance: thresholds around the true distance and fixed ones.
        const double tolerances[] = {0.0,
                                     0.05,
                                     0.3,
                                     (double)(truth * 0.5L),
                                     (double)(truth * 0.999L),
                                     (double)(truth + 1e-6L),
                                     (double)(truth * 1.5L + 0.01L),
                                     1e9};
        for (size_t k = 0; k < sizeof tolerances / sizeof tolerances[0]; k++) {
            check_tolerance(tolerance_reused, c, tolerances[k], 2, k % 2 == 0);
            if (k % 3 == 0) {
                PQP_ToleranceResult fresh;
                check_tolerance(fresh, c, tolerances[k], 8, false);
            }
        }

        if (n == kPoses - 1) {
            PQP_Model unbuilt;
            check_failing_queries(c, &unbuilt);
        }
    }

    // No time is printed: the output is diffed against PQP 1.3's (c_api_tests/README.md).
    // Nor the number of failing queries, most of which are pqp-rs's (check_failing_queries).
    printf("result_members: %d poses (%d colliding, %d within 0.1, %d farther), %d collide, %d "
           "distance and %d tolerance queries checked\n",
           kPoses, colliding, within, farther, collide_queries, distance_queries, tolerance_queries);
    EXPECT(error_queries > 0);
    if (failures) {
        fprintf(stderr, "result_members: %d check(s) failed\n", failures);
        return 1;
    }
    printf("result_members: all checks passed\n");
    return 0;
}
