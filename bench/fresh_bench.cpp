// Fresh results and root-only calls against PQP 1.3, in the patterns legacy PQP programs use (a
// benchmark, run by hand; never a test).
//
// Patterns, each on poses drawn at random (fixed seed) from a family, bunny (model 1, at the
// identity) against torus (model 2, a random rotation, pushed along a random direction until the
// distance is a random gap):
//   distance, fresh result per call: touching (overlapping by up to 5% of the bunny's size), near
//     contact (gap 0.1-5%) and far apart (gap 50-200%); pqp-rs through the C ABI (create, query, destroy) and PQP.h (a
//     PQP_DistanceResult declared inside the calling function), PQP 1.3 likewise;
//   distance, reused result (the C ABI; the same pose again, so its front applies), for reference;
//   approximate distance (rel_err 0.1, abs_err infinite), fresh results, near and far;
//   root-only calls (gap 150-400%: the root volumes apart): collide first contact and tolerance
//     (1e-3 to 1e-1 of the size), fresh results, C ABI and PQP.h.
// Each pose is timed alone (a batch of repeated calls sized to about 20 us), ours and PQP 1.3
// alternating which goes first; per pose the ratio PQP 1.3 time / ours (above 1: we are faster).
// Printed per pattern: median and 10th percentile of the ratios, and median times. Every answer
// is checked against PQP 1.3's (distances within 1e-9 relative, verdicts equal).
//
// cargo build --release && cmake -S bench -B build-bench -DPQP13_SOURCE_DIR=<PQP 1.3 src> &&
// cmake --build build-bench --target fresh_bench && build-bench/fresh_bench [rounds] [poses]
#include <pqp/pqp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "fresh_cxx.hpp"
#include "pqp13_peer.hpp"
#include "workloads.hpp"

using bench::Mesh;
using bench::Pose;
using bench::Rng;

namespace {

Mesh load(const std::string& path) {
    std::ifstream in(path);
    std::size_t n = 0;
    in >> n;
    Mesh m(n);
    for (auto& t : m)
        for (double& x : t) in >> x;
    if (!in) {
        std::fprintf(stderr, "cannot read %s\n", path.c_str());
        std::exit(1);
    }
    return m;
}

double size_of(const Mesh& m) {
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
    for (const auto& t : m)
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], t[3 * v + k]);
                hi[k] = std::max(hi[k], t[3 * v + k]);
            }
    return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

pqp_model* build_ours(const Mesh& m) {
    pqp_model* p = pqp_model_create();
    pqp_model_begin(p, static_cast<int>(m.size()));
    for (std::size_t k = 0; k < m.size(); ++k)
        pqp_model_add_tri(p, &m[k][0], &m[k][3], &m[k][6], static_cast<int>(k));
    if (pqp_model_end(p) != PQP_OK) std::exit(1);
    return p;
}

const double kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
const double kZero[3] = {0, 0, 0};

// A family: torus poses whose distance to the bunny is a gap drawn in [lo, hi] times the size.
std::vector<Pose> family(pqp_model* a, pqp_model* b, double size, double lo, double hi, int n,
                         uint64_t seed) {
    Rng rng(seed);
    std::vector<Pose> out;
    pqp_distance_result* r = pqp_distance_result_create();
    while (static_cast<int>(out.size()) < n) {
        Pose p;
        p.R = bench::random_rotation(rng);
        const auto u = bench::random_direction(rng);
        // hi = 0: touching, then pushed in by up to 5% of the size (overlapping).
        const double depth = hi == 0 ? size * 0.05 * rng.uniform() : 0.0;
        const double gap = size * (lo + (hi - lo) * rng.uniform());
        // The distance falls by at most the step along u: stepping by (d - gap) never overshoots.
        double s = 4.0 * size + gap;
        double d = 0;
        for (int it = 0; it < 60; ++it) {
            p.T = {u[0] * s, u[1] * s, u[2] * s};
            pqp_distance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, 0, 0, 2);
            d = pqp_distance_result_distance(r);
            if (d - gap <= 1e-3 * gap) break;
            s -= d - gap;
        }
        if (hi == 0) {
            s -= depth;
            p.T = {u[0] * s, u[1] * s, u[2] * s};
            pqp_distance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, 0, 0, 2);
            if (pqp_distance_result_distance(r) == 0) out.push_back(p);
        } else if (std::fabs(d - gap) <= 1e-2 * gap) {
            out.push_back(p);
        }
    }
    pqp_distance_result_destroy(r);
    return out;
}

