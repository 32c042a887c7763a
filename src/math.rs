//! Vectors, matrices and poses.

use crate::error::{Error, MAX_COORDINATE};
use nalgebra::{Matrix3, Vector3};

/// A 3-vector of `f64`.
pub type Vec3 = Vector3<f64>;
/// A 3x3 matrix of `f64`.
pub type Mat3 = Matrix3<f64>;

/// The absolute part of every rounding allowance of a bound or an overlap test, added to the part
/// relative to the magnitudes involved. Below about 1e-154 the squares of lengths are subnormal or
/// zero, so a volume fitted to tiny points, or a length computed as the root of a sum of squares,
/// may be off by up to about 1e-161 whatever the magnitudes: this covers it many times over. In
/// scenes of ordinary size it changes no bound (it is below their rounding); a scene whose
/// coordinates are all below about 1e-135 is answered as exactly, but its volumes prune less, down
/// to none below 1e-150.
pub(crate) const UNDERFLOW_SLACK: f64 = 1e-150;

/// The frame with first axes `a0`, `a1` and third `a0 x a1`. The hierarchy stores only the first
/// two axes of a frame, and recovers the third through this function, bit for bit as the build
/// computed it.
#[inline(always)]
pub(crate) fn frame_from(a0: &Vec3, a1: &Vec3) -> Mat3 {
    // Entry by entry (row-major arguments): built in place, where `from_columns` goes through a
    // copy.
    let c = a0.cross(a1);
    Mat3::new(a0.x, a1.x, c.x, a0.y, a1.y, c.y, a0.z, a1.z, c.z)
}

/// Where a model is in the world: `x_world = rotation * x_model + translation`.
///
/// As in PQP, the columns of `rotation` are the model's axes in world coordinates. The rotation is
/// used as given (it is not re-orthonormalised); give a proper rotation for meaningful answers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Rotation matrix (model axes as columns).
    pub rotation: Mat3,
    /// Translation of the model's origin.
    pub translation: Vec3,
}

impl Default for Pose {
    fn default() -> Self {
        Pose::identity()
    }
}

impl Pose {
    /// The identity pose.
    pub fn identity() -> Pose {
        Pose {
            rotation: Mat3::identity(),
            translation: Vec3::zeros(),
        }
    }

    /// A pose from PQP's arrays: `r` row by row, and `t`.
    ///
    /// ```
    /// let pose = pqp::Pose::new([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], [0.0, 0.0, 2.0]);
    /// assert_eq!(pose.translation.z, 2.0);
    /// ```
    pub fn new(r: [[f64; 3]; 3], t: [f64; 3]) -> Pose {
        Pose {
            rotation: Mat3::new(
                r[0][0], r[0][1], r[0][2], r[1][0], r[1][1], r[1][2], r[2][0], r[2][1], r[2][2],
            ),
            translation: Vec3::new(t[0], t[1], t[2]),
        }
    }

    /// A pure translation.
    pub fn from_translation(t: [f64; 3]) -> Pose {
        Pose {
            rotation: Mat3::identity(),
            translation: Vec3::new(t[0], t[1], t[2]),
        }
    }

    /// Maps a point from model coordinates to world coordinates.
    pub fn transform_point(&self, p: &Vec3) -> Vec3 {
        self.rotation * p + self.translation
    }

    /// `Err(NonFinitePose)` unless every entry is finite and not above [`MAX_COORDINATE`].
    pub fn validate(&self) -> Result<(), Error> {
        // Without short circuits (a NaN fails the comparison): vector comparisons, no branches.
        let ok = self
            .rotation
            .iter()
            .chain(self.translation.iter())
            .fold(true, |ok, v| ok & (v.abs() <= MAX_COORDINATE));
        if ok {
            Ok(())
        } else {
            Err(Error::NonFinitePose)
        }
    }
}

/// The pose of frame B in frame A: `x_A = rot * x_B + trans`.
///
/// Queries work in model 1's frame: model 2's volumes and triangles are brought there with the
/// relative pose `R1^T R2, R1^T (T2 - T1)`, so the world frame never appears in the inner loops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelPose {
    /// Rotation from B to A.
    pub rot: Mat3,
    /// Translation from B to A.
    pub trans: Vec3,
}

impl RelPose {
    /// The pose of model 2's frame in model 1's frame.
    pub fn between(pose1: &Pose, pose2: &Pose) -> RelPose {
        let r1t = pose1.rotation.transpose();
        RelPose {
            rot: r1t * pose2.rotation,
            trans: r1t * (pose2.translation - pose1.translation),
        }
    }

