// pqp-rs against FCL 0.7, same meshes and poses, same process. See BENCHMARKS.md.
//
//   pqp_bench [--models DIR] [--only w1,w2,...] [--reps N] [--quick] [--ours-only] [--threads N]
//             [--no-verify]
// Workloads: spheres shells bunny-collide bunny-distance coherent build threads strategies
// build-speed (only when named, with PQP 1.3 built in: ours on 1 and on every core against it), and
// peers when built with PQP 1.3 or Coal (CMake -DPQP13_SOURCE_DIR, -DCOAL_PREFIX; see
// BENCHMARKS.md) (default: all). `strategies` times our distance query with every search strategy
// (ours only); `peers` runs ours, PQP 1.3 and Coal in alternating rounds.
// --quick shrinks every workload (for valgrind); --ours-only skips FCL (for profiling ours).
// --fcl-rss-collide also times FCL's collision on BVHModel<RSS> (very slow); --cube F sets the side
// of the bunny workloads' offset cube in bunny radii (default 2).
//
// Timing: every query is timed on its own with std::chrono::steady_clock; the pose set is run
// `reps` times (default 3) and each pose keeps its fastest run (the machine is shared, and the
// minimum is the least noisy estimate of a query's cost); the table reports the median over poses.

#include <pqp/pqp.h>

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/detail/traversal/collision/mesh_collision_traversal_node.h>
#include <fcl/narrowphase/detail/traversal/collision_node.h>
#include <fcl/narrowphase/detail/traversal/distance/mesh_distance_traversal_node.h>
#include <fcl/narrowphase/distance.h>
#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cstdarg>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "brute.hpp"
#include "workloads.hpp"
#ifdef PQP_BENCH_WITH_PQP13
#include "pqp13_peer.hpp"
#endif
#ifdef PQP_BENCH_WITH_COAL
#include "coal_peer.hpp"
#endif

#ifndef PQP_BENCH_MODELS_DIR
#define PQP_BENCH_MODELS_DIR "/work/shared/models"
#endif

using namespace bench;
using Clock = std::chrono::steady_clock;
using PairList = std::vector<std::pair<int, int>>;

namespace {

// ---------------------------------------------------------------------------------------------
// Options and small utilities

struct Options {
    std::string models = PQP_BENCH_MODELS_DIR;
    std::set<std::string> only;
    int reps = 3;
    bool quick = false;
    bool ours_only = false;
    bool verify = true;
    int threads = 0;
    bool fcl_rss_collide = false;  // FCL's RSS collision is ~500x slower than its OBB: off by default
    double cube = 2.0;  // side of the bunny workloads' offset cube, in bunny radii
    bool want(const std::string& w) const { return only.empty() || only.count(w) != 0; }
};

// Exits without running static destructors: with FCL and Coal both linked, their static objects
// were destroyed twice at exit ("double free detected" after an unknown option).
[[noreturn]] void die(const std::string& msg) {
    std::fprintf(stderr, "pqp_bench: %s\n", msg.c_str());
    std::fflush(stderr);
    std::_Exit(1);
}

void check(int rc, const char* what) {
    if (rc != PQP_OK) die(std::string(what) + ": " + pqp_error_string(rc));
}

double secs(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

double median(std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? std::nan("") : s / static_cast<double>(v.size());
}

std::string fmt(const char* f, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char* f, ...) {
    char buf[512];
    va_list ap;
    va_start(ap, f);
    std::vsnprintf(buf, sizeof buf, f, ap);
    va_end(ap);
    return buf;
}

// Distances agree when within 1e-9 relative (with a 1e-12 absolute floor for touching poses).
bool same_distance(double a, double b) {
    return std::fabs(a - b) <= 1e-9 * std::max(std::fabs(a), std::fabs(b)) + 1e-12;
}

size_t heap_in_use() {
    const struct mallinfo2 mi = mallinfo2();
    return mi.uordblks + mi.hblkhd;
}

// Runs query(i) for every pose, `reps` times; returns each pose's fastest time in seconds.
// record(i) runs after the first timed run of pose i, outside the timed region.
template <class Q, class R>
std::vector<double> time_each(size_t n, int reps, Q&& query, R&& record) {
    std::vector<double> best(n, std::numeric_limits<double>::infinity());
    for (int rep = 0; rep < reps; ++rep) {
        for (size_t i = 0; i < n; ++i) {
            const auto t0 = Clock::now();
            query(i);
            const auto t1 = Clock::now();
            best[i] = std::min(best[i], secs(t0, t1));
            if (rep == 0) record(i);
        }
    }
    return best;
}

// ---------------------------------------------------------------------------------------------
// Meshes

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

std::vector<Pose> load_path(const std::string& path) {
    std::ifstream in(path);
    if (!in) die("cannot open " + path);
    long n = 0;
    in >> n;
    std::vector<Pose> out(static_cast<size_t>(n));
    for (auto& p : out) {
        for (double& x : p.R) in >> x;
        for (double& x : p.T) in >> x;
    }
    if (!in) die("bad .path file " + path);
    return out;
}

struct Box {
    std::array<double, 3> lo, hi;
    std::array<double, 3> centre() const {
        return {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
    }
    double size() const { return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}); }
};

Box bounds(const Mesh& m) {
    Box b;
    b.lo.fill(std::numeric_limits<double>::infinity());
    b.hi.fill(-std::numeric_limits<double>::infinity());
    for (const auto& t : m)
        for (int k = 0; k < 9; ++k) {
            b.lo[k % 3] = std::min(b.lo[k % 3], t[k]);
            b.hi[k % 3] = std::max(b.hi[k % 3], t[k]);
        }
    return b;
}

// ---------------------------------------------------------------------------------------------
// The two libraries' models

pqp_model* build_ours(const Mesh& mesh) {
    pqp_model* m = pqp_model_create();
    if (!m) die("pqp_model_create failed");
    check(pqp_model_begin(m, static_cast<int>(mesh.size())), "pqp_model_begin");
    for (size_t i = 0; i < mesh.size(); ++i)
        check(pqp_model_add_tri(m, &mesh[i][0], &mesh[i][3], &mesh[i][6], static_cast<int>(i)),
              "pqp_model_add_tri");
    check(pqp_model_end(m), "pqp_model_end");
    return m;
}

struct OurModel {
    pqp_model* m = nullptr;
    OurModel() = default;
    explicit OurModel(const Mesh& mesh) : m(build_ours(mesh)) {}
    OurModel(const OurModel&) = delete;
    OurModel& operator=(const OurModel&) = delete;
    ~OurModel() { pqp_model_destroy(m); }
};

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

// FCL's BVHModel memory, from its public counts: one BVNode<BV> per node, the vertex array (FCL
// stores three vertices per triangle added with addTriangle), the index triangles, and the
// primitive index array the builder keeps (one unsigned int per triangle).
template <class BV>
size_t fcl_memory_estimate(const fcl::BVHModel<BV>& m) {
    return static_cast<size_t>(m.getNumBVs()) * sizeof(fcl::BVNode<BV>) +
           static_cast<size_t>(m.num_vertices) * sizeof(fcl::Vector3d) +
           static_cast<size_t>(m.num_tris) * (sizeof(fcl::Triangle) + sizeof(unsigned int));
}

fcl::Transform3d to_fcl(const Pose& p) {
    fcl::Matrix3d R;
    R << p.R[0], p.R[1], p.R[2], p.R[3], p.R[4], p.R[5], p.R[6], p.R[7], p.R[8];
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = R;
    tf.translation() = fcl::Vector3d(p.T[0], p.T[1], p.T[2]);
    return tf;
}

struct FclModels {
    std::shared_ptr<fcl::BVHModel<fcl::RSSd>> rss;
    std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> obbrss;
    std::shared_ptr<fcl::BVHModel<fcl::OBBd>> obb;
    void build(const Mesh& m) {
        rss = build_fcl<fcl::RSSd>(m);
        obbrss = build_fcl<fcl::OBBRSSd>(m);
        obb = build_fcl<fcl::OBBd>(m);
    }
};

// ---------------------------------------------------------------------------------------------
// One pair of models with a list of poses, and the queries run on it

struct Case {
    std::string name;
    const Mesh* mesh1;
    const Mesh* mesh2;
    std::vector<std::pair<Pose, Pose>> poses;
    OurModel ours1, ours2;
    FclModels fcl1, fcl2;
    std::vector<std::pair<fcl::Transform3d, fcl::Transform3d>> tfs;

    Case(std::string n, const Mesh& a, const Mesh& b, std::vector<std::pair<Pose, Pose>> p, bool with_fcl)
        : name(std::move(n)), mesh1(&a), mesh2(&b), poses(std::move(p)), ours1(a), ours2(b) {
        if (with_fcl) {
            fcl1.build(a);
            fcl2.build(b);
        }
        for (const auto& pp : poses) tfs.emplace_back(to_fcl(pp.first), to_fcl(pp.second));
    }
    size_t size() const { return poses.size(); }
};

// A table row: one query on one workload.
struct Row {
    std::string workload, query;
    size_t n = 0;
    double ours_med = NAN, ours_mean = NAN;
    double fcl_med = NAN, fcl_mean = NAN;
    std::string fcl_variant;
    double bv = NAN, tri = NAN;
    std::string ours_ck, fcl_ck;
    std::string agree;
    std::string note;
};

// Every FCL variant's result on a query, for the secondary table.
struct VariantRow {
    std::string workload, query, variant;
    double med, mean_;
    std::string ck;
    std::string agree;
    double bv = NAN, tri = NAN;  // FCL's own counters, where measured
};

std::vector<Row> g_rows;
std::vector<VariantRow> g_variants;
std::vector<std::string> g_notes;

struct DistAnswers {
    std::vector<double> d;
    std::vector<double> time;
    double bv = 0, tri = 0;
    double sum() const {
        double s = 0;
        for (double x : d) s += x;
        return s;
    }
};

// ---- ours

DistAnswers ours_distance(Case& c, int reps, double rel_err, double abs_err) {
    DistAnswers a;
    a.d.resize(c.size());
    pqp_distance_result* r = pqp_distance_result_create();
    int rc = PQP_OK;
    a.time = time_each(
        c.size(), reps,
        [&](size_t i) {
            const auto& p = c.poses[i];
            rc |= pqp_distance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(),
                               p.second.T.data(), c.ours2.m, rel_err, abs_err, 2);
        },
        [&](size_t i) {
            a.d[i] = pqp_distance_result_distance(r);
            a.bv += static_cast<double>(pqp_distance_result_num_bv_tests(r));
            a.tri += static_cast<double>(pqp_distance_result_num_tri_tests(r));
        });
    check(rc, "pqp_distance");
    pqp_distance_result_destroy(r);
    a.bv /= static_cast<double>(c.size());
    a.tri /= static_cast<double>(c.size());
    return a;
}