double now_us() {
    using namespace std::chrono;
    return duration<double, std::micro>(steady_clock::now().time_since_epoch()).count();
}

// Time of one call in us: the median of 3 batches of reps calls.
double time_call(const std::function<void()>& f, int reps) {
    double best[3];
    for (double& b : best) {
        const double t0 = now_us();
        for (int k = 0; k < reps; ++k) f();
        b = (now_us() - t0) / reps;
    }
    std::sort(best, best + 3);
    return best[1];
}

int reps_for(const std::function<void()>& f) {
    const double t0 = now_us();
    f();
    const double t = std::max(now_us() - t0, 0.05);
    return std::max(1, std::min(2000, static_cast<int>(20.0 / t)));
}

double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * (v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    const double f = pos - i;
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

struct Stat {
    std::vector<double> ratio, ours, peer;
};

// One pattern over its poses: ours(pose) and peer(pose) answer; they must agree.
// `tol`: how far the answers may differ, relative (0: the same bits).
void run(const char* name, const std::vector<Pose>& poses, Stat& st,
         const std::function<double(const Pose&)>& ours,
         const std::function<double(const Pose&)>& peer, double tol) {
    for (std::size_t i = 0; i < poses.size(); ++i) {
        const Pose& p = poses[i];
        const double a = ours(p), b = peer(p);
        const bool same = tol == 0 ? a == b : std::fabs(a - b) <= tol * std::max(1.0, std::fabs(b));
        if (!same) {
            std::fprintf(stderr, "%s pose %zu: ours %.17g, PQP 1.3 %.17g\n", name, i, a, b);
            std::exit(2);
        }
        std::function<void()> fo = [&] { ours(p); };
        std::function<void()> fp = [&] { peer(p); };
        const int ro = reps_for(fo), rp = reps_for(fp);
        double to, tp;
        if (i % 2 == 0) {
            to = time_call(fo, ro);
            tp = time_call(fp, rp);
        } else {
            tp = time_call(fp, rp);
            to = time_call(fo, ro);
        }
        st.ratio.push_back(tp / to);
        st.ours.push_back(to);
        st.peer.push_back(tp);
    }
}

}  // namespace