    /// The identity.
    pub fn identity() -> RelPose {
        RelPose {
            rot: Mat3::identity(),
            trans: Vec3::zeros(),
        }
    }

    /// Maps a point of frame B into frame A.
    #[inline]
    pub fn apply(&self, p: &Vec3) -> Vec3 {
        self.rot * p + self.trans
    }

    /// Maps a point of frame A back into frame B (the rotation is taken as orthonormal).
    #[inline]
    pub fn apply_inverse(&self, p: &Vec3) -> Vec3 {
        self.rot.tr_mul(&(p - self.trans))
    }
}

/// The smaller of two numbers, as a select (for operands that are never NaN: cheaper than
/// `f64::min`, which must order NaN).
#[inline(always)]
pub(crate) fn least(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// The larger of two numbers, as a select (for operands that are never NaN: cheaper than
/// `f64::max`).
#[inline(always)]
pub(crate) fn most(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

/// Asks the processor to bring the cache line holding address `p` into the cache: a hint, which
/// reads nothing into the program and cannot fault, whatever `p` is (nothing on other
/// architectures, nor under Miri). The one prefetch every search and the build use.
#[inline(always)]
pub(crate) fn prefetch_line(p: *const u8) {
    #[cfg(all(target_arch = "x86_64", not(miri)))]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE, which `_mm_prefetch` needs, is part of every x86_64 processor; a prefetch
        // has no effect on memory and does not fault, even for an address outside the program's.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(p.cast::<i8>()) };
    }
    #[cfg(not(all(target_arch = "x86_64", not(miri))))]
    let _ = p;
}

/// Whether the distance search may run its copies compiled for AVX2 (x86-64 processors since
/// about 2013; the check is a cached flag). Those copies do the same IEEE operations in the same
/// order as the portable ones (Rust never fuses a multiply and an add on its own), so every answer
/// and count is bit for bit the same either way; they only take fewer instructions (three-operand
/// forms, fewer register copies and spills).
#[inline(always)]
pub(crate) fn use_avx2() -> bool {
    #[cfg(test)]
    if PORTABLE_ONLY.with(std::cell::Cell::get) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Runs `f` in a copy compiled for AVX2 when [`use_avx2`] says so, else in a portable copy:
/// each a function of its own (never inlined: one copy of a kernel serves all its callers), into
/// which `f`, and what it inlines, is inlined.
#[inline(always)]
pub(crate) fn avx2_or_portable<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if use_avx2() {
        // SAFETY: the processor has AVX2.
        return unsafe { in_avx2(f) };
    }
    in_portable(f)
}

/// See [`avx2_or_portable`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline(never)]
fn in_avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// See [`avx2_or_portable`].
#[inline(never)]
fn in_portable<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(test)]
thread_local! {
    static PORTABLE_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` on this thread with the portable copies only (see [`use_avx2`]), to compare them with
/// the others.
#[cfg(test)]
pub(crate) fn portable_only<R>(f: impl FnOnce() -> R) -> R {
    PORTABLE_ONLY.with(|p| p.set(true));
    let r = f();
    PORTABLE_ONLY.with(|p| p.set(false));
    r
}

/// How far a matrix may be from orthonormal and still be taken as a rotation by
/// [`nearest_rotation`]: each of its singular values within this of 1. Rotations written with 6
/// significant digits (the shared `.path` files) are within 1e-6 (torus1.path: 9.5e-7 at most).
pub const ROTATION_TOLERANCE: f64 = 1e-6;

/// The proper rotation nearest to `m` (its orthonormal polar factor `U V^T`, from the singular
/// value decomposition `m = U S V^T`), or `Err(InvalidArgument)` unless `m` is a rotation to
/// within [`ROTATION_TOLERANCE`]: every singular value within that of 1, and a positive
/// determinant (a reflection is refused). `m` is taken finite.
pub fn nearest_rotation(m: &Mat3) -> Result<Mat3, Error> {
    let svd = m.svd(true, true);
    let orthonormal = svd
        .singular_values
        .iter()
        .all(|s| (s - 1.0).abs() <= ROTATION_TOLERANCE);
    match (svd.u, svd.v_t) {
        (Some(u), Some(v_t)) if orthonormal && m.determinant() > 0.0 => Ok(u * v_t),
        _ => Err(Error::InvalidArgument),
    }
}

/// The rotation by `angle` (radians, right-handed) about the unit vector `axis` (Rodrigues'
/// formula).
pub fn axis_angle_rotation(axis: &Vec3, angle: f64) -> Mat3 {
    let k = axis.cross_matrix();
    let (s, c) = angle.sin_cos();
    Mat3::identity() + k * s + k * k * (1.0 - c)
}

/// How close to pi (in radians) a turn is taken as a half turn by [`rotation_log`]: a relative
/// turn given as exactly pi comes out of the projections and products of its rotations within a
/// few 1e-16 of it, on either side, so which way is shorter is the rounding's choice.
pub const HALF_TURN_TOLERANCE: f64 = 1e-12;

/// The logarithm of a rotation `q` as a unit axis and an angle in `[0, pi]`, the shorter way:
/// `q = axis_angle_rotation(axis, angle)`. A turn within [`HALF_TURN_TOLERANCE`] of pi is a half
/// turn (both ways are as short): its angle is `pi` (the double nearest to it) and its axis the one
/// whose largest-magnitude component is positive (when several components are equal in magnitude
/// to within [`HALF_TURN_TOLERANCE`], the first of them: x before y before z). For angle 0 the axis
/// is the x axis.
pub fn rotation_log(q: &Mat3) -> (Vec3, f64) {
    // The skew part of q is sin(angle) [axis]x, its trace 1 + 2 cos(angle).
    let w = 0.5 * Vec3::new(q.m32 - q.m23, q.m13 - q.m31, q.m21 - q.m12);
    let c = (0.5 * (q.trace() - 1.0)).clamp(-1.0, 1.0);
    let s = w.norm();
    let angle = s.atan2(c);
    if s == 0.0 && c > 0.0 {
        return (Vec3::x(), 0.0);
    }
    if c > 0.0 {
        // Below pi/2 the skew part is well conditioned.
        return (w / s, angle);
    }
    // Near pi sin(angle) vanishes; the symmetric part (q + q^T)/2 = c I + (1 - c) axis axis^T gives
    // the axis up to sign through its column of largest diagonal entry, and the skew part gives
    // the sign, unless the turn is a half turn to within the tolerance (|w| = sin(pi - angle)).
    let a = (0.5 * (q + q.transpose()) - Mat3::identity() * c) / (1.0 - c);
    let j = (0..3)
        .max_by(|&i, &k| a[(i, i)].total_cmp(&a[(k, k)]).then(k.cmp(&i)))
        .unwrap_or(0);
    let mut axis = a.column(j).into_owned();
    axis /= axis.norm();
    if s <= HALF_TURN_TOLERANCE {
        // The documented half turn: the first component within the tolerance of the largest
        // magnitude is made positive.
        let m = axis.amax();
        let k = (0..3)
            .find(|&k| axis[k].abs() >= m - HALF_TURN_TOLERANCE)
            .unwrap_or(0);
        if axis[k] < 0.0 {
            axis = -axis;
        }
        return (axis, std::f64::consts::PI);
    }
    if axis.dot(&w) < 0.0 {
        axis = -axis;
    }
    (axis, angle)
}

/// A rotation turning at constant angular velocity about a fixed axis from `start` (at t = 0) to
/// `end` (at t = 1), the shorter way: `R(t) = start exp(t log(start^T end))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RotationPath {
    /// The rotation at t = 0 (projected to the nearest rotation).
    pub start: Mat3,
    /// The axis of the relative turn, in `start`'s frame (unit).
    pub axis: Vec3,
    /// The angle of the relative turn, in `[0, pi]`: the angular speed.
    pub angle: f64,
}

impl RotationPath {
    /// The path from `start` to `end`, each first projected to its [`nearest_rotation`];
    /// `Err(InvalidArgument)` if either is not a rotation to within [`ROTATION_TOLERANCE`]. A
    /// relative turn of pi (to within [`HALF_TURN_TOLERANCE`]) turns as [`rotation_log`] says:
    /// right-handed by +pi about the axis, in `start`'s frame, whose largest-magnitude component is
    /// positive.
    pub fn new(start: &Mat3, end: &Mat3) -> Result<RotationPath, Error> {
        let (start, end) = (nearest_rotation(start)?, nearest_rotation(end)?);
        let (axis, angle) = rotation_log(&(start.transpose() * end));
        Ok(RotationPath { start, axis, angle })
    }

    /// The rotation at time `t`.
    pub fn at(&self, t: f64) -> Mat3 {
        self.start * axis_angle_rotation(&self.axis, t * self.angle)
    }
}