struct TolAnswers {
    std::vector<int> closer;
    std::vector<double> time;
    double bv = 0, tri = 0;
    int count() const {
        int s = 0;
        for (int x : closer) s += x;
        return s;
    }
};

TolAnswers ours_tolerance(Case& c, int reps, double tol) {
    TolAnswers a;
    a.closer.resize(c.size());
    pqp_tolerance_result* r = pqp_tolerance_result_create();
    int rc = PQP_OK;
    a.time = time_each(
        c.size(), reps,
        [&](size_t i) {
            const auto& p = c.poses[i];
            rc |= pqp_tolerance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(),
                                p.second.T.data(), c.ours2.m, tol, 2);
        },
        [&](size_t i) {
            a.closer[i] = pqp_tolerance_result_closer_than_tolerance(r);
            a.bv += static_cast<double>(pqp_tolerance_result_num_bv_tests(r));
            a.tri += static_cast<double>(pqp_tolerance_result_num_tri_tests(r));
        });
    check(rc, "pqp_tolerance");
    pqp_tolerance_result_destroy(r);
    a.bv /= static_cast<double>(c.size());
    a.tri /= static_cast<double>(c.size());
    return a;
}

struct CollAnswers {
    std::vector<int> colliding;
    std::vector<PairList> pairs;  // all contacts: sorted; first contact: the one pair reported
    std::vector<double> time;
    double bv = 0, tri = 0;
    int poses_colliding() const {
        int s = 0;
        for (int x : colliding) s += x;
        return s;
    }
    size_t total_pairs() const {
        size_t s = 0;
        for (const auto& p : pairs) s += p.size();
        return s;
    }
};

CollAnswers ours_collide(Case& c, int reps, int flag) {
    CollAnswers a;
    a.colliding.resize(c.size());
    a.pairs.resize(c.size());
    pqp_collide_result* r = pqp_collide_result_create();
    int rc = PQP_OK;
    a.time = time_each(
        c.size(), reps,
        [&](size_t i) {
            const auto& p = c.poses[i];
            rc |= pqp_collide(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(),
                              p.second.T.data(), c.ours2.m, flag);
        },
        [&](size_t i) {
            a.colliding[i] = pqp_collide_result_colliding(r);
            const int n = pqp_collide_result_num_pairs(r);
            const pqp_contact_pair* pr = pqp_collide_result_pairs(r);
            for (int k = 0; k < n; ++k) a.pairs[i].emplace_back(pr[k].id1, pr[k].id2);
            std::sort(a.pairs[i].begin(), a.pairs[i].end());
            a.bv += static_cast<double>(pqp_collide_result_num_bv_tests(r));
            a.tri += static_cast<double>(pqp_collide_result_num_tri_tests(r));
        });
    check(rc, "pqp_collide");
    pqp_collide_result_destroy(r);
    a.bv /= static_cast<double>(c.size());
    a.tri /= static_cast<double>(c.size());
    return a;
}

// ---- FCL

template <class BV>
DistAnswers fcl_distance(const fcl::BVHModel<BV>& m1, const fcl::BVHModel<BV>& m2, Case& c, int reps,
                         double rel_err = 0.0) {
    DistAnswers a;
    a.d.resize(c.size());
    fcl::DistanceRequestd req(true);
    req.rel_err = rel_err;
    fcl::DistanceResultd res;
    a.time = time_each(
        c.size(), reps,
        [&](size_t i) {
            res.clear();
            fcl::distance(&m1, c.tfs[i].first, &m2, c.tfs[i].second, req, res);
        },
        [&](size_t i) { a.d[i] = res.min_distance; });
    return a;
}

template <class BV>
CollAnswers fcl_collide(const fcl::BVHModel<BV>& m1, const fcl::BVHModel<BV>& m2, Case& c, int reps,
                        bool all) {
    CollAnswers a;
    a.colliding.resize(c.size());
    a.pairs.resize(c.size());
    fcl::CollisionRequestd req(all ? std::numeric_limits<size_t>::max() : 1, false);
    fcl::CollisionResultd res;
    a.time = time_each(
        c.size(), reps,
        [&](size_t i) {
            res.clear();
            fcl::collide(&m1, c.tfs[i].first, &m2, c.tfs[i].second, req, res);
        },
        [&](size_t i) {
            a.colliding[i] = res.isCollision() ? 1 : 0;
            for (size_t k = 0; k < res.numContacts(); ++k) {
                const auto& ct = res.getContact(k);
                a.pairs[i].emplace_back(ct.b1, ct.b2);
            }
            std::sort(a.pairs[i].begin(), a.pairs[i].end());
        });
    return a;
}

// FCL's work counters: its high-level calls do not return them, so the traversal is re-run (untimed)
// through the same internal entry points the high-level call uses, with statistics on.
struct FclStats {
    double bv = 0, tri = 0, sum_d = 0;
};

FclStats fcl_distance_stats_rss(const fcl::BVHModel<fcl::RSSd>& m1, const fcl::BVHModel<fcl::RSSd>& m2, Case& c,
                                double rel_err = 0.0, size_t limit = std::numeric_limits<size_t>::max()) {
    FclStats st;
    fcl::DistanceRequestd req(true);
    req.rel_err = rel_err;
    const size_t n = std::min(limit, c.size());
    for (size_t i = 0; i < n; ++i) {
        fcl::DistanceResultd res;
        fcl::detail::MeshDistanceTraversalNodeRSS<double> node;
        fcl::detail::initialize(node, m1, c.tfs[i].first, m2, c.tfs[i].second, req, res);
        node.enable_statistics = true;
        fcl::detail::distance(&node);
        st.bv += node.num_bv_tests;
        st.tri += node.num_leaf_tests;
        st.sum_d += res.min_distance;
    }
    st.bv /= static_cast<double>(n);
    st.tri /= static_cast<double>(n);
    return st;
}

FclStats fcl_collide_stats_obb(const fcl::BVHModel<fcl::OBBd>& m1, const fcl::BVHModel<fcl::OBBd>& m2, Case& c,
                               bool all) {
    FclStats st;
    const fcl::CollisionRequestd req(all ? std::numeric_limits<size_t>::max() : 1, false);
    for (size_t i = 0; i < c.size(); ++i) {
        fcl::CollisionResultd res;
        fcl::detail::MeshCollisionTraversalNodeOBB<double> node;
        fcl::detail::initialize(node, m1, c.tfs[i].first, m2, c.tfs[i].second, req, res);
        node.enable_statistics = true;
        fcl::detail::collide(&node);
        st.bv += node.num_bv_tests;
        st.tri += node.num_leaf_tests;
    }
    st.bv /= static_cast<double>(c.size());
    st.tri /= static_cast<double>(c.size());
    return st;
}

// ---------------------------------------------------------------------------------------------
// Comparing answers, and refereeing disagreements by brute force

const Options* g_opt = nullptr;

std::string compare_distances(Case& c, const std::string& query, const std::string& who, const DistAnswers& ours,
                              const DistAnswers& other) {
    int bad = 0, refereed = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (same_distance(ours.d[i], other.d[i])) continue;
        ++bad;
        std::string line = fmt("%s/%s: pose %zu: ours %.17g, %s %.17g", c.name.c_str(), query.c_str(), i,
                               ours.d[i], who.c_str(), other.d[i]);
        if (g_opt->verify && refereed < 3) {
            ++refereed;
            const double bf = brute::mesh_distance(*c.mesh1, c.poses[i].first, *c.mesh2, c.poses[i].second,
                                                   std::max(ours.d[i], other.d[i]));
            line += fmt("; brute force %.17g (ours off by %.3g, %s off by %.3g)", bf, ours.d[i] - bf, who.c_str(),
                        other.d[i] - bf);
        }
        g_notes.push_back(line);
    }
    return bad == 0 ? "yes" : fmt("NO (%d poses)", bad);
}

std::string compare_flags(Case& c, const std::string& query, const std::string& who, const std::vector<int>& ours,
                          const std::vector<int>& other) {
    int bad = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (ours[i] == other[i]) continue;
        ++bad;
        g_notes.push_back(fmt("%s/%s: pose %zu: ours %d, %s %d", c.name.c_str(), query.c_str(), i, ours[i],
                              who.c_str(), other[i]));
    }
    return bad == 0 ? "yes" : fmt("NO (%d poses)", bad);
}

// All-contacts: the pair sets must be equal. A differing pair is refereed with the brute-force
// triangle distance (0 = they intersect) so touching cases show as such.
std::string compare_pair_sets(Case& c, const std::string& query, const std::string& who, const CollAnswers& ours,
                              const CollAnswers& other) {
    int bad = 0, shown = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        if (ours.pairs[i] == other.pairs[i]) continue;
        ++bad;
        PairList only_ours, only_other;
        std::set_difference(ours.pairs[i].begin(), ours.pairs[i].end(), other.pairs[i].begin(),
                            other.pairs[i].end(), std::back_inserter(only_ours));
        std::set_difference(other.pairs[i].begin(), other.pairs[i].end(), ours.pairs[i].begin(),
                            ours.pairs[i].end(), std::back_inserter(only_other));
        std::string line = fmt("%s/%s: pose %zu: %zu pairs only in ours, %zu only in %s", c.name.c_str(),
                               query.c_str(), i, only_ours.size(), only_other.size(), who.c_str());
        if (g_opt->verify && shown < 5) {
            ++shown;
            auto referee = [&](const PairList& l, const char* tag) {
                for (size_t k = 0; k < std::min<size_t>(l.size(), 4); ++k) {
                    const double d = brute::pair_distance(*c.mesh1, c.poses[i].first, l[k].first, *c.mesh2,
                                                          c.poses[i].second, l[k].second);
                    line += fmt("; %s (%d,%d) brute-force distance %.3g", tag, l[k].first, l[k].second, d);
                }
            };
            referee(only_ours, "only-ours");
            referee(only_other, "only-other");
        }
        g_notes.push_back(line);
    }
    return bad == 0 ? "yes" : fmt("NO (%d poses)", bad);
}

