// Shared test harness: seeded random numbers, meshes and poses, world-space brute force in long double,
// wrappers over our C API (and the PQP.h drop-in), and the report that decides pass/fail.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <PQP.h>
#include <pqp/pqp.h>

#include "bf.hpp"

namespace ht {

using L = long double;
using LV = bf::V<L>;

// ---------------------------------------------------------------------------------------------------
// Random numbers: xoshiro256** seeded by splitmix64 (own implementation, so runs are reproducible
// everywhere from the printed seed).
class Rng {
  public:
    explicit Rng(uint64_t seed);
    uint64_t next();
    double uniform();                          ///< [0, 1)
    double uniform(double a, double b);        ///< [a, b)
    double log_uniform(double a, double b);    ///< log-uniform in [a, b), a > 0
    int below(int n);                          ///< [0, n)
    double normal();

  private:
    uint64_t s_[4];
};

// ---------------------------------------------------------------------------------------------------
struct Tri {
    double p[3][3];
};

struct Mesh {
    std::string name;
    std::vector<Tri> tris;
    /// All coordinates exact and all non-touching feature distances large: at exact poses (identity,
    /// axis permutations, small integer translations) touching is decided exactly, no borderline band.
    bool exact = false;
    double radius() const;  ///< max |vertex|
};

Mesh make_sphere(double r, int nlat, int nlon);                   ///< UV sphere, 2*nlon*(nlat-1) tris
Mesh make_torus(double R, double r, int nu, int nv);              ///< 2*nu*nv tris
Mesh make_soup(Rng &rng, int n, double box, double size);         ///< random triangles in a cube
Mesh make_thin(Rng &rng, int n, double box, double size);         ///< slivers, needles, segments, points
Mesh make_flat(Rng &rng, int n, double extent);                   ///< degenerate and thin triangles in z = 0
Mesh make_grid(int nx, int ny);                                   ///< unit squares at z = 0, exact
Mesh make_cube();                                                 ///< cube [-1,1]^3 (12 tris), exact
Mesh make_box(int nsub);                                          ///< cube [-1,1]^3, faces nsub x nsub
/// Reads a `.tris` file (n, then n*9 numbers). Returns false if missing or malformed.
bool load_tris(const std::string &path, Mesh *out);
struct Options;
/// The first `dir/file` that exists among the --models directories, else "".
std::string find_model(const Options &o, const std::string &file);
/// The model file if found and it loads, otherwise the fallback (with a note on stdout).
Mesh load_or(const Options &o, const std::string &file, const Mesh &fallback);
/// The mesh recentred at its bounding-box centre and scaled to radius ~1 (exact meshes unchanged).
Mesh normalized(const Mesh &m);

// ---------------------------------------------------------------------------------------------------
struct Pose {
    double R[9];  ///< row-major
    double T[3];
};

Pose identity_pose();
Pose random_pose(Rng &rng, double tscale);
void random_rotation(Rng &rng, double R[9]);
struct PosePair {
    Pose a, b;
    std::string kind;
    bool exact = false;  ///< exact data at exact poses: touching is decided without a band
};

/// Random unit vector.
LV rand_dir(Rng &rng);
/// Random rotations; b's centre at a random direction from a's, at (ra + rb) * U(lo, hi).
PosePair random_pair(Rng &rng, double ra, double rb, double lo, double hi, const char *kind);
/// Adds the same offset (magnitude 10^U(0,6)) to both translations.
void add_offset(Rng &rng, PosePair &pp);
/// A pose with the models about `gap` apart: moves b along the direction between the closest points of
/// the pair that `closest` names (computed here in long double), a few times.
PosePair near_pair(Rng &rng, const Mesh &A, const Mesh &B, double ra, double rb, double gap,
                   const std::function<std::pair<int, int>(const PosePair &)> &closest);
/// Model b resting on the top face (z = 1) of the box [-1,1]^3 that model a is (in a's frame): b turned
/// about z only (type 0: face on face for a box), turned 45 degrees about x too (type 1: edge down), or
/// at random (type 2: vertex down); then tilted by `tilt` radians about a random horizontal axis, and
/// lifted so that its lowest vertex is at height 1 + gap (gap < 0: penetration). Then both are placed
/// at a random pose (a at the identity for a quarter of them).
PosePair contact_pair(Rng &rng, const Mesh &B, int type, double gap, double tilt);
/// gap for contact poses: 0, or +-10^U(-12,-2)
double contact_gap(Rng &rng);
/// tilt for contact poses: 0, 1e-9, 1e-6 or 1e-3 radians
double contact_tilt(Rng &rng);

/// Gram-Schmidt on the rows (for rotations read from files with few digits).
void orthonormalize(double R[9]);

/// World-space triangles in long double (x = R p + T evaluated in long double) and their boxes.
struct World {
    std::vector<LV> v;  ///< 3 per triangle
    std::vector<LV> lo, hi;
    double scale = 1;   ///< max |coordinate|
    const LV *tri(int i) const { return &v[3 * static_cast<size_t>(i)]; }
    int size() const { return static_cast<int>(lo.size()); }
};
World to_world(const Mesh &m, const Pose &p);
LV to_world(const double *R, const double *T, const double *x);
L point_triangle_distance(const LV &p, const LV *tri);

/// Calls f(i, j) for every pair whose boxes are within `margin` (sweep along x).
void box_pairs(const World &A, const World &B, L margin, const std::function<void(int, int)> &f);
L box_distance(const World &A, int i, const World &B, int j);

enum class Truth { Separated, Intersecting, Borderline };
const char *truth_name(Truth t);

/// The band of geometric ambiguity for a pose: 1e-12 * max(1, largest |coordinate|).
double band_for(const World &A, const World &B);

struct PairTruth {
    L dist, depth;
    Truth truth;
    LV pa, pb;
};
PairTruth pair_truth(const World &A, int i, const World &B, int j, double band, bool exact);

/// All truly intersecting and borderline pairs (full brute force over box-overlapping pairs).
struct CollideTruth {
    std::vector<std::pair<int, int>> intersecting, borderline;
    long pairs_tested = 0;
};
CollideTruth collide_truth(const World &A, const World &B, double band, bool exact);

/// Exact minimum distance over all pairs; `hint_pairs` seed the upper bound (their distances are
/// evaluated independently, so a wrong hint only costs time).
struct DistanceTruth {
    L dist;
    int i = -1, j = -1;
    long pairs_tested = 0;
};
DistanceTruth distance_truth(const World &A, const World &B, const std::vector<std::pair<int, int>> &hint_pairs);

// ---------------------------------------------------------------------------------------------------
// Our library through the C ABI.
class OurModel {
  public:
    explicit OurModel(const Mesh &m);
    ~OurModel();
    OurModel(const OurModel &) = delete;
    OurModel &operator=(const OurModel &) = delete;
    const pqp_model *get() const { return m_; }
    int build_rc = PQP_OK;  ///< first non-OK code of the build, if any

