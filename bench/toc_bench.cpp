// Time of first contact (BENCHMARKS.md): pqp_time_of_contact against FCL 0.7's
// continuous collision on the same motions (c_tests/toc_fcl.hpp makes FCL's InterpMotion equal to
// ours): its conservative advancement on BVHModel<RSS> and BVHModel<OBBRSS>, and its naive method
// (collision queries at 1000 evenly spaced times). Motions: the falling tori of /work/shared/models
// from frame a to frame a + k (k = 1, 10, 100; a every max(k, 4) frames, as
// examples/time_of_contact.rs, whose step counts are for these motions). Ours runs at tolerance
// 1e-5 B (B: the speed bound of every point; the tolerance FCL's time error 1e-5 implies, see
// c_tests/toc_compare.cpp) and at 1e-12 of the scene's size (touching, as FCL's naive method
// decides contact). Rounds alternate between the libraries; medians of the rounds' times.
//
//   toc_bench [models-dir] [rounds]        (defaults PQP_BENCH_MODELS_DIR and 3)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <pqp/pqp.h>

#include "../c_tests/toc_fcl.hpp"

namespace {

using Tris = std::vector<std::array<double, 9>>;

Tris read_tris(const std::string &file) {
    Tris out;
    std::ifstream in(file);
    long n = 0;
    if (!in || !(in >> n) || n <= 0) return out;
    out.resize(size_t(n));
    for (auto &t : out)
        for (double &x : t) in >> x;
    return in ? out : Tris{};
}

pqp_model *our_model(const Tris &tris) {
    pqp_model *m = pqp_model_create();
    int rc = pqp_model_begin(m, int(tris.size()));
    for (size_t i = 0; i < tris.size() && rc == PQP_OK; ++i)
        rc = pqp_model_add_tri(m, &tris[i][0], &tris[i][3], &tris[i][6], int(i));
    if (rc == PQP_OK) rc = pqp_model_end(m);
    if (rc != PQP_OK) {
        std::fprintf(stderr, "model: rc %d\n", rc);
        std::exit(1);
    }
    return m;
}

double radius(const Tris &tris) {
    double r = 0;
    for (const auto &t : tris)
        for (int k = 0; k < 9; k += 3) r = std::max(r, std::sqrt(t[size_t(k)] * t[size_t(k)] + t[size_t(k + 1)] * t[size_t(k + 1)] + t[size_t(k + 2)] * t[size_t(k + 2)]));
    return r;
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

struct Answer {
    bool contact;
    double toc;
    long steps;
};

}  // namespace

int main(int argc, char **argv) {
    const std::string dir = argc > 1 ? argv[1] : PQP_BENCH_MODELS_DIR;
    const int rounds = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
    const Tris t1 = read_tris(dir + "/torus1.tris"), t2 = read_tris(dir + "/torus2.tris");
    const auto p1 = toc::read_path(dir + "/torus1.path"), p2 = toc::read_path(dir + "/torus2.path");
    if (t1.empty() || t2.empty() || p1.empty() || p2.empty()) {
        std::fprintf(stderr, "torus1/torus2 .tris/.path not found in %s\n", dir.c_str());
        return 1;
    }
    pqp_model *m1 = our_model(t1), *m2 = our_model(t2);
    const auto r1 = toc::fcl_mesh<fcl::RSSd>(t1), r2 = toc::fcl_mesh<fcl::RSSd>(t2);
    const auto o1 = toc::fcl_mesh<fcl::OBBRSSd>(t1), o2 = toc::fcl_mesh<fcl::OBBRSSd>(t2);
    const double rad1 = radius(t1), rad2 = radius(t2);
    const size_t n = std::min(p1.size(), p2.size());
    std::printf("tori: %zu x %zu triangles, %zu frames, %d rounds\n\n", t1.size(), t2.size(), n, rounds);
    std::printf("| frames apart | queries | method | contacts | time per query | steps: mean | max | toc vs ours: agree | median abs diff |\n");
    std::printf("| ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for (int k : {1, 10, 100}) {
        std::vector<std::pair<toc::Motion, toc::Motion>> motions;
        for (size_t a = 0; a + size_t(k) < n; a += size_t(std::max(k, 4)))
            motions.push_back({toc::between(p1[a], p1[a + size_t(k)]), toc::between(p2[a], p2[a + size_t(k)])});
        const char *names[] = {"ours, tol 1e-5 B", "ours, tol 1e-12 (touching)", "FCL CA, RSS", "FCL CA, OBBRSS",
                               "FCL naive, 1000 samples"};
        constexpr int kMethods = 5;
        std::vector<Answer> answers[kMethods];
        std::vector<double> times[kMethods];
        for (int round = 0; round < rounds; ++round)
            for (int method = 0; method < kMethods; ++method) {
                std::vector<Answer> out;
                const double start = now();
                for (const auto &[a, b] : motions) {
                    if (method < 2) {
                        double scale = 1;
                        for (const toc::V3 *T : {&a.Ta, &a.Tb, &b.Ta, &b.Tb})
                            scale = std::max(scale, std::sqrt((*T)[0] * (*T)[0] + (*T)[1] * (*T)[1] + (*T)[2] * (*T)[2]) + rad1 + rad2);
                        const double tol = method == 0 ? std::max(1e-5 * toc::speed_bound(a, rad1, b, rad2), 1e-9 * scale)
                                                       : 1e-12 * scale;
                        pqp_contact_time c;
                        const int rc = pqp_time_of_contact(&c, a.Ra.data(), a.Ta.data(), a.Rb.data(), a.Tb.data(), m1,
                                                           b.Ra.data(), b.Ta.data(), b.Rb.data(), b.Tb.data(), m2, tol);
                        if (rc != PQP_OK) {
                            std::fprintf(stderr, "pqp_time_of_contact: rc %d\n", rc);
                            return 1;
                        }
                        out.push_back({c.contact != 0, c.contact ? c.toc : 1.0, -1});
                    } else {
                        const toc::FclToc f = method == 2   ? toc::fcl_toc(*r1, a, *r2, b)
                                              : method == 3 ? toc::fcl_toc(*o1, a, *o2, b)
                                                            : toc::fcl_naive_toc(*o1, a, *o2, b, 1000);
                        out.push_back({f.contact, f.toc, f.steps});
                    }
                }
                times[method].push_back((now() - start) / double(motions.size()));
                answers[method] = out;
            }
        for (int method = 0; method < kMethods; ++method) {
            const std::vector<Answer> &v = answers[method];
            // Agreement with ours: the same verdict and, with contact, toc within the method's own
            // accuracy of ours at the matching tolerance (FCL CA: ours at 1e-5 B, within 1e-3 of t;
            // naive: ours touching, within one sample after).
            const std::vector<Answer> &ref = answers[method == 4 ? 1 : 0];
            long contacts = 0, agree = 0, steps = 0, most = 0;
            std::vector<double> diffs;
            for (size_t i = 0; i < v.size(); ++i) {
                contacts += v[i].contact;
                steps += std::max(0L, v[i].steps);
                most = std::max(most, v[i].steps);
                if (v[i].contact && ref[i].contact) diffs.push_back(std::fabs(v[i].toc - ref[i].toc));
                const bool same = v[i].contact == ref[i].contact &&
                                  (!v[i].contact || (method == 4 ? v[i].toc >= ref[i].toc && v[i].toc - ref[i].toc <= 1.0 / 999 + 1e-12
                                                                 : std::fabs(v[i].toc - ref[i].toc) <= 1e-3));
                agree += same;
            }
            const std::string step_cols = method < 2 ? "- | -" : std::to_string(double(steps) / double(v.size())).substr(0, 5) + " | " + std::to_string(most);
            std::printf("| %d | %zu | %s | %ld | %.1f us | %s | %s | %s |\n", k, v.size(), names[method], contacts,
                        median(times[method]) * 1e6, step_cols.c_str(),
                        method < 2 ? "-" : (std::to_string(agree) + " / " + std::to_string(v.size())).c_str(),
                        diffs.empty() ? "-" : (std::to_string(median(diffs)).substr(0, 8)).c_str());
        }
    }
    pqp_model_destroy(m1);
    pqp_model_destroy(m2);
    return 0;
}