// First-contact: both must agree on colliding; each reported pair must really intersect.
int count_false_first_pairs(Case& c, const CollAnswers& a) {
    int bad = 0;
    for (size_t i = 0; i < c.size(); ++i)
        for (const auto& p : a.pairs[i])
            if (brute::pair_distance(*c.mesh1, c.poses[i].first, p.first, *c.mesh2, c.poses[i].second, p.second) >
                1e-9)
                ++bad;
    return bad;
}

std::string us(double s) { return fmt("%.2f", s * 1e6); }

// Keeps the fastest FCL variant in the main row and every variant in the secondary table.
void add_variant(Row& row, const std::string& variant, const std::vector<double>& times, const std::string& ck,
                 const std::string& agree) {
    const double med = median(times);
    g_variants.push_back({row.workload, row.query, variant, med, mean(times), ck, agree});
    if (std::isnan(row.fcl_med) || med < row.fcl_med) {
        row.fcl_med = med;
        row.fcl_mean = mean(times);
        row.fcl_variant = variant;
        row.fcl_ck = ck;
        row.agree = agree;
    }
}

void set_stats(const FclStats& st) {
    g_variants.back().bv = st.bv;
    g_variants.back().tri = st.tri;
}

// ---------------------------------------------------------------------------------------------
// Query runners shared by the workloads

void run_distance(Case& c, const std::string& workload, const Options& o, DistAnswers* ours_out = nullptr,
                  const std::string& query = "distance") {
    Row row;
    row.workload = workload;
    row.query = query;
    row.n = c.size();
    DistAnswers ours = ours_distance(c, o.reps, 0.0, 0.0);
    row.ours_med = median(ours.time);
    row.ours_mean = mean(ours.time);
    row.bv = ours.bv;
    row.tri = ours.tri;
    row.ours_ck = fmt("sum d = %.12f", ours.sum());
    if (!o.ours_only) {
        auto rss = fcl_distance(*c.fcl1.rss, *c.fcl2.rss, c, o.reps);
        add_variant(row, "RSS", rss.time, fmt("sum d = %.12f", rss.sum()), compare_distances(c, query, "FCL-RSS", ours, rss));
        set_stats(fcl_distance_stats_rss(*c.fcl1.rss, *c.fcl2.rss, c));
        auto obbrss = fcl_distance(*c.fcl1.obbrss, *c.fcl2.obbrss, c, o.reps);
        add_variant(row, "OBBRSS", obbrss.time, fmt("sum d = %.12f", obbrss.sum()),
                    compare_distances(c, query, "FCL-OBBRSS", ours, obbrss));
    }
    g_rows.push_back(row);
    if (ours_out) *ours_out = std::move(ours);
}

void run_tolerance(Case& c, const std::string& workload, const Options& o, double tol) {
    Row row;
    row.workload = workload;
    row.query = fmt("tolerance %g", tol);
    row.n = c.size();
    TolAnswers ours = ours_tolerance(c, o.reps, tol);
    row.ours_med = median(ours.time);
    row.ours_mean = mean(ours.time);
    row.bv = ours.bv;
    row.tri = ours.tri;
    row.ours_ck = fmt("%d closer", ours.count());
    row.note = "FCL has no tolerance query: its time is an exact distance query, then d <= t";
    if (!o.ours_only) {
        auto run = [&](auto& m1, auto& m2, const char* v) {
            auto d = fcl_distance(m1, m2, c, o.reps);
            std::vector<int> closer(c.size());
            int n = 0;
            for (size_t i = 0; i < c.size(); ++i) n += closer[i] = d.d[i] <= tol ? 1 : 0;
            add_variant(row, v, d.time, fmt("%d closer", n),
                        compare_flags(c, row.query, std::string("FCL-") + v, ours.closer, closer));
        };
        run(*c.fcl1.rss, *c.fcl2.rss, "RSS");
        run(*c.fcl1.obbrss, *c.fcl2.obbrss, "OBBRSS");
    }
    g_rows.push_back(row);
}

void run_collide(Case& c, const std::string& workload, const Options& o, bool all) {
    Row row;
    row.workload = workload;
    row.query = all ? "collide all" : "collide first";
    row.n = c.size();
    const CollAnswers ours = ours_collide(c, o.reps, all ? PQP_ALL_CONTACTS : PQP_FIRST_CONTACT);
    row.ours_med = median(ours.time);
    row.ours_mean = mean(ours.time);
    row.bv = ours.bv;
    row.tri = ours.tri;
    auto ck = [&](const CollAnswers& a) {
        return all ? fmt("%d poses, %zu pairs", a.poses_colliding(), a.total_pairs())
                   : fmt("%d poses", a.poses_colliding());
    };
    row.ours_ck = ck(ours);
    if (!all && o.verify) {
        const int bad = count_false_first_pairs(c, ours);
        if (bad) g_notes.push_back(fmt("%s/collide first: %d pairs reported by ours are apart (brute force)", c.name.c_str(), bad));
    }
    if (!o.ours_only) {
        auto run = [&](auto& m1, auto& m2, const char* v) {
            const CollAnswers f = fcl_collide(m1, m2, c, o.reps, all);
            const std::string who = std::string("FCL-") + v;
            const std::string agree = all ? compare_pair_sets(c, row.query, who, ours, f)
                                          : compare_flags(c, row.query, who, ours.colliding, f.colliding);
            add_variant(row, v, f.time, ck(f), agree);
        };
        run(*c.fcl1.obb, *c.fcl2.obb, "OBB");
        set_stats(fcl_collide_stats_obb(*c.fcl1.obb, *c.fcl2.obb, c, all));
        run(*c.fcl1.obbrss, *c.fcl2.obbrss, "OBBRSS");
        if (o.fcl_rss_collide) run(*c.fcl1.rss, *c.fcl2.rss, "RSS");
    }
    g_rows.push_back(row);
}

// ---------------------------------------------------------------------------------------------
// Workloads

void workload_spheres(const Options& o) {
    const Mesh sphere = uv_sphere(1.0, kSphereLat, kSphereLon);
    const auto sp = spheres_poses(o.quick ? 10 : 100);
    std::vector<std::pair<Pose, Pose>> poses;
    for (const auto& p : sp) poses.emplace_back(p.p1, p.p2);
    Case c("spheres", sphere, sphere, poses, !o.ours_only);
    DistAnswers ours;
    run_distance(c, "1 spheres-distance", o, &ours);
    // Per-gap medians (ours, and FCL-RSS if run).
    DistAnswers fcl;
    if (!o.ours_only) fcl = fcl_distance(*c.fcl1.rss, *c.fcl2.rss, c, o.reps);
    const size_t per = sp.size() / 4;
    for (int g = 0; g < 4; ++g) {
        std::vector<double> to(ours.time.begin() + g * per, ours.time.begin() + (g + 1) * per);
        std::string line = fmt("spheres gap %g: ours median %s us", sp[g * per].gap, us(median(to)).c_str());
        if (!o.ours_only) {
            std::vector<double> tf(fcl.time.begin() + g * per, fcl.time.begin() + (g + 1) * per);
            line += fmt(", FCL-RSS median %s us, ratio %.2f", us(median(tf)).c_str(), median(tf) / median(to));
        }
        g_notes.push_back(line);
    }
    // The generator's fingerprint, which examples/bvtt_efficiency.rs prints too: the sum of every
    // pose entry (R1, T1, R2, T2 per pose, in order) and then of every vertex coordinate.
    double fingerprint = 0.0;
    for (const auto& p : sp) {
        for (double x : p.p1.R) fingerprint += x;
        for (double x : p.p1.T) fingerprint += x;
        for (double x : p.p2.R) fingerprint += x;
        for (double x : p.p2.T) fingerprint += x;
    }
    for (const auto& t : sphere)
        for (double x : t) fingerprint += x;
    uint64_t bits = 0;
    std::memcpy(&bits, &fingerprint, sizeof bits);
    g_notes.push_back(fmt("spheres: %zu triangles per sphere; generator fingerprint %.17g (bits %016" PRIx64 ")",
                          sphere.size(), fingerprint, bits));
}

void workload_shells(const Options& all) {
    // A query here takes a large fraction of a second, so one run per pose is already a stable
    // measurement; repeating would cost minutes.
    Options o = all;
    o.reps = 1;
    const Mesh inner = uv_sphere(1.0, kSphereLat, kSphereLon);
    const Mesh outer = uv_sphere(1.05, kSphereLat, kSphereLon);
    Rng rng(2);
    std::vector<std::pair<Pose, Pose>> poses;
    const int n = o.quick ? 20 : 200;
    const Pose id{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};
    for (int k = 0; k < n; ++k) poses.emplace_back(id, Pose{random_rotation(rng), {0, 0, 0}});
    Case c("shells", inner, outer, poses, !o.ours_only);
    DistAnswers exact;
    run_distance(c, "2 shells", o, &exact, "distance exact");

    Row row;
    row.workload = "2 shells";
    row.query = "distance rel_err 0.1";
    row.n = c.size();
    const DistAnswers approx = ours_distance(c, o.reps, 0.1, 1e300);
    row.ours_med = median(approx.time);
    row.ours_mean = mean(approx.time);
    row.bv = approx.bv;
    row.tri = approx.tri;
    row.ours_ck = fmt("sum d = %.12f", approx.sum());
    int bad = 0;
    for (size_t i = 0; i < c.size(); ++i) {
        const double t = exact.d[i];
        if (!(approx.d[i] >= t * (1 - 1e-12) && approx.d[i] <= t * 1.1 * (1 + 1e-12))) ++bad;
    }
    row.note = "FCL ignores rel_err/abs_err for mesh-mesh distance; its number is its exact query";
    if (!o.ours_only) {
        // FCL's exact time is its number for this row; it is also run with rel_err = 0.1 to show
        // the bound changes nothing.
        const std::string agree = bad == 0 ? "bound holds" : fmt("NO: bound broken on %d poses", bad);
        std::vector<VariantRow> exact_rows;
        for (const auto& v : g_variants)
            if (v.workload == "2 shells" && v.query == "distance exact") exact_rows.push_back(v);
        for (const auto& v : exact_rows) {
            g_variants.push_back({row.workload, row.query, v.variant + " (exact)", v.med, v.mean_, v.ck, agree});
            if (std::isnan(row.fcl_med) || v.med < row.fcl_med) {
                row.fcl_med = v.med;
                row.fcl_mean = v.mean_;
                row.fcl_variant = v.variant + " exact";
                row.fcl_ck = v.ck;
                row.agree = agree;
            }
        }
        // FCL with rel_err = 0.1 requested, on the first poses: same answers and the same work
        // (its counters) as its exact query, which shows the bound is ignored without timing noise.
        const size_t few = std::min<size_t>(c.size(), 10);
        const FclStats st_exact = fcl_distance_stats_rss(*c.fcl1.rss, *c.fcl2.rss, c, 0.0, few);
        const FclStats st_rel = fcl_distance_stats_rss(*c.fcl1.rss, *c.fcl2.rss, c, 0.1, few);
        g_notes.push_back(fmt("shells: FCL-RSS on the first %zu poses: %.0f BV tests/q exact, %.0f with rel_err 0.1 "
                              "requested; sum d %.12f and %.12f",
                              few, st_exact.bv, st_rel.bv, st_exact.sum_d, st_rel.sum_d));
    } else {
        row.agree = bad == 0 ? "bound holds" : fmt("NO: bound broken on %d poses", bad);
    }
    g_rows.push_back(row);
}

