// UNC's PQP 1.3 as an optional benchmark peer (CMake: -DPQP13_SOURCE_DIR=<PQP 1.3's src>).
//
// PQP 1.3 and pqp-rs's PQP.h both define class PQP_Model and the result structs, so PQP 1.3 lives
// in its own translation unit (pqp13_peer.cpp, compiled against PQP 1.3's headers) and is reached
// only through this interface, which names none of its types. pqp_bench.cpp talks to pqp-rs through
// the C API <pqp/pqp.h> only. Poses are PQP's: R row-major (9 doubles), T (3 doubles).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace pqp13 {

struct Model;    // a built PQP_Model
struct Results;  // one PQP_CollideResult, PQP_DistanceResult and PQP_ToleranceResult

// Builds a model from n triangles of 9 doubles each (triangle k gets id k); NULL if PQP 1.3
// refuses. Timing a build times this call.
Model* build(const double* tris, std::size_t n);
void destroy(Model* m);

Results* results_create();
void results_destroy(Results* r);

// PQP_Collide (all contacts or the first); returns PQP 1.3's code. pairs(r) lists the last answer.
int collide(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
            const double* T2, Model* m2, bool all);
std::vector<std::pair<int, int>> pairs(Results* r);

// PQP_Distance; returns the distance (NaN if PQP 1.3 returned an error).
double distance(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
                const double* T2, Model* m2, double rel_err, double abs_err, int qsize);

// PQP_Tolerance; returns the closer flag (-1 if PQP 1.3 returned an error).
int tolerance(Results* r, const double* R1, const double* T1, Model* m1, const double* R2,
              const double* T2, Model* m2, double tol, int qsize);

// PQP 1.3's own memory report for a model (MemUsage(0)).
int memory_usage(Model* m);

}  // namespace pqp13

namespace pqp13 {

// As legacy programs call PQP 1.3: the result object declared inside the call (a fresh one each
// time; PQP 1.3 keeps its last closest pair in the models, so it still starts warm).
double distance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err);
int collide_first_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                        const double* T2, Model* m2);
int tolerance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                    const double* T2, Model* m2, double tol);

}  // namespace pqp13

namespace pqp13 {
// The bound tests of a distance query with a fresh result (PQP 1.3's num_bv_tests).
int distance_bv_tests(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err);
}  // namespace pqp13
