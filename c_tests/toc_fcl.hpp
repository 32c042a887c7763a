// Time of first contact on both sides, for c_tests/toc_compare.cpp and bench/toc_bench.cpp: FCL 0.7's
// continuous collision by conservative advancement (CCDC_CONSERVATIVE_ADVANCEMENT) on mesh models,
// with the motion made identical to pqp_time_of_contact's, and that motion evaluated at any t.
//
// The motion. pqp_time_of_contact moves a model from (Ra, Ta) at t = 0 to (Rb, Tb) at t = 1 as
//   R(t) = Ra exp(t log(Ra^T Rb)),   T(t) = Ta + t (Tb - Ta),
// the shorter way. FCL's InterpMotion (fcl/math/motion/interp_motion-inl.h) takes the angle-axis of
// Rb Ra^T (angle in [0, pi]) and a reference point O (model coordinates), and poses the model as
//   R(t) = exp(t log(Rb Ra^T)) Ra,   T(t) = t (Tb O + Tb - Ta O - Ta) + Ta O + Ta - R(t) O
// (writing P x = R_P x + T_P): the point O moves on a straight line and the model turns about it.
// The rotations are the same: Ra exp(t log(Ra^T Rb)) Ra^T = exp(t Ra log(Ra^T Rb) Ra^T) =
// exp(t log(Ra Ra^T Rb Ra^T)) = exp(t log(Rb Ra^T)), conjugation commuting with exp and log (both
// take the shorter way; an angle of exactly pi is avoided by the callers). With O = 0 the
// translation is Ta + t (Tb - Ta), ours. So FCL gets InterpMotion(Ra, Ta, Rb, Tb, O = 0) through its
// five-argument matrix constructor, which sets O and computes the velocities. Not through
// continuousCollide(o1, tf1_beg, tf1_end, ...) with CCDM_LINEAR: that builds InterpMotion(tf_beg,
// tf_end), whose constructor leaves the reference point uninitialised (an Eigen vector is not
// zeroed), and the constructor from two transforms and O never computes the velocities at all.
//
// FCL's conservative advancement on meshes is known to miss contacts in 0.7 (FCL issues #120, open
// since 2016, and #555: the traversal adds the two models' motion bounds along the normal with their
// signs, so they can cancel and the step overshoots). So FCL's naive continuous collision
// (CCDC_NAIVE: a discrete collision query at n evenly spaced times, the first colliding one being the
// toc) on the same motions is compared too; its toc is accurate to 1 / (n - 1) and it misses
// contacts shorter than that.
//
// FCL's steps: its advancement loop calls integrate() on each motion once per step (and once more
// at the end when it reports a contact); a motion that counts those calls gives the number of
// distance traversals FCL made.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/motion/interp_motion.h>
#include <fcl/narrowphase/continuous_collision.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "fcl_util.hpp"