  private:
    pqp_model *m_;
};

struct CollideOut {
    int rc = 0;
    bool colliding = false;
    std::vector<std::pair<int, int>> pairs;
};
struct DistanceOut {
    int rc = 0;
    double d = 0;
    double p1[3] = {0, 0, 0}, p2[3] = {0, 0, 0};
    int id1 = -1, id2 = -1;  ///< -1 when the interface cannot tell (PQP.h)
    int overlap = -1;        ///< -1 when the interface cannot tell (PQP.h)
};
struct ToleranceOut {
    int rc = 0;
    bool closer = false;
    double d = 0, t = 0;
    double p1[3] = {0, 0, 0}, p2[3] = {0, 0, 0};
};

CollideOut our_collide(pqp_collide_result *r, const PosePair &pp, const OurModel &a, const OurModel &b, int flag);
DistanceOut our_distance(pqp_distance_result *r, const PosePair &pp, const OurModel &a, const OurModel &b,
                         double rel, double abs, int qsize);
ToleranceOut our_tolerance(pqp_tolerance_result *r, const PosePair &pp, const OurModel &a, const OurModel &b,
                           double t, int qsize);

// The same through the C++ drop-in header.
struct PqpHModel {
    PQP_Model m;
    int build_rc = PQP_OK;
    explicit PqpHModel(const Mesh &mesh);
};
CollideOut pqph_collide(PQP_CollideResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, int flag);
DistanceOut pqph_distance(PQP_DistanceResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, double rel,
                          double abs, int qsize);
ToleranceOut pqph_tolerance(PQP_ToleranceResult *r, const PosePair &pp, PqpHModel &a, PqpHModel &b, double t,
                            int qsize);

// ---------------------------------------------------------------------------------------------------
/// Counts checks, comparisons and disagreements. Every check where our library is wrong is printed
/// as it happens and fails the run; disagreements where the peer is wrong are counted by category.
class Report {
  public:
    explicit Report(std::string program) : program_(std::move(program)) {}
    /// Context printed with failures; `cls` (a pose class, see pose_class) breaks disagreement
    /// categories down.
    void set_context(const std::string &ctx, const std::string &cls = "") {
        ctx_ = ctx;
        cls_ = cls;
    }
    const std::string &context() const { return ctx_; }
    /// A check of our library; prints and counts a failure when !ok.
    bool check(bool ok, const std::string &what);
    /// A disagreement with a peer, resolved by brute force. `we_wrong` fails the run.
    void disagreement(const std::string &peer, const std::string &category, bool we_wrong, const std::string &detail);
    void count(const std::string &key, long n = 1) { counters_[key] += n; }
    long failed() const { return failed_; }
    /// Prints the summary; returns the process exit code.
    int finish(double seconds);

