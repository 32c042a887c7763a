// pqp-rs's C++ interface (PQP.h) as the fresh-result benchmark calls it: compiled in its own
// translation unit (fresh_cxx.cpp), since PQP.h and PQP 1.3 both define class PQP_Model. Poses
// are PQP's: R row-major (9 doubles), T (3 doubles).
#pragma once

#include <cstddef>

namespace fresh_cxx {

struct Model;  // a built PQP_Model of PQP.h

Model* build(const double* tris, std::size_t n);
void destroy(Model* m);

// Each call declares its result object inside (as legacy programs do): a fresh result per call.
double distance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                      const double* T2, Model* m2, double rel_err, double abs_err);
int collide_first_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                        const double* T2, Model* m2);
int tolerance_fresh(const double* R1, const double* T1, Model* m1, const double* R2,
                    const double* T2, Model* m2, double tol);

// The same with one result object kept across calls.
double distance_reused(const double* R1, const double* T1, Model* m1, const double* R2,
                       const double* T2, Model* m2, double rel_err, double abs_err);

}  // namespace fresh_cxx
