//! Batch queries: pqp_collide_batch, pqp_distance_batch, pqp_tolerance_batch, over the Rust API's
//! batches (`crate::query::collide_batch`, ...).
//!
//! The C layer checks the pointers and the C-only arguments, copies the n pose pairs into Rust
//! values (so that the worker threads share no raw pointer), lets the core check and answer them,
//! and copies the answers out only when every query has been answered: on any error nothing is
//! written.

#![allow(non_snake_case)] // R1, T1, R2, T2 keep PQP's names, which the header shows.

use super::{
    IN_C_CALL, PQP_ALL_CONTACTS, PQP_FIRST_CONTACT, PosedModel, deref, pqp_model, read_pose, status,
};
use crate::error::Error;
use crate::math::Pose;
use crate::model::Model;
use crate::query::{
    DistanceOptions, Search, Workers, collide_batch_with, distance_batch_with, tolerance_batch_with,
};
use std::ffi::{c_int, c_uint};

/// Answers the collision query of pqp_collide at each of n pose pairs of the same two models, on
/// several threads: `colliding[i]` is 1 if m1 at (R1 + 9 i, T1 + 3 i) and m2 at (R2 + 9 i, T2 + 3 i)
/// collide, else 0.
///
/// Poses are as for pqp_collide, one after the other: R1 holds n rotations of 9 doubles (query i
/// uses R1[9 i] to R1[9 i + 8]), T1 n translations of 3 doubles, and likewise R2 and T2. The
/// verdicts are those of n calls of pqp_collide; flag is checked as there, but since only the
/// verdict is returned every query stops at its first colliding pair, whatever the flag.
///
/// @param colliding  n ints to fill with 1 (colliding) or 0.
/// @param n          the number of queries; 0: nothing is read or written and PQP_OK is returned
///                   (every pointer may then be NULL).
/// @param R1, T1     n rotations (9 doubles each) and n translations (3 doubles each) of model 1.
/// @param m1         model 1 (built).
/// @param R2, T2     n rotations and n translations of model 2.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param flag       PQP_ALL_CONTACTS or PQP_FIRST_CONTACT (the same verdicts).
/// @param threads    the number of threads to answer on, the calling thread included: 0 for every
///                   available core (counted once per process); any value is valid and is capped
///                   to the available cores and to n. With 1 no thread is started.
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL (n > 0); PQP_ERR_INVALID_ARGUMENT
///         if flag is neither PQP_ALL_CONTACTS nor PQP_FIRST_CONTACT, or if n is too large for
///         R1 to be an array (9 n doubles beyond the address space); PQP_ERR_OUT_OF_MEMORY if the
///         batch's working storage (about 200 bytes per query) could not be allocated;
///         PQP_ERR_UNPROCESSED_MODEL if a model is not built; PQP_ERR_NONFINITE_POSE if an entry
///         of any of the n poses is NaN, infinite or larger than 1e150 in magnitude;
///         PQP_ERR_INTERNAL on an internal fault. Every argument and every pose is checked
///         before any query runs; on any error colliding is left unchanged.
/// Thread safety: any number of calls may use the same models at once; colliding must not be
///                used by another thread during the call.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_collide_batch(
    colliding: *mut c_int,
    n: usize,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    flag: c_int,
    threads: c_uint,
) -> c_int {
    let check = || match flag {
        PQP_ALL_CONTACTS | PQP_FIRST_CONTACT => Ok(()),
        _ => Err(Error::InvalidArgument),
    };
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        batch(
            colliding,
            n,
            (R1, T1, m1),
            (R2, T2, m2),
            check,
            |m1, m2, poses| {
                let answers = collide_batch_with(m1, m2, poses, workers(threads))?;
                Ok(answers.into_iter().map(c_int::from))
            },
        )
    }
}