  private:
    struct Cat {
        long count = 0;
        bool we_wrong = false;
        std::vector<std::string> examples;
    };
    std::string program_, ctx_, cls_;
    std::map<std::string, long> counters_;
    std::map<std::string, Cat> cats_;
    long passed_ = 0, failed_ = 0;
};

/// Tolerances of the comparisons.
constexpr double kRel = 1e-9;
inline double dist_tol(double d, double band) { return kRel * d + band; }

std::string fmt(const char *f, ...) __attribute__((format(printf, 1, 2)));
std::string join(const std::vector<std::string> &v);
std::string pose_str(const PosePair &pp);
/// Short class of a pose for the summary: "near", "contact face", "deep overlap", ... (+offset).
std::string pose_class(const PosePair &pp);

/// Command line shared by the programs.
struct Options {
    uint64_t seed = 20240611;
    double scale = 1.0;  ///< workload multiplier
    std::vector<std::string> models_dirs;  ///< searched in order (--models, repeatable)
    std::string only;  ///< run only the workloads whose name contains this
};
Options parse_options(int argc, char **argv);
int scaled(const Options &o, int n);  ///< max(1, round(n * scale))
/// Prints the program's first line: its name, the seed, the scale and the model directories.
void announce(const char *program, const Options &o);

/// The main loop of the programs that compare workloads of two meshes (`w.name`, `w.a`, `w.b`):
/// for each workload whose name contains --only, `run(w)` checks it and returns how many poses (or
/// motions: `unit`) it checked; a line with the sizes, that count, the time and whether anything
/// failed follows. Returns the report's exit code, timed from `start`.
template <typename W, typename Run>
int run_workloads(Report &rep, const Options &o, const std::vector<W> &ws, const char *unit,
                  std::chrono::steady_clock::time_point start, Run run) {
    for (const W &w : ws) {
        if (w.name.find(o.only) == std::string::npos) continue;
        const auto t1 = std::chrono::steady_clock::now();
        const long failed_before = rep.failed();
        rep.set_context(w.name);
        const size_t checked = run(w);
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
        std::printf("  %-48s %5zu tris x %5zu tris, %4zu %s, %6.2f s%s\n", w.name.c_str(), w.a.tris.size(),
                    w.b.tris.size(), checked, unit, secs, rep.failed() > failed_before ? "  FAILURES" : "");
        std::fflush(stdout);
    }
    return rep.finish(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace ht