// Workloads 3 and 4: bunny vs bunny and bunny vs torus, 4,000 poses (seed 3). Per pose: R1, R2 =
// random rotations, offset = ((2u-1) s, (2u-1) s, (2u-1) s) with s the bunny's radius (half its
// largest bounding-box side), so the offsets fill a cube of side 2s; each model's bounding-box centre
// is placed at the origin and at the offset respectively.
std::vector<std::pair<Pose, Pose>> bunny_poses(const Mesh& m1, const Mesh& m2, double s, int n) {
    Rng rng(3);
    const auto c1 = bounds(m1).centre(), c2 = bounds(m2).centre();
    std::vector<std::pair<Pose, Pose>> out;
    for (int k = 0; k < n; ++k) {
        Pose p1, p2;
        p1.R = random_rotation(rng);
        p2.R = random_rotation(rng);
        std::array<double, 3> off;
        for (double& x : off) x = (2.0 * rng.uniform() - 1.0) * s;
        for (int r = 0; r < 3; ++r) {
            p1.T[r] = -(p1.R[3 * r] * c1[0] + p1.R[3 * r + 1] * c1[1] + p1.R[3 * r + 2] * c1[2]);
            p2.T[r] = off[r] - (p2.R[3 * r] * c2[0] + p2.R[3 * r + 1] * c2[1] + p2.R[3 * r + 2] * c2[2]);
        }
        out.emplace_back(p1, p2);
    }
    return out;
}

void workload_bunny(const Options& o, bool collide, bool distance) {
    const Mesh bunny = load_tris(o.models + "/bunny.tris");
    const Mesh torus = load_tris(o.models + "/torus.tris");
    // The bunny's size is taken as its radius, half its largest bounding-box side (0.778): a cube of
    // side twice that (offsets within +-radius) makes most poses collide, as the workload intends
    // (with the full width as the size only ~30% would).
    const double radius = 0.5 * bounds(bunny).size();
    const int n = o.quick ? 400 : 4000;
    // Tolerance 0.05 in the bunny's units: its bounding box is about 1.56 x 1.54 x 1.21, so 0.05 is
    // about 3% of its size; kept as given.
    const double tol = 0.05;
    for (int which = 0; which < 2; ++which) {
        const Mesh& other = which == 0 ? bunny : torus;
        const std::string name = which == 0 ? "bunny-bunny" : "bunny-torus";
        Case c(name, bunny, other, bunny_poses(bunny, other, 0.5 * o.cube * radius, n), !o.ours_only);
        if (collide) {
            run_collide(c, "3 " + name, o, true);
            run_collide(c, "3 " + name, o, false);
        }
        if (distance) {
            run_distance(c, "4 " + name, o);
            run_tolerance(c, "4 " + name, o, tol);
        }
    }
    g_notes.push_back(fmt("bunny: %zu tris, radius %.4f (half its largest bounding-box side), offsets in a cube of "
                          "side %.4f; torus: %zu tris",
                          bunny.size(), radius, o.cube * radius, torus.size()));
}

void workload_coherent(const Options& o) {
    const Mesh t1 = load_tris(o.models + "/torus1.tris");
    const Mesh t2 = load_tris(o.models + "/torus2.tris");
    const auto p1 = load_path(o.models + "/torus1.path");
    const auto p2 = load_path(o.models + "/torus2.path");
    if (p1.size() != p2.size()) die("path lengths differ");
    std::vector<std::pair<Pose, Pose>> poses;
    const size_t n = o.quick ? std::min<size_t>(300, p1.size()) : p1.size();
    for (size_t k = 0; k < n; ++k) poses.emplace_back(p1[k], p2[k]);
    Case c("coherent", t1, t2, poses, !o.ours_only);

    // Cached: one result object for the whole path (a fresh one per repetition).
    Row cached;
    cached.workload = "5 coherent";
    cached.query = "distance, result reused";
    cached.n = n;
    DistAnswers a;
    a.d.resize(n);
    a.time.assign(n, std::numeric_limits<double>::infinity());
    int rc = PQP_OK;
    for (int rep = 0; rep < o.reps; ++rep) {
        pqp_distance_result* r = pqp_distance_result_create();
        for (size_t i = 0; i < n; ++i) {
            const auto& p = c.poses[i];
            const auto t0 = Clock::now();
            rc |= pqp_distance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(), p.second.T.data(),
                               c.ours2.m, 0.0, 0.0, 2);
            const auto t1c = Clock::now();
            a.time[i] = std::min(a.time[i], secs(t0, t1c));
            if (rep == 0) {
                a.d[i] = pqp_distance_result_distance(r);
                a.bv += static_cast<double>(pqp_distance_result_num_bv_tests(r));
                a.tri += static_cast<double>(pqp_distance_result_num_tri_tests(r));
            }
        }
        pqp_distance_result_destroy(r);
    }
    check(rc, "pqp_distance");
    cached.ours_med = median(a.time);
    cached.ours_mean = mean(a.time);
    cached.bv = a.bv / static_cast<double>(n);
    cached.tri = a.tri / static_cast<double>(n);
    cached.ours_ck = fmt("sum d = %.12f", a.sum());

    // Fresh: a new result object every frame (created and destroyed outside the timed call).
    Row fresh = cached;
    fresh.query = "distance, fresh result";
    fresh.fcl_med = NAN;
    DistAnswers b;
    b.d.resize(n);
    b.time.assign(n, std::numeric_limits<double>::infinity());
    for (int rep = 0; rep < o.reps; ++rep)
        for (size_t i = 0; i < n; ++i) {
            pqp_distance_result* r = pqp_distance_result_create();
            const auto& p = c.poses[i];
            const auto t0 = Clock::now();
            rc |= pqp_distance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(), p.second.T.data(),
                               c.ours2.m, 0.0, 0.0, 2);
            const auto t1c = Clock::now();
            b.time[i] = std::min(b.time[i], secs(t0, t1c));
            if (rep == 0) {
                b.d[i] = pqp_distance_result_distance(r);
                b.bv += static_cast<double>(pqp_distance_result_num_bv_tests(r));
                b.tri += static_cast<double>(pqp_distance_result_num_tri_tests(r));
            }
            pqp_distance_result_destroy(r);
        }
    check(rc, "pqp_distance");
    fresh.ours_med = median(b.time);
    fresh.ours_mean = mean(b.time);
    fresh.bv = b.bv / static_cast<double>(n);
    fresh.tri = b.tri / static_cast<double>(n);
    fresh.ours_ck = fmt("sum d = %.12f", b.sum());
    fresh.agree = compare_distances(c, "fresh vs cached", "ours-fresh", a, b) == "yes" ? "= cached answers" : "NO";
    if (!o.ours_only) {
        auto rss = fcl_distance(*c.fcl1.rss, *c.fcl2.rss, c, o.reps);
        add_variant(cached, "RSS", rss.time, fmt("sum d = %.12f", rss.sum()),
                    compare_distances(c, "coherent", "FCL-RSS", a, rss));
        set_stats(fcl_distance_stats_rss(*c.fcl1.rss, *c.fcl2.rss, c));
        auto obbrss = fcl_distance(*c.fcl1.obbrss, *c.fcl2.obbrss, c, o.reps);
        add_variant(cached, "OBBRSS", obbrss.time, fmt("sum d = %.12f", obbrss.sum()),
                    compare_distances(c, "coherent", "FCL-OBBRSS", a, obbrss));
        fresh.fcl_med = cached.fcl_med;
        fresh.fcl_mean = cached.fcl_mean;
        fresh.fcl_variant = cached.fcl_variant;
        fresh.fcl_ck = cached.fcl_ck;
    }
    int zero = 0;
    for (double d : a.d) zero += d <= 0.0;
    g_notes.push_back(fmt("coherent: %zu frames, %d with the tori touching (distance 0); torus1 %zu tris, torus2 %zu tris",
                          n, zero, t1.size(), t2.size()));
    g_rows.push_back(cached);
    g_rows.push_back(fresh);
}

// ---- Search strategies (ours only): every pose in order with one result object, so the triangle
// cache carries from pose to pose as it would in an application.

struct StrategyRow {
    std::string workload, strategy;
    size_t poses;
    double med, mean_, bv, tri, sum;
};
std::vector<StrategyRow> g_strategies;