/// Answers the distance query of pqp_distance at each of n pose pairs of the same two models, on
/// several threads: `distance[i]` is the separation distance of m1 at (R1 + 9 i, T1 + 3 i) and m2 at
/// (R2 + 9 i, T2 + 3 i), 0 where they touch or overlap.
///
/// Poses are laid out as for pqp_collide_batch. Each answer is, bit for bit, what pqp_distance with
/// a freshly created result returns for that pose pair (with the default search). Exact queries
/// (abs_err or rel_err 0) keep each thread's triangle cache and BVTT front from one pose to the next,
/// which cannot change an exact answer and makes consecutive nearby poses cheap; approximate ones
/// search each pose pair from the root, because where a search starts decides which answer within
/// the bounds it finds.
///
/// @param distance  n doubles to fill with the distances.
/// @param n         the number of queries; 0: nothing is read or written and PQP_OK is returned
///                  (every pointer may then be NULL).
/// @param R1, T1    n rotations (9 doubles each) and n translations (3 doubles each) of model 1.
/// @param m1        model 1 (built).
/// @param R2, T2    n rotations and n translations of model 2.
/// @param m2        model 2 (built; may be the same model as m1).
/// @param rel_err   relative error allowed, >= 0 (as for pqp_distance).
/// @param abs_err   absolute error allowed, >= 0 (0: exact).
/// @param threads   as for pqp_collide_batch (0: every available core).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL (n > 0); PQP_ERR_INVALID_ARGUMENT
///         if rel_err or abs_err is negative or NaN, or n is too large (as for
///         pqp_collide_batch); PQP_ERR_OUT_OF_MEMORY, PQP_ERR_UNPROCESSED_MODEL,
///         PQP_ERR_NONFINITE_POSE and PQP_ERR_INTERNAL as for pqp_collide_batch. Every argument
///         and every pose is checked before any query runs; on any error distance is left
///         unchanged.
/// Thread safety: as pqp_collide_batch.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_distance_batch(
    distance: *mut f64,
    n: usize,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    rel_err: f64,
    abs_err: f64,
    threads: c_uint,
) -> c_int {
    let options = DistanceOptions::approximate(rel_err, abs_err);
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        batch(
            distance,
            n,
            (R1, T1, m1),
            (R2, T2, m2),
            || Ok(()),
            |m1, m2, poses| distance_batch_with(m1, m2, poses, &options, workers(threads)),
        )
    }
}

/// Answers the tolerance query of pqp_tolerance at each of n pose pairs of the same two models, on
/// several threads: `closer[i]` is 1 if m1 at (R1 + 9 i, T1 + 3 i) and m2 at (R2 + 9 i, T2 + 3 i) are
/// within tolerance of each other, else 0.
///
/// Poses are laid out as for pqp_collide_batch; the verdicts are those of n calls of pqp_tolerance
/// (default search).
///
/// @param closer     n ints to fill with 1 (within the tolerance) or 0.
/// @param n          the number of queries; 0: nothing is read or written and PQP_OK is returned
///                   (every pointer may then be NULL).
/// @param R1, T1     n rotations (9 doubles each) and n translations (3 doubles each) of model 1.
/// @param m1         model 1 (built).
/// @param R2, T2     n rotations and n translations of model 2.
/// @param m2         model 2 (built; may be the same model as m1).
/// @param tolerance  the distance, >= 0 (+infinity is allowed).
/// @param threads    as for pqp_collide_batch (0: every available core).
/// @return PQP_OK; PQP_ERR_NULL_POINTER if any pointer is NULL (n > 0); PQP_ERR_INVALID_ARGUMENT
///         if tolerance is negative or NaN, or n is too large (as for pqp_collide_batch);
///         PQP_ERR_OUT_OF_MEMORY, PQP_ERR_UNPROCESSED_MODEL, PQP_ERR_NONFINITE_POSE and
///         PQP_ERR_INTERNAL as for pqp_collide_batch. Every argument and every pose is checked
///         before any query runs; on any error closer is left unchanged.
/// Thread safety: as pqp_collide_batch.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn pqp_tolerance_batch(
    closer: *mut c_int,
    n: usize,
    R1: *const f64,
    T1: *const f64,
    m1: *const pqp_model,
    R2: *const f64,
    T2: *const f64,
    m2: *const pqp_model,
    tolerance: f64,
    threads: c_uint,
) -> c_int {
    // SAFETY: every pointer argument is NULL or valid as the header requires of the caller.
    unsafe {
        batch(
            closer,
            n,
            (R1, T1, m1),
            (R2, T2, m2),
            || Ok(()),
            |m1, m2, poses| {
                let search = Search::default();
                let answers =
                    tolerance_batch_with(m1, m2, poses, tolerance, &search, workers(threads))?;
                Ok(answers.into_iter().map(c_int::from))
            },
        )
    }
}

