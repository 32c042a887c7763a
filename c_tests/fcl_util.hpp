// FCL 0.7 set-up shared by the C test programs that compare with FCL (c_tests/*_compare.cpp) and the
// benchmarks that time it (bench/*.cpp): a triangle mesh as an FCL BVH model, and a row-major pose
// (our C API's R[9], T[3]) as an FCL transform. Header-only; needs nothing but FCL.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>

#include <cstddef>
#include <memory>

namespace fclu {

/// An FCL mesh of `n` triangles with bounding volumes `BV`, triangle i's corner k (0..2) at
/// `corner(i, k)` (three doubles). One addTriangle per triangle, so FCL's primitive index is the
/// triangle's position in the input (our id, where the ids are 0..n-1).
template <typename BV, typename Corner>
std::shared_ptr<fcl::BVHModel<BV>> mesh(size_t n, Corner corner) {
    auto g = std::make_shared<fcl::BVHModel<BV>>();
    g->beginModel(static_cast<int>(n), static_cast<int>(3 * n));
    for (size_t i = 0; i < n; ++i) {
        const double *a = corner(i, 0), *b = corner(i, 1), *c = corner(i, 2);
        g->addTriangle(fcl::Vector3d(a[0], a[1], a[2]), fcl::Vector3d(b[0], b[1], b[2]),
                       fcl::Vector3d(c[0], c[1], c[2]));
    }
    g->endModel();
    g->computeLocalAABB();
    return g;
}

/// The same, from triangles stored as nine doubles each (p1, p2, p3) in any container of arrays.
template <typename BV, typename Tris>
std::shared_ptr<fcl::BVHModel<BV>> mesh_of_flat(const Tris &tris) {
    return mesh<BV>(tris.size(), [&](size_t i, int k) { return &tris[i][size_t(3 * k)]; });
}

/// The transform x -> R x + T, R row-major.
inline fcl::Transform3d transform(const double R[9], const double T[3]) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    fcl::Matrix3d m;
    m << R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8];
    tf.linear() = m;
    tf.translation() = fcl::Vector3d(T[0], T[1], T[2]);
    return tf;
}

}  // namespace fclu