void run_strategies(Case& c, const std::string& workload, int reps) {
    // Breadth-first cannot prune before it reaches triangle pairs, which on 40,000-triangle models
    // takes most of the BVTT: it runs on the first few poses only (sums then cover those poses).
    struct Variant {
        const char* name;
        int strategy, qsize;
    };
    const size_t bfs_poses = std::min<size_t>(c.size(), 3);
    const Variant variants[] = {
        {"auto (default: priority, queue of 1024)", PQP_SEARCH_AUTO, 1024},
        {"priority, unbounded queue", PQP_SEARCH_PRIORITY, 0},
        {"priority, queue of 32 (PQP's qsize 32)", PQP_SEARCH_PRIORITY, 32},
        {"depth-first (PQP's default, qsize 2)", PQP_SEARCH_DEPTH_FIRST, 0},
        {"breadth-first", PQP_SEARCH_BREADTH_FIRST, 0},
    };
    double reference = NAN;
    for (const Variant& v : variants)
        for (int cache = 1; cache >= 0; --cache) {
            pqp_search_options opt = pqp_search_options_default();
            opt.strategy = v.strategy;
            opt.qsize = v.qsize;
            opt.triangle_cache = cache;
            const size_t n = v.strategy == PQP_SEARCH_BREADTH_FIRST ? bfs_poses : c.size();
            std::vector<double> t(n, std::numeric_limits<double>::infinity());
            double bv = 0, tri = 0, sum = 0;
            int rc = PQP_OK;
            const int runs = v.strategy == PQP_SEARCH_BREADTH_FIRST ? 1 : reps;
            for (int rep = 0; rep < runs; ++rep) {
                pqp_distance_result* r = pqp_distance_result_create();
                for (size_t i = 0; i < n; ++i) {
                    const auto& p = c.poses[i];
                    const auto t0 = Clock::now();
                    rc |= pqp_distance_search(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(),
                                              p.second.T.data(), c.ours2.m, 0.0, 0.0, &opt);
                    t[i] = std::min(t[i], secs(t0, Clock::now()));
                    if (rep == 0) {
                        bv += static_cast<double>(pqp_distance_result_num_bv_tests(r));
                        tri += static_cast<double>(pqp_distance_result_num_tri_tests(r));
                        sum += pqp_distance_result_distance(r);
                    }
                }
                pqp_distance_result_destroy(r);
            }
            check(rc, "pqp_distance_search");
            if (std::isnan(reference)) reference = sum;
            if (n == c.size() && !same_distance(sum, reference))
                g_notes.push_back(fmt("strategies/%s: %s gives sum d %.12f, not %.12f", workload.c_str(), v.name, sum,
                                      reference));
            const double nd = static_cast<double>(n);
            g_strategies.push_back({workload, std::string(v.name) + (cache ? ", cache" : ", no cache"), n, median(t),
                                    mean(t), bv / nd, tri / nd, sum});
        }
}

void workload_strategies(const Options& o) {
    {
        const Mesh sphere = uv_sphere(1.0, kSphereLat, kSphereLon);
        const auto sp = spheres_poses(o.quick ? 10 : 100);
        std::vector<std::pair<Pose, Pose>> poses;
        for (const auto& p : sp) poses.emplace_back(p.p1, p.p2);
        Case c("spheres", sphere, sphere, poses, false);
        run_strategies(c, "1 spheres-distance", o.reps);
    }
    const Mesh t1 = load_tris(o.models + "/torus1.tris");
    const Mesh t2 = load_tris(o.models + "/torus2.tris");
    const auto p1 = load_path(o.models + "/torus1.path");
    const auto p2 = load_path(o.models + "/torus2.path");
    std::vector<std::pair<Pose, Pose>> poses;
    const size_t n = o.quick ? std::min<size_t>(300, p1.size()) : std::min(p1.size(), p2.size());
    for (size_t k = 0; k < n; ++k) poses.emplace_back(p1[k], p2[k]);
    Case c("coherent", t1, t2, poses, false);
    run_strategies(c, "5 coherent", o.reps);
}

struct BuildRow {
    size_t tris;
    std::string lib;
    double secs;
    double bytes_per_tri_reported;
    double bytes_per_tri_heap;
};
std::vector<BuildRow> g_build;

template <class BV>
void build_fcl_row(const Mesh& m, int reps, const char* name) {
    double best = std::numeric_limits<double>::infinity();
    size_t est = 0, heap = 0;
    for (int r = 0; r < reps; ++r) {
        const size_t h0 = heap_in_use();
        const auto t0 = Clock::now();
        auto model = build_fcl<BV>(m);
        const auto t1 = Clock::now();
        heap = heap_in_use() - h0;
        est = fcl_memory_estimate(*model);
        best = std::min(best, secs(t0, t1));
    }
    const double n = static_cast<double>(m.size());
    g_build.push_back({m.size(), std::string("FCL BVHModel<") + name + ">", best, static_cast<double>(est) / n,
                       static_cast<double>(heap) / n});
}

void workload_build(const Options& o) {
    std::vector<std::pair<int, int>> sizes = {{kSphereLat, kSphereLon}};
    if (!o.quick) sizes.emplace_back(501, 1000);  // 1,000,000 triangles
    for (const auto& sz : sizes) {
        const Mesh m = uv_sphere(1.0, sz.first, sz.second);
        const int reps = m.size() > 100000 ? 3 : 10;
        double best = std::numeric_limits<double>::infinity();
        size_t reported = 0, heap = 0;
        for (int r = 0; r < reps; ++r) {
            const size_t h0 = heap_in_use();
            const auto t0 = Clock::now();
            pqp_model* model = build_ours(m);
            const auto t1 = Clock::now();
            heap = heap_in_use() - h0;
            reported = pqp_model_memory_usage(model);
            best = std::min(best, secs(t0, t1));
            pqp_model_destroy(model);
        }
        const double n = static_cast<double>(m.size());
        g_build.push_back({m.size(), "pqp-rs", best, static_cast<double>(reported) / n, static_cast<double>(heap) / n});
        if (!o.ours_only) {
            build_fcl_row<fcl::RSSd>(m, reps, "RSS");
            build_fcl_row<fcl::OBBRSSd>(m, reps, "OBBRSS");
            build_fcl_row<fcl::OBBd>(m, reps, "OBB");
        }
    }
}

struct ThreadRow {
    std::string lib;
    int threads;
    double qps;
    double cpu_us;  // CPU time per query, summed over the threads
};
std::vector<ThreadRow> g_threads;

double thread_cpu_secs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Queries per second over the pose list with `nt` threads, pose i going to thread i % nt: the best
// of `reps` runs of the whole list. Also the CPU time per query (the least over the runs): unlike
// the wall clock it does not depend on other processes leaving the cores free, so equal CPU time per
// query with 1 and with nt threads shows that the threads do not slow each other down.
// make_worker() returns the per-thread loop body.
template <class W>
std::pair<double, double> parallel_qps(size_t n, int nt, int reps, W&& make_worker) {
    double best = std::numeric_limits<double>::infinity();
    double best_cpu = std::numeric_limits<double>::infinity();
    for (int r = 0; r < reps; ++r) {
        std::vector<std::thread> pool;
        std::vector<double> cpu(static_cast<size_t>(nt), 0.0);
        const auto t0 = Clock::now();
        for (int t = 0; t < nt; ++t)
            pool.emplace_back([&, t] {
                auto work = make_worker();
                const double c0 = thread_cpu_secs();
                for (size_t i = static_cast<size_t>(t); i < n; i += static_cast<size_t>(nt)) work(i);
                cpu[static_cast<size_t>(t)] = thread_cpu_secs() - c0;
            });
        for (auto& th : pool) th.join();
        best = std::min(best, secs(t0, Clock::now()));
        double total = 0.0;
        for (double x : cpu) total += x;
        best_cpu = std::min(best_cpu, total);
    }
    return {static_cast<double>(n) / best, best_cpu / static_cast<double>(n)};
}

