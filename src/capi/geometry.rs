//! Distances between single triangles and between single segments: the exact kernels of
//! [`crate::geometry`] for C, and what PQP 1.3's `TriDist.h` (`TriDist`, `SegPoints`) wraps.

use super::{read_doubles, status};
use crate::error::{Error, MAX_COORDINATE};
use crate::geometry::{ClosestPoints, Tri, segment_segment_dir, tri_distance};
use crate::math::Vec3;
use std::ffi::c_int;

/// `Err(NonFiniteCoordinate)` unless every value is finite and at most [`MAX_COORDINATE`] in
/// magnitude (the limit every other coordinate of the C ABI has).
fn check_coordinates(values: &[f64]) -> Result<(), Error> {
    if values
        .iter()
        .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE)
    {
        Ok(())
    } else {
        Err(Error::NonFiniteCoordinate)
    }
}

/// A triangle from 9 doubles, vertex by vertex.
fn triangle(v: &[f64; 9]) -> Tri {
    [
        Vec3::new(v[0], v[1], v[2]),
        Vec3::new(v[3], v[4], v[5]),
        Vec3::new(v[6], v[7], v[8]),
    ]
}

/// Writes an answer to C's three outputs, after every input has been read (so that outputs may
/// overlap inputs).
///
/// # Safety
/// Each pointer is non-NULL and writable: `distance` one double, `p` and `q` three each.
unsafe fn write_answer(c: &ClosestPoints, distance: *mut f64, p: *mut f64, q: *mut f64) {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        distance.write_unaligned(c.distance);
        p.cast::<[f64; 3]>().write_unaligned([c.p.x, c.p.y, c.p.z]);
        q.cast::<[f64; 3]>().write_unaligned([c.q.x, c.q.y, c.q.z]);
    }
}

/// `Err(NullPointer)` if any output pointer is NULL.
fn check_outputs(distance: *mut f64, p: *mut f64, q: *mut f64) -> Result<(), Error> {
    if distance.is_null() || p.is_null() || q.is_null() {
        Err(Error::NullPointer)
    } else {
        Ok(())
    }
}

/// Computes the distance between two triangles and a closest pair of points, exactly (PQP 1.3's
/// TriDist, which TriDist.h wraps).
///
/// Exact means: the distance is 0 exactly when the triangles share a point (intersect or touch),
/// and otherwise correct to a few roundings of the triangles' size, also in the near-degenerate
/// configurations where PQP 1.3's routine could be far off. When the triangles share a point, p
/// and q are the same point, common to both (to rounding). A degenerate triangle (collinear or
/// repeated vertices) counts as the segment or point it spans. Coordinates of any magnitude up to
/// 1e150 (subnormals included) are answered as exactly as at unit scale.
///
/// @param distance  where the distance is written (1 double).
/// @param p         where the closest point on triangle s is written (3 doubles).
/// @param q         where the closest point on triangle t is written (3 doubles).
/// @param s         the first triangle: 9 doubles, its three vertices one after the other (x, y, z
///                  of each), as PQP's `double s[3][3]` (pass `&s[0][0]`).
/// @param t         the second triangle, likewise.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_NONFINITE_COORDINATE if a
///         coordinate is NaN, infinite or larger than 1e150 in magnitude; PQP_ERR_INTERNAL on an
///         internal fault. On an error nothing is written. The outputs may overlap the inputs.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_triangle_distance(
    distance: *mut f64,
    p: *mut f64,
    q: *mut f64,
    s: *const f64,
    t: *const f64,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let s: [f64; 9] = read_doubles(s)?;
            let t: [f64; 9] = read_doubles(t)?;
            check_outputs(distance, p, q)?;
            check_coordinates(&s)?;
            check_coordinates(&t)?;
            let c = tri_distance(&triangle(&s), &triangle(&t));
            write_answer(&c, distance, p, q);
            Ok(())
        })
    }
}

