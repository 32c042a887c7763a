// Coal 3 (the FCL fork of the Pinocchio project) as an optional benchmark peer (CMake:
// -DCOAL_PREFIX=<the cmeel.prefix directory of `pip install libcoal==3.0.3`>). Like PQP 1.3
// (pqp13_peer.hpp) it lives in its own translation unit, so pqp_bench.cpp needs none of Coal's
// headers (which would clash with FCL's Eigen setup only in name, but keep the builds apart).
// Meshes use Coal's default bounding volume for meshes, OBBRSS. Poses are PQP's: R row-major
// (9 doubles), T (3 doubles).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace coalpeer {

struct Model;

// Builds a BVHModel<OBBRSS> from n triangles of 9 doubles each (triangle k is index k).
Model* build(const double* tris, std::size_t n);
void destroy(Model* m);

// Collision, all contacts or the first; the triangle index pairs found.
std::vector<std::pair<int, int>> collide(const double* R1, const double* T1, Model* m1,
                                         const double* R2, const double* T2, Model* m2, bool all);
// Number of pairs only (for timing: no vector is built).
std::size_t collide_count(const double* R1, const double* T1, Model* m1, const double* R2,
                          const double* T2, Model* m2, bool all);

// Distance with Coal's rel_err / abs_err.
double distance(const double* R1, const double* T1, Model* m1, const double* R2,
                const double* T2, Model* m2, double rel_err, double abs_err);

}  // namespace coalpeer