int main(int argc, char** argv) {
    const int rounds = argc > 1 ? std::atoi(argv[1]) : 3;
    const int n = argc > 2 ? std::atoi(argv[2]) : 100;
    const std::string dir = PQP_BENCH_MODELS_DIR;
    const Mesh bunny = load(dir + "/bunny.tris"), torus = load(dir + "/torus.tris");
    const double size = size_of(bunny);
    pqp_model *a = build_ours(bunny), *b = build_ours(torus);
    fresh_cxx::Model *xa = fresh_cxx::build(&bunny[0][0], bunny.size()),
                     *xb = fresh_cxx::build(&torus[0][0], torus.size());
    pqp13::Model *pa = pqp13::build(&bunny[0][0], bunny.size()),
                 *pb = pqp13::build(&torus[0][0], torus.size());

    const std::vector<Pose> touching = family(a, b, size, 0.0, 0.0, n, 4200);
    const std::vector<Pose> near = family(a, b, size, 0.001, 0.05, n, 4201);
    const std::vector<Pose> far = family(a, b, size, 0.5, 2.0, n, 4202);
    const std::vector<Pose> apart = family(a, b, size, 1.5, 4.0, n, 4203);
    std::vector<double> tols;
    Rng trng(4204);
    for (int i = 0; i < n; ++i) tols.push_back(size * std::pow(10.0, -3.0 + 2.0 * trng.uniform()));
    auto tol_of = [&](const Pose& p) { return tols[&p - &apart[0]]; };

    // Root-only check: the poses of `apart` end at the root for collision and tolerance.
    long extra = 0;
    {
        pqp_collide_result* c = pqp_collide_result_create();
        pqp_tolerance_result* t = pqp_tolerance_result_create();
        for (const Pose& p : apart) {
            pqp_collide(c, kIdentity, kZero, a, p.R.data(), p.T.data(), b, PQP_FIRST_CONTACT);
            pqp_tolerance(t, kIdentity, kZero, a, p.R.data(), p.T.data(), b, tol_of(p), 2);
            extra += pqp_collide_result_num_bv_tests(c) - 1 + pqp_tolerance_result_num_bv_tests(t) - 1;
        }
        pqp_collide_result_destroy(c);
        pqp_tolerance_result_destroy(t);
    }

    // Bound tests per query, fresh results, each pose queried twice in a row (the second starts
    // from the first's closest pair in both libraries): medians over the family.
    auto tests = [&](const std::vector<Pose>& poses, double rel) {
        std::vector<double> ours, peer;
        for (const Pose& p : poses) {
            for (int k = 0; k < 2; ++k) {
                pqp_distance_result* r = pqp_distance_result_create();
                const double abs = rel > 0 ? INFINITY : 0.0;
                pqp_distance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, rel, abs, 2);
                if (k == 1) ours.push_back(pqp_distance_result_num_bv_tests(r));
                pqp_distance_result_destroy(r);
                const int t = pqp13::distance_bv_tests(kIdentity, kZero, pa, p.R.data(),
                                                       p.T.data(), pb, rel, abs);
                if (k == 1) peer.push_back(t);
            }
        }
        return std::make_pair(quantile(ours, 0.5), quantile(peer, 0.5));
    };
    for (double rel : {0.0, 0.1}) {
        const auto tn = tests(near, rel), tf = tests(far, rel);
        std::printf("bound tests, median (rel_err %g, abs_err %s): near ours %.0f PQP 1.3 %.0f; "
                    "far ours %.0f PQP 1.3 %.0f\n",
                    rel, rel > 0 ? "inf" : "0", tn.first, tn.second, tf.first, tf.second);
    }

    pqp_distance_result* kept = pqp_distance_result_create();
    auto c_fresh = [&](const Pose& p) {
        pqp_distance_result* r = pqp_distance_result_create();
        pqp_distance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, 0, 0, 2);
        const double d = pqp_distance_result_distance(r);
        pqp_distance_result_destroy(r);
        return d;
    };
    auto c_approx = [&](const Pose& p) {
        pqp_distance_result* r = pqp_distance_result_create();
        pqp_distance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, 0.1, INFINITY, 2);
        const double d = pqp_distance_result_distance(r);
        pqp_distance_result_destroy(r);
        return d;
    };
    auto p_approx = [&](const Pose& p) {
        return pqp13::distance_fresh(kIdentity, kZero, pa, p.R.data(), p.T.data(), pb, 0.1,
                                     INFINITY);
    };
    auto c_reused = [&](const Pose& p) {
        pqp_distance(kept, kIdentity, kZero, a, p.R.data(), p.T.data(), b, 0, 0, 2);
        return pqp_distance_result_distance(kept);
    };
    auto x_fresh = [&](const Pose& p) {
        return fresh_cxx::distance_fresh(kIdentity, kZero, xa, p.R.data(), p.T.data(), xb, 0, 0);
    };
    auto p_fresh = [&](const Pose& p) {
        return pqp13::distance_fresh(kIdentity, kZero, pa, p.R.data(), p.T.data(), pb, 0, 0);
    };
    auto c_collide = [&](const Pose& p) {
        pqp_collide_result* r = pqp_collide_result_create();
        pqp_collide(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, PQP_FIRST_CONTACT);
        const int c = pqp_collide_result_colliding(r);
        pqp_collide_result_destroy(r);
        return static_cast<double>(c);
    };
    auto x_collide = [&](const Pose& p) {
        return static_cast<double>(
            fresh_cxx::collide_first_fresh(kIdentity, kZero, xa, p.R.data(), p.T.data(), xb));
    };
    auto p_collide = [&](const Pose& p) {
        return static_cast<double>(
            pqp13::collide_first_fresh(kIdentity, kZero, pa, p.R.data(), p.T.data(), pb));
    };
    auto c_tol = [&](const Pose& p) {
        pqp_tolerance_result* r = pqp_tolerance_result_create();
        pqp_tolerance(r, kIdentity, kZero, a, p.R.data(), p.T.data(), b, tol_of(p), 2);
        const int c = pqp_tolerance_result_closer_than_tolerance(r);
        pqp_tolerance_result_destroy(r);
        return static_cast<double>(c);
    };
    auto x_tol = [&](const Pose& p) {
        return static_cast<double>(
            fresh_cxx::tolerance_fresh(kIdentity, kZero, xa, p.R.data(), p.T.data(), xb, tol_of(p)));
    };
    auto p_tol = [&](const Pose& p) {
        return static_cast<double>(
            pqp13::tolerance_fresh(kIdentity, kZero, pa, p.R.data(), p.T.data(), pb, tol_of(p)));
    };

    struct Pattern {
        const char* name;
        const std::vector<Pose>* poses;
        std::function<double(const Pose&)> ours, peer;
        double tol;
        Stat st;
    };
    std::vector<Pattern> patterns = {
        {"distance touching, fresh, C ABI", &touching, c_fresh, p_fresh, 1e-9, {}},
        {"distance touching, fresh, PQP.h", &touching, x_fresh, p_fresh, 1e-9, {}},
        {"distance near, fresh, C ABI", &near, c_fresh, p_fresh, 1e-9, {}},
        {"distance near, fresh, PQP.h", &near, x_fresh, p_fresh, 1e-9, {}},
        {"distance near, reused, C ABI", &near, c_reused, p_fresh, 1e-9, {}},
        {"distance far, fresh, C ABI", &far, c_fresh, p_fresh, 1e-9, {}},
        {"distance far, fresh, PQP.h", &far, x_fresh, p_fresh, 1e-9, {}},
        {"distance far, reused, C ABI", &far, c_reused, p_fresh, 1e-9, {}},
        {"distance near, rel_err 0.1, fresh, C ABI", &near, c_approx, p_approx, 0.1, {}},
        {"distance far, rel_err 0.1, fresh, C ABI", &far, c_approx, p_approx, 0.1, {}},
        {"root-only collide first, C ABI", &apart, c_collide, p_collide, 0, {}},
        {"root-only collide first, PQP.h", &apart, x_collide, p_collide, 0, {}},
        {"root-only tolerance, C ABI", &apart, c_tol, p_tol, 0, {}},
        {"root-only tolerance, PQP.h", &apart, x_tol, p_tol, 0, {}},
    };
    for (int round = 0; round < rounds; ++round)
        for (Pattern& pt : patterns) run(pt.name, *pt.poses, pt.st, pt.ours, pt.peer, pt.tol);

    std::printf("bunny (%zu) vs torus (%zu), size %.4g, %d poses a family, %d rounds; root-only "
                "poses with more than one bound test: %ld\n",
                bunny.size(), torus.size(), size, n, rounds, extra);
    std::printf("| pattern | PQP 1.3 / ours, median | 10th percentile | ours (us) | PQP 1.3 (us) |\n");
    std::printf("|---|---:|---:|---:|---:|\n");
    for (const Pattern& pt : patterns)
        std::printf("| %s | %.2f | %.2f | %.3f | %.3f |\n", pt.name, quantile(pt.st.ratio, 0.5),
                    quantile(pt.st.ratio, 0.1), quantile(pt.st.ours, 0.5),
                    quantile(pt.st.peer, 0.5));
    pqp_distance_result_destroy(kept);
    pqp_model_destroy(a);
    pqp_model_destroy(b);
    fresh_cxx::destroy(xa);
    fresh_cxx::destroy(xb);
    pqp13::destroy(pa);
    pqp13::destroy(pb);
    return 0;
}