/// The most queries a batch accepts: beyond it the 9 n doubles of R1 would not fit in the address
/// space (no C array can be that large), and n * 9 would overflow.
const MAX_QUERIES: usize = isize::MAX as usize / (9 * size_of::<f64>());

/// The workers of a batch from C: `threads` as asked, and each started thread marked as inside a C
/// call (see [`quietly`]).
pub(super) fn workers(threads: c_uint) -> Workers {
    Workers {
        threads: usize::try_from(threads).unwrap_or(usize::MAX),
        enter: quietly,
    }
}

/// Runs a batch's started thread as if inside the C call that started it: a panic there (a bug)
/// stays silent, as on the calling thread, and is resumed on the calling thread, whose boundary
/// turns it into PQP_ERR_INTERNAL.
fn quietly(work: &mut dyn FnMut()) {
    /// Restores the thread's flag however `work` ends.
    struct Restore(bool);
    impl Drop for Restore {
        fn drop(&mut self) {
            IN_C_CALL.with(|f| f.set(self.0));
        }
    }
    let _restore = Restore(IN_C_CALL.with(|f| f.replace(true)));
    work();
}

/// The body of the three batch entry points: inside the boundary, returns at once for n = 0; checks
/// the answer array, each posed model's pointers (as the single queries do, in their order), then
/// `check` (the C-only arguments) and n; copies the pose pairs; hands them to `run`, and writes its
/// answers to `out` when it succeeds.
///
/// # Safety
/// Every pointer is NULL or valid as the header requires: `out` n writable answers, each rotation
/// array 9 n doubles, each translation array 3 n doubles, the models live handles.
unsafe fn batch<T, A: IntoIterator<Item = T>>(
    out: *mut T,
    n: usize,
    (r1, t1, m1): PosedModel,
    (r2, t2, m2): PosedModel,
    check: impl FnOnce() -> Result<(), Error>,
    run: impl FnOnce(&Model, &Model, &[(Pose, Pose)]) -> Result<A, Error>,
) -> c_int {
    status(|| {
        if n == 0 {
            return Ok(());
        }
        let null = [r1, t1, r2, t2].iter().any(|p| p.is_null());
        if out.is_null() || null {
            return Err(Error::NullPointer);
        }
        // SAFETY: the models are NULL or live handles (this function's contract).
        let (m1, m2) = unsafe { (deref(m1)?, deref(m2)?) };
        check()?;
        if n > MAX_QUERIES {
            return Err(Error::InvalidArgument);
        }
        let mut poses = Vec::new();
        poses.try_reserve_exact(n).map_err(|_| Error::OutOfMemory)?;
        for i in 0..n {
            // SAFETY: the arrays hold n poses (this function's contract) and i < n; the offsets
            // fit in an isize because n <= MAX_QUERIES.
            let pair = unsafe {
                (
                    read_pose(r1.add(9 * i), t1.add(3 * i))?,
                    read_pose(r2.add(9 * i), t2.add(3 * i))?,
                )
            };
            poses.push(pair);
        }
        let answers = run(&m1.model, &m2.model, &poses)?;
        // SAFETY: `out` is not NULL, so it points to n writable answers (this function's
        // contract), which no other reference reaches during the call.
        let out = unsafe { std::slice::from_raw_parts_mut(out, n) };
        for (slot, answer) in out.iter_mut().zip(answers) {
            *slot = answer;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::capi::{PQP_ERR_INTERNAL, PQP_OK};
    use crate::query::answer_all;
    use std::cell::Cell;

    #[test]
    fn a_panic_in_a_started_thread_is_silent_and_becomes_internal() {
        let main = std::thread::current().id();
        let code = status(|| {
            answer_all(
                200,
                workers(2),
                || (),
                |_, _| {
                    // Every thread of the batch is marked, so the quiet hook stays silent.
                    assert!(IN_C_CALL.with(Cell::get));
                    std::thread::sleep(std::time::Duration::from_micros(100));
                    if std::thread::current().id() != main {
                        panic!("worker bug");
                    }
                    Ok(0u8)
                },
            )
            .map(|_| ())
        });
        let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
        assert_eq!(code, if cores >= 2 { PQP_ERR_INTERNAL } else { PQP_OK });
        assert!(!IN_C_CALL.with(Cell::get));
    }

    #[test]
    fn the_flag_is_restored() {
        quietly(&mut || assert!(IN_C_CALL.with(Cell::get)));
        assert!(!IN_C_CALL.with(Cell::get));
    }
}