/// Computes the distance between two segments and a closest pair of points (the closest points of
/// PQP 1.3's SegPoints, which TriDist.h wraps).
///
/// Each segment is given as PQP gives it, by a start point and a direction vector: the first is
/// the points a + u da for u in [0, 1], the second b + v db for v in [0, 1]. Either direction may
/// be zero (the segment is then a point). The distance is correct to a few roundings of the
/// segments' size, also for parallel and nearly parallel segments (then one of the closest pairs
/// is given). Coordinates of any magnitude up to 1e150 are answered as exactly as at unit scale.
///
/// @param distance  where the distance is written (1 double).
/// @param x         where the closest point on the first segment is written (3 doubles).
/// @param y         where the closest point on the second segment is written (3 doubles).
/// @param a, da     the first segment's start and direction (3 doubles each).
/// @param b, db     the second segment's start and direction (3 doubles each).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL; PQP_ERR_NONFINITE_COORDINATE if a
///         coordinate is NaN, infinite or larger than 1e150 in magnitude; PQP_ERR_INTERNAL on an
///         internal fault. On an error nothing is written. The outputs may overlap the inputs.
/// Thread safety: may be called from any thread at any time.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_segment_distance(
    distance: *mut f64,
    x: *mut f64,
    y: *mut f64,
    a: *const f64,
    da: *const f64,
    b: *const f64,
    db: *const f64,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        status(|| {
            let inputs: [[f64; 3]; 4] = [
                read_doubles(a)?,
                read_doubles(da)?,
                read_doubles(b)?,
                read_doubles(db)?,
            ];
            check_outputs(distance, x, y)?;
            for v in &inputs {
                check_coordinates(v)?;
            }
            let [a, da, b, db] = inputs.map(Vec3::from);
            let c = segment_segment_dir(&a, &da, &b, &db);
            write_answer(&c, distance, x, y);
            Ok(())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::capi::{PQP_ERR_NONFINITE_COORDINATE, PQP_ERR_NULL_POINTER, PQP_OK};
    use std::ptr;

    const S: [f64; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

    /// pqp_triangle_distance's answer, or its error code.
    fn tri(s: &[f64; 9], t: &[f64; 9]) -> Result<(f64, [f64; 3], [f64; 3]), c_int> {
        let (mut d, mut p, mut q) = (f64::NAN, [f64::NAN; 3], [f64::NAN; 3]);
        // SAFETY: every pointer is to a live local array of the length the function reads or writes.
        let rc = unsafe {
            pqp_triangle_distance(
                &mut d,
                p.as_mut_ptr(),
                q.as_mut_ptr(),
                s.as_ptr(),
                t.as_ptr(),
            )
        };
        if rc == PQP_OK { Ok((d, p, q)) } else { Err(rc) }
    }

    /// pqp_segment_distance's answer, or its error code.
    fn seg(v: [[f64; 3]; 4]) -> Result<(f64, [f64; 3], [f64; 3]), c_int> {
        let (mut d, mut x, mut y) = (f64::NAN, [f64::NAN; 3], [f64::NAN; 3]);
        // SAFETY: every pointer is to a live local array of the length the function reads or writes.
        let rc = unsafe {
            pqp_segment_distance(
                &mut d,
                x.as_mut_ptr(),
                y.as_mut_ptr(),
                v[0].as_ptr(),
                v[1].as_ptr(),
                v[2].as_ptr(),
                v[3].as_ptr(),
            )
        };
        if rc == PQP_OK { Ok((d, x, y)) } else { Err(rc) }
    }

    #[test]
    fn triangles_above_and_through_each_other() {
        // A triangle 2 above s, over its interior: the closest points are straight below.
        let t = [0.25, 0.25, 2.0, 3.0, 0.25, 2.0, 0.25, 3.0, 2.0];
        assert_eq!(tri(&S, &t), Ok((2.0, [0.25, 0.25, 0.0], [0.25, 0.25, 2.0])));
        // Piercing s: distance 0 and one common point.
        let t = [0.25, 0.25, -1.0, 0.25, 0.25, 1.0, 5.0, 5.0, 1.0];
        // They share the segment from (1/4, 1/4, 0) to (1/2, 1/2, 0).
        let (d, p, q) = tri(&S, &t).unwrap();
        assert_eq!((d, p), (0.0, q));
        assert!(
            p[2] == 0.0 && p[0] == p[1] && (0.25..=0.5).contains(&p[0]),
            "{p:?}"
        );
        // A point (a triangle with three equal vertices) against s.
        let t = [0.5, -2.0, 0.0, 0.5, -2.0, 0.0, 0.5, -2.0, 0.0];
        assert_eq!(tri(&S, &t), Ok((2.0, [0.5, 0.0, 0.0], [0.5, -2.0, 0.0])));
    }

    #[test]
    fn triangle_errors_write_nothing() {
        let mut bad = S;
        for v in [f64::NAN, f64::INFINITY, -1.5e150] {
            bad[4] = v;
            assert_eq!(tri(&bad, &S), Err(PQP_ERR_NONFINITE_COORDINATE));
            assert_eq!(tri(&S, &bad), Err(PQP_ERR_NONFINITE_COORDINATE));
        }
        bad[4] = -1e150;
        assert!(tri(&bad, &S).is_ok());
        let (mut d, mut p, mut q) = (7.0, [7.0; 3], [7.0; 3]);
        let (dp, pp, qp) = (&mut d as *mut f64, p.as_mut_ptr(), q.as_mut_ptr());
        let s = S.as_ptr();
        // SAFETY: every pointer is NULL (the case under test) or to a live local of the right length.
        unsafe {
            assert_eq!(
                pqp_triangle_distance(ptr::null_mut(), pp, qp, s, s),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_triangle_distance(dp, ptr::null_mut(), qp, s, s),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_triangle_distance(dp, pp, ptr::null_mut(), s, s),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_triangle_distance(dp, pp, qp, ptr::null(), s),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_triangle_distance(dp, pp, qp, s, ptr::null()),
                PQP_ERR_NULL_POINTER
            );
        }
        assert_eq!((d, p, q), (7.0, [7.0; 3], [7.0; 3]));
    }

    #[test]
    fn segments_as_start_and_direction() {
        // Crossing at (1, 0, 0) one above the other: u = 1/2 on the first, v = 1/4 on the second.
        let r = seg([
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, -1.0, 3.0],
            [0.0, 4.0, 0.0],
        ]);
        assert_eq!(r, Ok((3.0, [1.0, 0.0, 0.0], [1.0, 0.0, 3.0])));
        // A zero direction is a point; the far end is start + direction.
        let r = seg([[0.0, 0.0, 0.0], [0.0; 3], [3.0, 4.0, 0.0], [-3.0, 0.0, 0.0]]);
        assert_eq!(r, Ok((4.0, [0.0; 3], [0.0, 4.0, 0.0])));
        // Huge and tiny scales answer as unit scale does (powers of two, which scale every
        // rounding exactly).
        for k in [2f64.powi(460), 2f64.powi(-990)] {
            let r = seg([
                [0.0; 3],
                [2.0 * k, 0.0, 0.0],
                [k, -k, 3.0 * k],
                [0.0, 4.0 * k, 0.0],
            ]);
            assert_eq!(r, Ok((3.0 * k, [k, 0.0, 0.0], [k, 0.0, 3.0 * k])));
        }
    }

    #[test]
    fn segment_errors_write_nothing() {
        let ok = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        for i in 0..4 {
            for v in [f64::NAN, f64::NEG_INFINITY, 2e150] {
                let mut bad = ok;
                bad[i][2] = v;
                assert_eq!(seg(bad), Err(PQP_ERR_NONFINITE_COORDINATE));
            }
        }
        let (mut d, mut x, mut y) = (7.0, [7.0; 3], [7.0; 3]);
        let (dp, xp, yp) = (&mut d as *mut f64, x.as_mut_ptr(), y.as_mut_ptr());
        let v = ok[0].as_ptr();
        let n = ptr::null::<f64>();
        // SAFETY: every pointer is NULL (the case under test) or to a live local of the right length.
        unsafe {
            let m = ptr::null_mut::<f64>();
            assert_eq!(
                pqp_segment_distance(m, xp, yp, v, v, v, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, m, yp, v, v, v, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, xp, m, v, v, v, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, xp, yp, n, v, v, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, xp, yp, v, n, v, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, xp, yp, v, v, n, v),
                PQP_ERR_NULL_POINTER
            );
            assert_eq!(
                pqp_segment_distance(dp, xp, yp, v, v, v, n),
                PQP_ERR_NULL_POINTER
            );
        }
        assert_eq!((d, x, y), (7.0, [7.0; 3], [7.0; 3]));
    }
}