void workload_threads(const Options& o) {
    const Mesh sphere = uv_sphere(1.0, kSphereLat, kSphereLon);
    const auto sp = spheres_poses(o.quick ? 10 : 100);
    std::vector<std::pair<Pose, Pose>> poses;
    for (const auto& p : sp) poses.emplace_back(p.p1, p.p2);
    Case c("threads", sphere, sphere, poses, !o.ours_only);
    const int nt = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<int> rc{PQP_OK};
    // Each worker owns its result object (results are per thread; models are shared).
    auto ours_worker = [&]() {
        struct W {
            Case* c;
            std::atomic<int>* rc;
            std::shared_ptr<pqp_distance_result> r{pqp_distance_result_create(), pqp_distance_result_destroy};
            void operator()(size_t i) {
                const auto& p = c->poses[i];
                const int e = pqp_distance(r.get(), p.first.R.data(), p.first.T.data(), c->ours1.m, p.second.R.data(),
                                           p.second.T.data(), c->ours2.m, 0.0, 0.0, 2);
                if (e != PQP_OK) *rc = e;
            }
        };
        return W{&c, &rc, {pqp_distance_result_create(), pqp_distance_result_destroy}};
    };
    for (int t : {1, nt}) {
        const auto q = parallel_qps(c.size(), t, o.reps, ours_worker);
        g_threads.push_back({"pqp-rs", t, q.first, q.second * 1e6});
    }
    check(rc.load(), "pqp_distance (threads)");
    if (!o.ours_only) {
        auto fcl_worker = [&]() {
            struct W {
                Case* c;
                fcl::DistanceRequestd req{true};
                fcl::DistanceResultd res;
                void operator()(size_t i) {
                    res.clear();
                    fcl::distance(c->fcl1.rss.get(), c->tfs[i].first, c->fcl2.rss.get(), c->tfs[i].second, req, res);
                }
            };
            return W{&c, fcl::DistanceRequestd(true), fcl::DistanceResultd()};
        };
        for (int t : {1, nt}) {
            const auto q = parallel_qps(c.size(), t, o.reps, fcl_worker);
            g_threads.push_back({"FCL RSS", t, q.first, q.second * 1e6});
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Report

#if defined(PQP_BENCH_WITH_PQP13) || defined(PQP_BENCH_WITH_COAL)
// ---------------------------------------------------------------------------------------------
// PQP 1.3 and Coal 3 as peers (built from PQP 1.3's sources with -DPQP13_SOURCE_DIR, and against
// Coal's pip package with -DCOAL_PREFIX; see pqp13_peer.hpp, coal_peer.hpp). Ours and the peers run
// the same poses in alternating rounds (the order of the libraries rotates from round to round); a
// round times every query on its own and keeps the median over poses; the table gives the median
// over rounds. Answers are compared with ours in an untimed pass first (which also warms up).

struct PeerRow {
    std::string workload, query;
    size_t n = 0;
    double ours = NAN, pqp13 = NAN, coal = NAN;
    std::string agree13, agree_coal;
};
std::vector<PeerRow> g_peers;

#ifdef PQP_BENCH_WITH_PQP13
struct Peer13Model {
    pqp13::Model* m;
    explicit Peer13Model(const Mesh& mesh) : m(pqp13::build(mesh[0].data(), mesh.size())) {
        if (!m) die("PQP 1.3 refused a model");
    }
    Peer13Model(const Peer13Model&) = delete;
    Peer13Model& operator=(const Peer13Model&) = delete;
    ~Peer13Model() { pqp13::destroy(m); }
};

struct Peer13Results {
    pqp13::Results* r = pqp13::results_create();
    Peer13Results() = default;
    Peer13Results(const Peer13Results&) = delete;
    Peer13Results& operator=(const Peer13Results&) = delete;
    ~Peer13Results() { pqp13::results_destroy(r); }
};
#endif

#ifdef PQP_BENCH_WITH_COAL
struct CoalModel {
    coalpeer::Model* m;
    explicit CoalModel(const Mesh& mesh) : m(coalpeer::build(mesh[0].data(), mesh.size())) {}
    CoalModel(const CoalModel&) = delete;
    CoalModel& operator=(const CoalModel&) = delete;
    ~CoalModel() { coalpeer::destroy(m); }
};
#endif

// One pair of meshes with poses, built by every library.
struct PeerCase {
    std::string name;
    const Mesh* mesh1;
    const Mesh* mesh2;
    std::vector<std::pair<Pose, Pose>> poses;
    OurModel ours1, ours2;
#ifdef PQP_BENCH_WITH_PQP13
    Peer13Model peer1, peer2;
#endif
#ifdef PQP_BENCH_WITH_COAL
    CoalModel coal1, coal2;
#endif
    PeerCase(std::string n, const Mesh& a, const Mesh& b, std::vector<std::pair<Pose, Pose>> p)
        : name(std::move(n)), mesh1(&a), mesh2(&b), poses(std::move(p)), ours1(a), ours2(b)
#ifdef PQP_BENCH_WITH_PQP13
          , peer1(a), peer2(b)
#endif
#ifdef PQP_BENCH_WITH_COAL
          , coal1(a), coal2(b)
#endif
    {}
    size_t size() const { return poses.size(); }
};

int peer_rounds(const Options& o) { return std::max(3, o.reps); }

// One round: query(i) for every pose, each timed alone; the median over poses.
double round_median(size_t n, const std::function<void(size_t)>& query) {
    std::vector<double> t(n);
    for (size_t i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        query(i);
        t[i] = secs(t0, Clock::now());
    }
    return median(t);
}

// The libraries of a row: ours first, then the peers built in.
enum Side { kOurs, kPqp13, kCoal };
struct Timed {
    Side side;
    std::function<void(size_t)> query;
};

// Alternating rounds (round r starts with library r mod k); each library's median over rounds.
// At least `rounds` rounds, and more (up to 5 times as many) until every library has been timed
// for a second in all: on a shared machine a burst of load spoils a short round, and a row whose
// rounds take a tenth of a second (the nested shells with rel_err, the bunny's queries) otherwise
// rests on three of them.
std::map<Side, double> alternate(size_t n, int rounds, const std::vector<Timed>& libs) {
    std::map<Side, std::vector<double>> t;
    std::map<Side, double> spent;
    const size_t k = libs.size();
    auto least_spent = [&] {
        double m = 1e300;
        for (const Timed& lib : libs) m = std::min(m, spent[lib.side]);
        return m;
    };
    for (int r = 0; r < rounds || (r < 5 * rounds && least_spent() < 1.0); ++r)
        for (size_t j = 0; j < k; ++j) {
            const Timed& lib = libs[(static_cast<size_t>(r) + j) % k];
            const auto t0 = Clock::now();
            t[lib.side].push_back(round_median(n, lib.query));
            spent[lib.side] += secs(t0, Clock::now());
        }
    std::map<Side, double> out;
    for (const auto& e : t) out[e.first] = median(e.second);
    return out;
}

void add_peer_row(const std::string& workload, const std::string& query, size_t n,
                  const std::map<Side, double>& t, const std::string& agree13, const std::string& agree_coal) {
    PeerRow row;
    row.workload = workload;
    row.query = query;
    row.n = n;
    row.ours = t.at(kOurs);
    if (t.count(kPqp13)) row.pqp13 = t.at(kPqp13);
    if (t.count(kCoal)) row.coal = t.at(kCoal);
    row.agree13 = agree13;
    row.agree_coal = agree_coal;
    g_peers.push_back(row);
}

// A peer's distances against ours (untimed), compared.
std::string compare_peer_distances(const std::vector<double>& ours, const std::vector<double>& peer) {
    int differ = 0, ours_lower = 0;
    double worst = 0;
    for (size_t i = 0; i < ours.size(); ++i)
        if (!same_distance(ours[i], peer[i])) {
            ++differ;
            ours_lower += ours[i] < peer[i];
            worst = std::max(worst, std::fabs(ours[i] - peer[i]));
        }
    if (differ == 0) return "same distances";
    // Each reports the distance of a triangle pair it found, so the lower one is the better answer.
    return fmt("%d poses differ (max |d| difference %.3g; ours lower on %d)", differ, worst, ours_lower);
}

// Approximate distances against the exact ones (ours, rel_err 0).
std::string check_bound(const std::vector<double>& d, const std::vector<double>& truth, double rel_err) {
    int bad = 0;
    for (size_t i = 0; i < d.size(); ++i)
        bad += !(d[i] >= truth[i] * (1 - 1e-12) - 1e-12 && d[i] <= truth[i] * (1 + rel_err) * (1 + 1e-12) + 1e-12);
    return bad ? fmt("bound broken on %d poses", bad) : "within the bound";
}

void peer_distance(PeerCase& c, const std::string& workload, const Options& o, double rel_err, const char* query) {
    const size_t n = c.size();
    const bool exact = rel_err == 0.0;
    const double abs_err = exact ? 0.0 : 1e300;
    pqp_distance_result* r = pqp_distance_result_create();
    auto ours_q = [&](size_t i, double rel, double abs) {
        const auto& p = c.poses[i];
        check(pqp_distance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(), p.second.T.data(),
                           c.ours2.m, rel, abs, 2),
              "pqp_distance");
        return pqp_distance_result_distance(r);
    };
    std::vector<double> ours(n), truth(n);
    for (size_t i = 0; i < n; ++i) {
        ours[i] = ours_q(i, rel_err, abs_err);
        truth[i] = exact ? ours[i] : ours_q(i, 0.0, 0.0);
    }
    std::vector<Timed> libs{{kOurs, [&](size_t i) { ours_q(i, rel_err, abs_err); }}};
    std::string agree13 = "-", agree_coal = "-";
#ifdef PQP_BENCH_WITH_PQP13
    Peer13Results pr;
    auto peer_q = [&](size_t i) {
        const auto& p = c.poses[i];
        return pqp13::distance(pr.r, p.first.R.data(), p.first.T.data(), c.peer1.m, p.second.R.data(),
                               p.second.T.data(), c.peer2.m, rel_err, abs_err, 2);
    };
    std::vector<double> d13(n);
    for (size_t i = 0; i < n; ++i) d13[i] = peer_q(i);
    agree13 = exact ? compare_peer_distances(ours, d13) : check_bound(d13, truth, rel_err);
    libs.push_back({kPqp13, [&](size_t i) { peer_q(i); }});
#endif
#ifdef PQP_BENCH_WITH_COAL
    auto coal_q = [&](size_t i) {
        const auto& p = c.poses[i];
        return coalpeer::distance(p.first.R.data(), p.first.T.data(), c.coal1.m, p.second.R.data(), p.second.T.data(),
                                  c.coal2.m, rel_err, exact ? 0.0 : 1e300);
    };
    std::vector<double> dc(n);
    for (size_t i = 0; i < n; ++i) dc[i] = std::max(0.0, coal_q(i));  // Coal signs penetration
    agree_coal = exact ? compare_peer_distances(ours, dc) : check_bound(dc, truth, rel_err);
    libs.push_back({kCoal, [&](size_t i) { coal_q(i); }});
#endif
    if (!exact) {
        const std::string b = check_bound(ours, truth, rel_err);
        if (b != "within the bound") g_notes.push_back(workload + "/" + query + ": ours " + b);
    }
    const auto t = alternate(n, peer_rounds(o), libs);
    pqp_distance_result_destroy(r);
    add_peer_row(workload, query, n, t, agree13, agree_coal);
}

void peer_tolerance(PeerCase& c, const std::string& workload, const Options& o, double tol) {
    const size_t n = c.size();
    pqp_tolerance_result* r = pqp_tolerance_result_create();
    auto ours_q = [&](size_t i) {
        const auto& p = c.poses[i];
        check(pqp_tolerance(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(), p.second.T.data(),
                            c.ours2.m, tol, 2),
              "pqp_tolerance");
        return pqp_tolerance_result_closer_than_tolerance(r);
    };
    std::vector<int> ours(n);
    int closer = 0;
    for (size_t i = 0; i < n; ++i) closer += ours[i] = ours_q(i);
    auto flags = [&](const std::vector<int>& f) {
        int differ = 0;
        for (size_t i = 0; i < n; ++i) differ += f[i] != ours[i];
        return differ ? fmt("%d flags differ", differ) : fmt("same flags (%d closer)", closer);
    };
    std::vector<Timed> libs{{kOurs, [&](size_t i) { ours_q(i); }}};
    std::string agree13 = "-", agree_coal = "-";
#ifdef PQP_BENCH_WITH_PQP13
    Peer13Results pr;
    auto peer_q = [&](size_t i) {
        const auto& p = c.poses[i];
        return pqp13::tolerance(pr.r, p.first.R.data(), p.first.T.data(), c.peer1.m, p.second.R.data(),
                                p.second.T.data(), c.peer2.m, tol, 2);
    };
    std::vector<int> f13(n);
    for (size_t i = 0; i < n; ++i) f13[i] = peer_q(i);
    agree13 = flags(f13);
    libs.push_back({kPqp13, [&](size_t i) { peer_q(i); }});
#endif
#ifdef PQP_BENCH_WITH_COAL
    // Coal has no tolerance query: an exact distance query, then d <= tol (as for FCL).
    auto coal_q = [&](size_t i) {
        const auto& p = c.poses[i];
        return coalpeer::distance(p.first.R.data(), p.first.T.data(), c.coal1.m, p.second.R.data(), p.second.T.data(),
                                  c.coal2.m, 0.0, 0.0) <= tol
                   ? 1
                   : 0;
    };
    std::vector<int> fc(n);
    for (size_t i = 0; i < n; ++i) fc[i] = coal_q(i);
    agree_coal = flags(fc) + " (exact distance, then d <= t)";
    libs.push_back({kCoal, [&](size_t i) { coal_q(i); }});
#endif
    const auto t = alternate(n, peer_rounds(o), libs);
    pqp_tolerance_result_destroy(r);
    add_peer_row(workload, fmt("tolerance %g", tol), n, t, agree13, agree_coal);
}

void peer_collide(PeerCase& c, const std::string& workload, const Options& o, bool all) {
    const size_t n = c.size();
    const int flag = all ? PQP_ALL_CONTACTS : PQP_FIRST_CONTACT;
    pqp_collide_result* r = pqp_collide_result_create();
    auto ours_q = [&](size_t i) {
        const auto& p = c.poses[i];
        check(pqp_collide(r, p.first.R.data(), p.first.T.data(), c.ours1.m, p.second.R.data(), p.second.T.data(),
                          c.ours2.m, flag),
              "pqp_collide");
    };
    std::vector<PairList> ours(n);
    int colliding = 0;
    size_t total = 0;
    for (size_t i = 0; i < n; ++i) {
        ours_q(i);
        const pqp_contact_pair* pairs = pqp_collide_result_pairs(r);
        for (int k = 0; k < pqp_collide_result_num_pairs(r); ++k) ours[i].emplace_back(pairs[k].id1, pairs[k].id2);
        std::sort(ours[i].begin(), ours[i].end());
        colliding += !ours[i].empty();
        total += ours[i].size();
    }
    // A peer's pairs against ours: all contacts, the same sets; first contact, the same verdicts.
    // Pairs one side reports and the other does not (first contact: every pair) are refereed by
    // brute force.
    auto compare = [&](const std::vector<PairList>& peer) {
        int differ = 0, ours_wrong = 0, peer_wrong = 0;
        for (size_t i = 0; i < n; ++i) {
            const PairList& a = ours[i];
            const PairList& b = peer[i];
            const bool same = all ? a == b : a.empty() == b.empty();
            differ += !same;
            if (same && all) continue;
            const auto& p = c.poses[i];
            auto touching = [&](const std::pair<int, int>& q) {
                return brute::pair_distance(*c.mesh1, p.first, q.first, *c.mesh2, p.second, q.second) <= 1e-12;
            };
            for (const auto& q : a)
                if ((!all || !std::binary_search(b.begin(), b.end(), q)) && !touching(q)) ++ours_wrong;
            for (const auto& q : b)
                if ((!all || !std::binary_search(a.begin(), a.end(), q)) && !touching(q)) ++peer_wrong;
        }
        std::string s = differ ? fmt("%d poses differ", differ) : (all ? "same pairs" : "same verdicts");
        if (ours_wrong || peer_wrong) s += fmt("; pairs apart by brute force: ours %d, peer %d", ours_wrong, peer_wrong);
        return s + (all ? fmt(" (%d colliding, %zu pairs)", colliding, total) : fmt(" (%d colliding)", colliding));
    };
    std::vector<Timed> libs{{kOurs, ours_q}};
    std::string agree13 = "-", agree_coal = "-";
#ifdef PQP_BENCH_WITH_PQP13
    Peer13Results pr;
    auto peer_q = [&](size_t i) {
        const auto& p = c.poses[i];
        pqp13::collide(pr.r, p.first.R.data(), p.first.T.data(), c.peer1.m, p.second.R.data(), p.second.T.data(),
                       c.peer2.m, all);
    };
    std::vector<PairList> p13(n);
    for (size_t i = 0; i < n; ++i) {
        peer_q(i);
        p13[i] = pqp13::pairs(pr.r);
        std::sort(p13[i].begin(), p13[i].end());
    }
    agree13 = compare(p13);
    libs.push_back({kPqp13, peer_q});
#endif
#ifdef PQP_BENCH_WITH_COAL
    std::vector<PairList> pc(n);
    for (size_t i = 0; i < n; ++i) {
        const auto& p = c.poses[i];
        pc[i] = coalpeer::collide(p.first.R.data(), p.first.T.data(), c.coal1.m, p.second.R.data(), p.second.T.data(),
                                  c.coal2.m, all);
        std::sort(pc[i].begin(), pc[i].end());
    }
    agree_coal = compare(pc);
    libs.push_back({kCoal, [&](size_t i) {
                        const auto& p = c.poses[i];
                        coalpeer::collide_count(p.first.R.data(), p.first.T.data(), c.coal1.m, p.second.R.data(),
                                                p.second.T.data(), c.coal2.m, all);
                    }});
#endif
    const auto t = alternate(n, peer_rounds(o), libs);
    pqp_collide_result_destroy(r);
    add_peer_row(workload, all ? "collide all" : "collide first", n, t, agree13, agree_coal);
}

// Builds: the order of the libraries rotates from round to round; each one's median build time.
void peer_build(const Mesh& m, int rounds) {
    std::vector<Timed> libs{{kOurs, [&](size_t) { pqp_model_destroy(build_ours(m)); }}};
    std::string agree13 = "-", agree_coal = "-";
    const double n = static_cast<double>(m.size());
    {
        pqp_model* model = build_ours(m);
        agree13 = agree_coal = fmt("bytes/tri: ours %.0f", static_cast<double>(pqp_model_memory_usage(model)) / n);
        pqp_model_destroy(model);
    }
#ifdef PQP_BENCH_WITH_PQP13
    {
        pqp13::Model* model = pqp13::build(m[0].data(), m.size());
        if (!model) die("PQP 1.3 refused a model");
        agree13 += fmt(", PQP 1.3 %.0f (its MemUsage)", pqp13::memory_usage(model) / n);
        pqp13::destroy(model);
    }
    libs.push_back({kPqp13, [&](size_t) { pqp13::destroy(pqp13::build(m[0].data(), m.size())); }});
#endif
#ifdef PQP_BENCH_WITH_COAL
    libs.push_back({kCoal, [&](size_t) { coalpeer::destroy(coalpeer::build(m[0].data(), m.size())); }});
#endif
    // A build is timed with its model's destruction (untimed would need the model kept: 1M
    // triangles each); destruction is a small part of a build.
    const auto t = alternate(1, rounds, libs);
    add_peer_row("build", fmt("%zu triangles", m.size()), 1, t, agree13, agree_coal);
}

// Build speed (issue 21): ours on one thread and on every core (pqp_model_end_threads, 0), PQP 1.3
// beside them when built in, in alternating rounds; each one's median build time, the model's
// destruction included, as peer_build. `--threads N` sets the threaded build's count (default 0,
// every core). Built with -DPQP_BENCH_OLD_LIBRARY (a library from before pqp_model_end_threads),
// the threaded column is left out: for before/after runs.
pqp_model* build_ours_threads(const Mesh& mesh, unsigned threads) {
    pqp_model* m = pqp_model_create();
    if (!m) die("pqp_model_create failed");
    check(pqp_model_begin(m, static_cast<int>(mesh.size())), "pqp_model_begin");
    for (size_t i = 0; i < mesh.size(); ++i)
        check(pqp_model_add_tri(m, &mesh[i][0], &mesh[i][3], &mesh[i][6], static_cast<int>(i)),
              "pqp_model_add_tri");
#ifdef PQP_BENCH_OLD_LIBRARY
    (void)threads;
    check(pqp_model_end(m), "pqp_model_end");
#else
    check(pqp_model_end_threads(m, threads), "pqp_model_end_threads");
#endif
    return m;
}

void workload_peer_builds(const Options& o) {
    const unsigned threads = o.threads > 0 ? static_cast<unsigned>(o.threads) : 0u;
    std::printf("\n## Build speed (ms per build, median of alternating rounds; threaded: %u = %s)\n\n"
                "| triangles | rounds | ours, 1 thread | ours, threaded | PQP 1.3 | PQP 1.3 / ours 1 thread | "
                "PQP 1.3 / ours threaded | 1 thread / threaded |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n",
                threads, threads == 0 ? "every core" : "threads");
    struct Size {
        int lat, lon, rounds;
    };
    for (const Size sz : {Size{kSphereLat, kSphereLon, 9}, Size{501, 1000, 5}}) {
        if (o.quick && sz.lat > kSphereLat) continue;
        const Mesh m = uv_sphere(1.0, sz.lat, sz.lon);
        const int rounds = std::max(o.reps, sz.rounds);
        std::vector<double> one, many, peer;
        for (int r = 0; r < rounds; ++r) {
            std::vector<std::function<void()>> libs{
                [&] {
                    const auto t0 = Clock::now();
                    pqp_model_destroy(build_ours_threads(m, 1));
                    one.push_back(secs(t0, Clock::now()));
                },
#ifndef PQP_BENCH_OLD_LIBRARY
                [&] {
                    const auto t0 = Clock::now();
                    pqp_model_destroy(build_ours_threads(m, threads));
                    many.push_back(secs(t0, Clock::now()));
                },
#endif
#ifdef PQP_BENCH_WITH_PQP13
                [&] {
                    const auto t0 = Clock::now();
                    pqp13::destroy(pqp13::build(m[0].data(), m.size()));
                    peer.push_back(secs(t0, Clock::now()));
                },
#endif
            };
            for (size_t j = 0; j < libs.size(); ++j) libs[(static_cast<size_t>(r) + j) % libs.size()]();
        }
        auto ms = [](std::vector<double> v) { return v.empty() ? 0.0 : 1e3 * median(v); };
        auto ratio = [](double a, double b) { return a > 0 && b > 0 ? fmt("%.2f", a / b) : std::string("-"); };
        const double a = ms(one), b = ms(many), c = ms(peer);
        std::printf("| %zu | %d | %.2f | %s | %s | %s | %s | %s |\n", m.size(), rounds, a,
                    b > 0 ? fmt("%.2f", b).c_str() : "-", c > 0 ? fmt("%.2f", c).c_str() : "-",
                    ratio(c, a).c_str(), ratio(c, b).c_str(), ratio(a, b).c_str());
        std::fflush(stdout);
    }
}

void workload_peers(const Options& o) {
    {
        const Mesh sphere = uv_sphere(1.0, kSphereLat, kSphereLon);
        const auto sp = spheres_poses(o.quick ? 10 : 100);
        std::vector<std::pair<Pose, Pose>> poses;
        for (const auto& p : sp) poses.emplace_back(p.p1, p.p2);
        PeerCase c("spheres", sphere, sphere, poses);
        peer_distance(c, "1 spheres-distance", o, 0.0, "distance");
    }
    {
        // Shells: a query takes a large fraction of a second; the first 10 of workload 2's poses.
        const Mesh inner = uv_sphere(1.0, kSphereLat, kSphereLon);
        const Mesh outer = uv_sphere(1.05, kSphereLat, kSphereLon);
        Rng rng(2);
        std::vector<std::pair<Pose, Pose>> poses;
        const Pose id{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};
        for (int k = 0; k < (o.quick ? 2 : 10); ++k) poses.emplace_back(id, Pose{random_rotation(rng), {0, 0, 0}});
        PeerCase c("shells", inner, outer, poses);
        peer_distance(c, "2 shells", o, 0.0, "distance exact");
        peer_distance(c, "2 shells", o, 0.1, "distance rel_err 0.1");
    }
    {
        const Mesh bunny = load_tris(o.models + "/bunny.tris");
        const Mesh torus = load_tris(o.models + "/torus.tris");
        const double radius = 0.5 * bounds(bunny).size();
        const int n = o.quick ? 200 : 1000;
        for (int which = 0; which < 2; ++which) {
            const Mesh& other = which == 0 ? bunny : torus;
            const std::string name = which == 0 ? "bunny-bunny" : "bunny-torus";
            PeerCase c(name, bunny, other, bunny_poses(bunny, other, 0.5 * o.cube * radius, n));
            peer_collide(c, "3 " + name, o, true);
            peer_collide(c, "3 " + name, o, false);
            peer_distance(c, "4 " + name, o, 0.0, "distance");
            peer_distance(c, "4 " + name, o, 0.05, "distance rel_err 0.05");
            peer_tolerance(c, "4 " + name, o, 0.05);
        }
    }
    {
        // Coherent motion: each library keeps what speeds up the next query of the path (ours in
        // the reused result object, PQP 1.3 in the models' last_tri; Coal keeps nothing).
        const Mesh t1 = load_tris(o.models + "/torus1.tris");
        const Mesh t2 = load_tris(o.models + "/torus2.tris");
        const auto p1 = load_path(o.models + "/torus1.path");
        const auto p2 = load_path(o.models + "/torus2.path");
        std::vector<std::pair<Pose, Pose>> poses;
        const size_t n = o.quick ? std::min<size_t>(300, p1.size()) : std::min(p1.size(), p2.size());
        for (size_t k = 0; k < n; ++k) poses.emplace_back(p1[k], p2[k]);
        PeerCase c("coherent", t1, t2, poses);
        peer_distance(c, "5 coherent", o, 0.0, "distance, result reused");
    }
    peer_build(uv_sphere(1.0, kSphereLat, kSphereLon), std::max(5, peer_rounds(o)));
    if (!o.quick) peer_build(uv_sphere(1.0, 501, 1000), peer_rounds(o));
}
#endif

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

void report_queries();
void report_rest(const Options& o);

void report(const Options& o) {
    if (!g_rows.empty()) report_queries();
    report_rest(o);
}

void report_queries() {
    std::printf("\n## Queries (median microseconds per query; FCL column is FCL's fastest BV type)\n\n");
    std::printf("| workload | query | poses | ours (us) | FCL (us) | FCL BV | FCL/ours | ours BV tests/q | ours tri "
                "tests/q | checksum ours | checksum FCL | agree |\n");
    std::printf("|---|---|---:|---:|---:|---|---:|---:|---:|---|---|---|\n");
    for (const auto& r : g_rows) {
        std::printf("| %s | %s | %zu | %s | %s | %s | %s | %.0f | %.0f | %s | %s | %s |\n", r.workload.c_str(),
                    r.query.c_str(), r.n, us(r.ours_med).c_str(), std::isnan(r.fcl_med) ? "-" : us(r.fcl_med).c_str(),
                    r.fcl_variant.c_str(), std::isnan(r.fcl_med) ? "-" : fmt("%.2f", r.fcl_med / r.ours_med).c_str(),
                    r.bv, r.tri, r.ours_ck.c_str(), r.fcl_ck.c_str(), r.agree.c_str());
    }
    std::printf("\nMeans (us per query): ");
    for (const auto& r : g_rows)
        std::printf("%s/%s ours %s FCL %s; ", r.workload.c_str(), r.query.c_str(), us(r.ours_mean).c_str(),
                    std::isnan(r.fcl_mean) ? "-" : us(r.fcl_mean).c_str());
    std::printf("\n");
    for (const auto& r : g_rows)
        if (!r.note.empty()) std::printf("\nNote (%s / %s): %s", r.workload.c_str(), r.query.c_str(), r.note.c_str());
    std::printf("\n");
}

void report_rest(const Options& o) {
    if (!g_variants.empty()) {
        std::printf("\n## Every FCL BV type\n\n| workload | query | FCL BV | median (us) | mean (us) | FCL BV tests/q | "
                    "FCL tri tests/q | checksum | agrees with ours |\n|---|---|---|---:|---:|---:|---:|---|---|\n");
        auto num = [](double x) { return std::isnan(x) ? std::string("-") : fmt("%.0f", x); };
        for (const auto& v : g_variants)
            std::printf("| %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", v.workload.c_str(), v.query.c_str(),
                        v.variant.c_str(), us(v.med).c_str(), us(v.mean_).c_str(), num(v.bv).c_str(),
                        num(v.tri).c_str(), v.ck.c_str(), v.agree.c_str());
    }
    if (!g_build.empty()) {
        std::printf("\n## Build\n\n| triangles | library | build (ms) | bytes/tri (reported/estimated) | bytes/tri "
                    "(heap delta) |\n|---:|---|---:|---:|---:|\n");
        for (const auto& b : g_build)
            std::printf("| %zu | %s | %.1f | %.1f | %.1f |\n", b.tris, b.lib.c_str(), b.secs * 1e3,
                        b.bytes_per_tri_reported, b.bytes_per_tri_heap);
    }
    if (!g_threads.empty()) {
        std::printf("\n## Threads (workload 1, exact distance)\n\n| library | threads | queries/s | speed-up | CPU us/query "
                    "| CPU time ratio to 1 thread |\n|---|---:|---:|---:|---:|---:|\n");
        for (const auto& t : g_threads) {
            double base = NAN, base_cpu = NAN;
            for (const auto& u : g_threads)
                if (u.lib == t.lib && u.threads == 1) base = u.qps, base_cpu = u.cpu_us;
            std::printf("| %s | %d | %.0f | %.2f | %.1f | %.3f |\n", t.lib.c_str(), t.threads, t.qps, t.qps / base,
                        t.cpu_us, t.cpu_us / base_cpu);
        }
        std::printf("\nload average at the end of the threads workload: %s\n", load_average().c_str());
    }
    if (!g_strategies.empty()) {
        std::printf("\n## Search strategies (ours, exact distance, one result object along the poses)\n\n"
                    "| workload | strategy | poses | median (us) | mean (us) | BV tests/q | tri tests/q | sum d |\n"
                    "|---|---|---:|---:|---:|---:|---:|---|\n");
        for (const auto& r : g_strategies)
            std::printf("| %s | %s | %zu | %.2f | %.2f | %.0f | %.1f | %.12f |\n", r.workload.c_str(),
                        r.strategy.c_str(), r.poses, r.med * 1e6, r.mean_ * 1e6, r.bv, r.tri, r.sum);
    }
#if defined(PQP_BENCH_WITH_PQP13) || defined(PQP_BENCH_WITH_COAL)
    if (!g_peers.empty()) {
        std::printf("\n## Against PQP 1.3 and Coal (median over %d or more alternating rounds, until each library has run 1 s, of the median us per query; "
                    "builds in ms; - where a peer is not built in)\n\n| workload | query | poses | ours | PQP 1.3 | "
                    "PQP 1.3/ours | Coal | Coal/ours | answers of PQP 1.3 | answers of Coal |\n"
                    "|---|---|---:|---:|---:|---:|---:|---:|---|---|\n",
                    peer_rounds(o));
        auto num = [](double x, double scale) { return std::isnan(x) ? std::string("-") : fmt("%.2f", x * scale); };
        for (const auto& r : g_peers) {
            const double scale = r.workload == "build" ? 1e3 : 1e6;
            std::printf("| %s | %s | %zu | %.2f | %s | %s | %s | %s | %s | %s |\n", r.workload.c_str(), r.query.c_str(),
                        r.n, r.ours * scale, num(r.pqp13, scale).c_str(), num(r.pqp13 / r.ours, 1).c_str(),
                        num(r.coal, scale).c_str(), num(r.coal / r.ours, 1).c_str(), r.agree13.c_str(),
                        r.agree_coal.c_str());
        }
    }
#endif
    if (!g_notes.empty()) {
        std::printf("\n## Notes and disagreements\n\n");
        for (const auto& n : g_notes) std::printf("- %s\n", n.c_str());
    }
    std::printf("\nreps = %d%s%s; hardware threads = %u; pqp-rs %s; FCL %s\n", o.reps, o.quick ? ", quick" : "",
                o.ours_only ? ", ours only" : "", std::thread::hardware_concurrency(), pqp_version(), FCL_VERSION);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) die("missing value after " + a);
            return argv[++i];
        };
        if (a == "--models") {
            o.models = value();
        } else if (a == "--only") {
            std::stringstream ss(value());
            std::string w;
            while (std::getline(ss, w, ',')) o.only.insert(w);
        } else if (a == "--reps") {
            o.reps = std::max(1, std::atoi(value().c_str()));
        } else if (a == "--threads") {
            o.threads = std::atoi(value().c_str());
        } else if (a == "--fcl-rss-collide") {
            o.fcl_rss_collide = true;
        } else if (a == "--cube") {
            o.cube = std::atof(value().c_str());
        } else if (a == "--quick") {
            o.quick = true;
        } else if (a == "--ours-only") {
            o.ours_only = true;
        } else if (a == "--no-verify") {
            o.verify = false;
        } else {
            die("unknown option " + a +
                " (see the comment at the top of bench/pqp_bench.cpp; workloads: spheres shells bunny-collide "
                "bunny-distance coherent build threads strategies peers build-speed)");
        }
    }
    return o;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    g_opt = &o;
    auto stage = [](const char* s) {
        std::fprintf(stderr, "[%s]\n", s);
        std::fflush(stderr);
    };
    if (o.want("spheres")) stage("spheres"), workload_spheres(o);
    if (o.want("shells")) stage("shells"), workload_shells(o);
    if (o.want("bunny-collide") || o.want("bunny-distance")) {
        stage("bunny");
        workload_bunny(o, o.want("bunny-collide"), o.want("bunny-distance"));
    }
    if (o.want("coherent")) stage("coherent"), workload_coherent(o);
    if (o.want("build")) stage("build"), workload_build(o);
    if (o.want("threads")) stage("threads"), workload_threads(o);
    if (o.want("strategies")) stage("strategies"), workload_strategies(o);
#if defined(PQP_BENCH_WITH_PQP13) || defined(PQP_BENCH_WITH_COAL)
    if (o.only.count("build-speed")) stage("build-speed"), workload_peer_builds(o);
    if (o.want("peers")) stage("peers"), workload_peers(o);
#endif
    report(o);
    // As in die(): FCL's and Coal's static objects must not be destroyed (twice) at exit.
    std::fflush(stdout);
    std::fflush(stderr);
    std::_Exit(0);
}