namespace toc {

using M3 = std::array<double, 9>;  ///< row-major rotation
using V3 = std::array<double, 3>;

/// One model's motion: pose a at t = 0, pose b at t = 1 (rotations proper to rounding).
struct Motion {
    M3 Ra, Rb;
    V3 Ta, Tb;
};

inline M3 mul(const M3 &a, const M3 &b) {
    M3 c{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) c[size_t(3 * i + j)] += a[size_t(3 * i + k)] * b[size_t(3 * k + j)];
    return c;
}

inline M3 transpose(const M3 &a) {
    M3 t{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t[size_t(3 * i + j)] = a[size_t(3 * j + i)];
    return t;
}

/// Angle (in [0, pi]) and unit axis of a rotation (the axis is (1, 0, 0) for the identity).
inline double rotation_angle_axis(const M3 &R, V3 *axis) {
    const double c = std::clamp((R[0] + R[4] + R[8] - 1) / 2, -1.0, 1.0);
    const V3 v{(R[7] - R[5]) / 2, (R[2] - R[6]) / 2, (R[3] - R[1]) / 2};  // sin(angle) axis
    const double s = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double angle = std::atan2(s, c);
    if (angle < 1e-300) {
        *axis = {1, 0, 0};
        return 0;
    }
    if (angle < 3.0) {
        *axis = {v[0] / s, v[1] / s, v[2] / s};
        return angle;
    }
    // Near pi the skew part vanishes: the symmetric part minus c I is (1 - c) a a^T; take its
    // largest column, and the sign from the skew part.
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (R[size_t(4 * i)] > R[size_t(4 * k)]) k = i;
    V3 a{};
    for (int i = 0; i < 3; ++i) a[size_t(i)] = (R[size_t(3 * i + k)] + R[size_t(3 * k + i)]) / 2 - (i == k ? c : 0);
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double sign = a[0] * v[0] + a[1] * v[1] + a[2] * v[2] < 0 ? -1 : 1;
    *axis = {sign * a[0] / n, sign * a[1] / n, sign * a[2] / n};
    return angle;
}

/// exp(angle [axis]x), Rodrigues' formula.
inline M3 rotation_exp(const V3 &u, double angle) {
    const double c = std::cos(angle), s = std::sin(angle), C = 1 - c;
    return {c + u[0] * u[0] * C,        u[0] * u[1] * C - u[2] * s, u[0] * u[2] * C + u[1] * s,
            u[1] * u[0] * C + u[2] * s, c + u[1] * u[1] * C,        u[1] * u[2] * C - u[0] * s,
            u[2] * u[0] * C - u[1] * s, u[2] * u[1] * C + u[0] * s, c + u[2] * u[2] * C};
}

/// The motion's relative turn (the angle of Rb Ra^T) and its axis.
inline double turn(const Motion &m, V3 *axis) { return rotation_angle_axis(mul(m.Rb, transpose(m.Ra)), axis); }

/// The pose at t, evaluated as exp(t log(Rb Ra^T)) Ra (FCL's form; equal to ours, above).
inline void pose_at(const Motion &m, double t, M3 *R, V3 *T) {
    V3 axis;
    const double angle = turn(m, &axis);
    *R = mul(rotation_exp(axis, t * angle), m.Ra);
    for (int k = 0; k < 3; ++k) (*T)[size_t(k)] = m.Ta[size_t(k)] + t * (m.Tb[size_t(k)] - m.Ta[size_t(k)]);
}

/// The poses of a `.path` file (count, then R row by row and T per frame), rotations made proper;
/// empty if the file is missing or malformed.
inline std::vector<std::pair<M3, V3>> read_path(const std::string &file) {
    std::vector<std::pair<M3, V3>> out;
    std::ifstream in(file);
    long n = 0;
    if (!in || !(in >> n) || n <= 0) return out;
    for (long i = 0; i < n; ++i) {
        std::pair<M3, V3> p;
        for (double &x : p.first) in >> x;
        for (double &x : p.second) in >> x;
        if (!in) return {};
        // Made proper through its angle and axis (the exponential of the rotation's logarithm
        // is a rotation, within 1e-6 of the one written).
        V3 axis;
        const double angle = rotation_angle_axis(p.first, &axis);
        p.first = rotation_exp(axis, angle);
        out.push_back(p);
    }
    return out;
}

/// The motion between two poses of a path.
inline Motion between(const std::pair<M3, V3> &a, const std::pair<M3, V3> &b) {
    return {a.first, b.first, a.second, b.second};
}

/// A bound on the speed of every point of two models moving as m1, m2 relative to each other:
/// |dT2 - dT1| + angle1 r1 + angle2 r2, r_i bounding |x| over model i's vertices.
inline double speed_bound(const Motion &m1, double r1, const Motion &m2, double r2) {
    V3 axis;
    double dv2 = 0;
    for (int k = 0; k < 3; ++k) {
        const double dv = (m2.Tb[size_t(k)] - m2.Ta[size_t(k)]) - (m1.Tb[size_t(k)] - m1.Ta[size_t(k)]);
        dv2 += dv * dv;
    }
    return std::sqrt(dv2) + turn(m1, &axis) * r1 + turn(m2, &axis) * r2;
}

/// An FCL mesh: one addTriangle per triangle (9 doubles each), so FCL's primitive index is our id.
template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> fcl_mesh(const std::vector<std::array<double, 9>> &tris) {
    return fclu::mesh_of_flat<BV>(tris);
}

/// FCL's linear interpolation motion about the model origin, counting its integrate() calls.
class CountingMotion : public fcl::InterpMotion<double> {
  public:
    explicit CountingMotion(const Motion &m)
        : fcl::InterpMotion<double>(matrix(m.Ra), vector(m.Ta), matrix(m.Rb), vector(m.Tb), fcl::Vector3d::Zero()) {}
    bool integrate(double dt) const override {
        ++calls;
        return fcl::InterpMotion<double>::integrate(dt);
    }
    mutable long calls = 0;

  private:
    static fcl::Matrix3d matrix(const M3 &R) {
        fcl::Matrix3d m;
        m << R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8];
        return m;
    }
    static fcl::Vector3d vector(const V3 &T) { return fcl::Vector3d(T[0], T[1], T[2]); }
};

struct FclToc {
    bool contact = false;
    double toc = 1;  ///< FCL's time of contact (1 without contact)
    long steps = 0;  ///< distance traversals FCL made (0: in collision at t = 0, decided by collide)
};

/// FCL's conservative advancement (its time error t_err is fixed at 1e-5 inside the traversal node;
/// the request's toc_err and iteration cap are not read by this solver).
template <typename BV>
FclToc fcl_toc(const fcl::BVHModel<BV> &g1, const Motion &m1, const fcl::BVHModel<BV> &g2, const Motion &m2) {
    const CountingMotion f1(m1), f2(m2);
    fcl::ContinuousCollisionRequestd req(10, 1e-5, fcl::CCDM_LINEAR, fcl::GST_LIBCCD,
                                        fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
    fcl::ContinuousCollisionResultd res;
    fcl::continuousCollide(&g1, &f1, &g2, &f2, req, res);
    FclToc out;
    out.contact = res.is_collide;
    out.toc = res.time_of_contact;
    // One integrate per advancement step, one more for the reported contact pose; a contact at t = 0
    // is found by a collision query before any step.
    const long loop = f1.calls - (res.is_collide ? 1 : 0);
    out.steps = (res.is_collide && res.time_of_contact == 0 && loop == 0) ? 0 : loop + 1;
    return out;
}

/// FCL's naive continuous collision: a collision query at `samples` evenly spaced times (steps: the
/// queries made).
template <typename BV>
FclToc fcl_naive_toc(const fcl::BVHModel<BV> &g1, const Motion &m1, const fcl::BVHModel<BV> &g2, const Motion &m2,
                     int samples) {
    const CountingMotion f1(m1), f2(m2);
    fcl::ContinuousCollisionRequestd req(size_t(samples), 1.0 / samples, fcl::CCDM_LINEAR, fcl::GST_LIBCCD,
                                        fcl::CCDC_NAIVE);
    fcl::ContinuousCollisionResultd res;
    fcl::continuousCollide(&g1, &f1, &g2, &f2, req, res);
    return {res.is_collide, res.time_of_contact, f1.calls};
}

/// The largest difference, over the entries of R and T at a few times, between FCL's pose of the
/// motion (InterpMotion::integrate) and pose_at's: the check that the two motions are one.
inline double motion_mismatch(const Motion &m) {
    const CountingMotion f(m);
    double worst = 0;
    for (double t : {0.0, 0.125, 0.37, 0.5, 0.81, 1.0}) {
        f.integrate(t);
        fcl::Transform3d tf;
        f.getCurrentTransform(tf);
        M3 R;
        V3 T;
        pose_at(m, t, &R, &T);
        for (int i = 0; i < 3; ++i) {
            worst = std::max(worst, std::fabs(tf.translation()[i] - T[size_t(i)]));
            for (int j = 0; j < 3; ++j) worst = std::max(worst, std::fabs(tf.linear()(i, j) - R[size_t(3 * i + j)]));
        }
    }
    return worst;
}

}  // namespace toc
