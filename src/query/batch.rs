//! Batch queries: the same two models at each of many pose pairs (a motion planner's loop), answered
//! on several threads at once.
//!
//! Every argument is checked before any query runs, with the codes and in the order of the single
//! queries, so that a batch either answers every pose pair or fails without answering. The poses are
//! then split into one run of consecutive pose pairs per thread; a thread answers its run from the
//! front, and one that finishes early takes the back half of what another has not yet started
//! (work stealing), so that threads finish together even when the cost of a query varies along the
//! batch. Each thread keeps its own result object, whose triangle cache (and, for exact distance,
//! BVTT front) carries over from one pose to the next, as it would for a caller reusing one result
//! for a sequence of single queries: long runs of consecutive poses keep that carry-over, so that a
//! batch along a motion path does no more work than the single calls (a thread meets a pose far
//! from its last one only when it starts and when it steals).
//!
//! The threads are scoped std threads, started per batch: a batch is one fork-join over a slice,
//! which they express directly (the threads borrow the models, the poses and disjoint answer
//! slices), and starting one costs tens of microseconds against milliseconds of queries.

use super::{
    CollideResult, ContactMode, DistanceOptions, DistanceResult, Search, ToleranceResult,
    collide_into, distance_into, tolerance_into,
};
use crate::error::Error;
use crate::math::Pose;
use crate::model::Model;
use std::panic::{self, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, OnceLock, PoisonError};

/// Whether `m1` at `poses[i].0` and `m2` at `poses[i].1` collide, for each `i`: the verdict of
/// [`collide`](super::collide) at each pose pair (a batch stops at the first contact of each pair,
/// which decides the verdict).
///
/// `threads` is the number of threads to answer on, the calling thread included: 0 for all
/// available cores ([`std::thread::available_parallelism`], asked once per process); any value is
/// valid, and it is capped to the available cores and to the number of pose pairs. With 1 the
/// batch runs on the calling thread alone.
///
/// Checked first, as [`collide`](super::collide) checks them: both models built
/// (`Err(UnprocessedModel)`), then every pose (`Err(NonFinitePose)`). An empty `poses` answers an
/// empty vector after these checks. A panic in a worker thread (a bug) is resumed on the calling
/// thread.
///
/// ```
/// use pqp::{collide_batch, Model, Pose};
/// let tri = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0);
/// let a = Model::from_triangles([tri]).unwrap();
/// let poses: Vec<(Pose, Pose)> = [0.0, 0.5, 2.0]
///     .iter()
///     .map(|&x| (Pose::identity(), Pose::from_translation([x, 0.0, 0.0])))
///     .collect();
/// assert_eq!(collide_batch(&a, &a, &poses, 0).unwrap(), [true, true, false]);
/// ```
pub fn collide_batch(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    threads: usize,
) -> Result<Vec<bool>, Error> {
    collide_batch_with(m1, m2, poses, Workers::plain(threads))
}

/// The separation distance of `m1` at `poses[i].0` and `m2` at `poses[i].1`, for each `i` (0 where
/// they touch or overlap): the `distance` of [`distance`](super::distance) at each pose pair.
///
/// The answers are those of one fresh [`DistanceResult`] per pose pair, bit for bit. An exact query
/// (`abs_err` or `rel_err` 0) reuses each thread's result from one pose to the next with
/// `options.search` as given (triangle cache and front), which cannot change an exact distance; an
/// approximate one searches each pose pair afresh (as with `search.triangle_cache` off), because
/// where a search starts decides which answer within the error bounds it returns.
///
/// `threads` as for [`collide_batch`]. Checked first, as [`distance`](super::distance) checks them:
/// the options (`Err(InvalidArgument)`), both models built, then every pose.
pub fn distance_batch(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    options: &DistanceOptions,
    threads: usize,
) -> Result<Vec<f64>, Error> {
    distance_batch_with(m1, m2, poses, options, Workers::plain(threads))
}

/// Whether `m1` at `poses[i].0` and `m2` at `poses[i].1` are within `tolerance` (>= 0) of each
/// other, for each `i`: the verdict of [`tolerance`](super::tolerance) at each pose pair.
///
/// `threads` as for [`collide_batch`]. Checked first, as [`tolerance`](super::tolerance) checks
/// them: the tolerance and the search (`Err(InvalidArgument)`), both models built, then every pose.
pub fn tolerance_batch(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    tolerance: f64,
    search: &Search,
    threads: usize,
) -> Result<Vec<bool>, Error> {
    tolerance_batch_with(m1, m2, poses, tolerance, search, Workers::plain(threads))
}

/// How many threads a batch asks for, and how each thread it starts runs its work.
#[derive(Clone, Copy)]
pub(crate) struct Workers {
    /// Threads asked for: 0 for all available cores.
    pub(crate) threads: usize,
    /// Runs a started thread's work: the C ABI passes one that marks the thread as inside a C call,
    /// so that a panic there stays silent as on the calling thread.
    pub(crate) enter: fn(&mut dyn FnMut()),
}

impl Workers {
    /// Threads that just run their work (the Rust API).
    pub(crate) fn plain(threads: usize) -> Workers {
        Workers {
            threads,
            enter: |work| work(),
        }
    }

    /// The threads to run on for `n` queries: as asked (all cores for 0), at most the available
    /// cores and `n`, at least 1.
    fn count(self, n: usize) -> usize {
        if n <= 1 || self.threads == 1 {
            return 1;
        }
        let cores = cores();
        let asked = if self.threads == 0 {
            cores
        } else {
            self.threads.min(cores)
        };
        asked.min(n).max(1)
    }
}

/// The available cores ([`std::thread::available_parallelism`]), asked once per process: the
/// question reads the scheduler's affinity and the cgroup's quota (about 0.1 ms, more than many
/// queries take).
fn cores() -> usize {
    static CORES: OnceLock<usize> = OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |c| c.get()))
}

/// [`collide_batch`] with the C ABI's choice of workers.
pub(crate) fn collide_batch_with(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    workers: Workers,
) -> Result<Vec<bool>, Error> {
    check_poses(m1, m2, poses)?;
    answer_all(poses.len(), workers, CollideResult::new, |r, i| {
        let (p1, p2) = &poses[i];
        collide_into(r, m1, p1, m2, p2, ContactMode::First)?;
        Ok(r.colliding())
    })
}

/// [`distance_batch`] with the C ABI's choice of workers.
pub(crate) fn distance_batch_with(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    options: &DistanceOptions,
    workers: Workers,
) -> Result<Vec<f64>, Error> {
    options.validate()?;
    check_poses(m1, m2, poses)?;
    let exact = options.abs_err == 0.0 || options.rel_err == 0.0;
    let mut options = *options;
    if !exact {
        // A result's cache and front are used only with triangle caching: off, each search starts
        // from the root, as a fresh result's does.
        options.search.triangle_cache = false;
    }
    answer_all(poses.len(), workers, DistanceResult::new, |r, i| {
        let (p1, p2) = &poses[i];
        distance_into(r, m1, p1, m2, p2, &options)?;
        Ok(r.distance)
    })
}

/// [`tolerance_batch`] with the C ABI's choice of workers.
pub(crate) fn tolerance_batch_with(
    m1: &Model,
    m2: &Model,
    poses: &[(Pose, Pose)],
    tolerance: f64,
    search: &Search,
    workers: Workers,
) -> Result<Vec<bool>, Error> {
    if tolerance.is_nan() || tolerance < 0.0 {
        return Err(Error::InvalidArgument);
    }
    search.validate()?;
    check_poses(m1, m2, poses)?;
    answer_all(poses.len(), workers, ToleranceResult::new, |r, i| {
        let (p1, p2) = &poses[i];
        tolerance_into(r, m1, p1, m2, p2, tolerance, search)?;
        Ok(r.closer_than_tolerance)
    })
}

/// What every query checks after its own arguments: both models built, then each pose, pair by
/// pair (the first failing pose pair decides the code, as its single query would).
fn check_poses(m1: &Model, m2: &Model, poses: &[(Pose, Pose)]) -> Result<(), Error> {
    m1.check_built()?;
    m2.check_built()?;
    poses.iter().try_for_each(|(p1, p2)| {
        p1.validate()?;
        p2.validate()
    })
}

/// Answers queries `0..n` on the threads `workers` gives: `answer(state, i)` is query `i`'s
/// answer, `state` the calling thread's own (made by `new_state`, once per thread). The calling
/// thread works too, so a batch on one thread starts none.
///
/// Returns the answers in query order, or the first error an answer returned (none is expected:
/// the batch's arguments were checked). A panic in any thread is resumed on the calling thread
/// after every thread has stopped; the others stop at their next chunk.
pub(crate) fn answer_all<S, T>(
    n: usize,
    workers: Workers,
    new_state: impl Fn() -> S + Sync,
    answer: impl Fn(&mut S, usize) -> Result<T, Error> + Sync,
) -> Result<Vec<T>, Error>
where
    T: Copy + Default + Send,
{
    let mut out = Vec::new();
    out.try_reserve_exact(n).map_err(|_| Error::OutOfMemory)?;
    out.resize(n, T::default());
    let threads = workers.count(n);
    let shares = Shares::new(&mut out, threads);
    let work = |me: usize| -> Result<(), Error> {
        let mut state = new_state();
        while let Some((first, slots)) = shares.next(me) {
            for (k, slot) in slots.iter_mut().enumerate() {
                *slot = answer(&mut state, first + k)?;
            }
        }
        Ok(())
    };
    // Any panic stops the other threads at their next chunk, then is resumed here.
    let guarded = |me: usize| {
        panic::catch_unwind(AssertUnwindSafe(|| work(me))).inspect_err(|_| {
            shares.stop.store(true, Ordering::Relaxed);
        })
    };
    let outcomes = std::thread::scope(|s| {
        let started: Vec<_> = (1..threads)
            .map(|me| {
                let guarded = &guarded;
                s.spawn(move || {
                    let mut outcome = None;
                    (workers.enter)(&mut || outcome = Some(guarded(me)));
                    outcome
                })
            })
            .collect();
        let mut outcomes = vec![guarded(0)];
        for t in started {
            // `guarded` catches every panic, so a thread ends normally with its outcome.
            match t.join() {
                Ok(Some(outcome)) => outcomes.push(outcome),
                // `enter` did not run the work: a bug of the C layer's `enter`.
                Ok(None) => outcomes.push(Ok(Err(Error::Internal))),
                Err(payload) => outcomes.push(Err(payload)),
            }
        }
        outcomes
    });
    let mut first_error = Ok(());
    for outcome in outcomes {
        match outcome {
            Err(payload) => panic::resume_unwind(payload),
            Ok(Err(e)) if first_error.is_ok() => first_error = Err(e),
            Ok(_) => {}
        }
    }
    first_error.map(|()| out)
}

/// A run of queries not yet started: the index of its first query and its answer slots.
type Run<'a, T> = (usize, &'a mut [T]);

/// The queries of a batch not yet started, as one run per thread.
struct Shares<'a, T> {
    /// Thread `k`'s run: it takes chunks from the front; a thread whose run is empty takes the
    /// back half of the longest other run.
    runs: Vec<Mutex<Run<'a, T>>>,
    /// Set when a thread panicked: the others take no more work.
    stop: AtomicBool,
}

impl<'a, T> Shares<'a, T> {
    /// `slots` split into `threads` runs of consecutive queries, as equal as can be.
    fn new(mut slots: &'a mut [T], threads: usize) -> Shares<'a, T> {
        let mut runs = Vec::with_capacity(threads);
        let mut first = 0;
        for k in 0..threads {
            let size = slots.len() / (threads - k);
            let (run, rest) = std::mem::take(&mut slots).split_at_mut(size);
            runs.push(Mutex::new((first, run)));
            first += size;
            slots = rest;
        }
        Shares {
            runs,
            stop: AtomicBool::new(false),
        }
    }

    /// Locks run `k`. Nothing can panic while a run is locked, but a poisoned lock still holds a
    /// consistent run.
    fn lock(&self, k: usize) -> std::sync::MutexGuard<'_, Run<'a, T>> {
        self.runs[k].lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Thread `me`'s next chunk: the front quarter of its run (at least one query), so that it
    /// locks its run a few dozen times per batch and leaves most of the run to be stolen. When its
    /// run is empty it first steals the back half of the longest other run; `None` when every run
    /// is empty.
    fn next(&self, me: usize) -> Option<Run<'a, T>> {
        if self.stop.load(Ordering::Relaxed) {
            return None;
        }
        loop {
            {
                let mut run = self.lock(me);
                let (first, slots) = std::mem::take(&mut *run);
                if !slots.is_empty() {
                    let size = slots.len().div_ceil(4);
                    let (chunk, rest) = slots.split_at_mut(size);
                    *run = (first + size, rest);
                    return Some((first, chunk));
                }
            }
            let stolen = self.steal(me)?;
            *self.lock(me) = stolen;
        }
    }

    /// The back half of the longest run other than `me`'s (all of it if it holds one query), taken
    /// out of that run; `None` if every other run is empty. Only one run is locked at a time.
    fn steal(&self, me: usize) -> Option<Run<'a, T>> {
        loop {
            let victim = (0..self.runs.len())
                .filter(|&k| k != me)
                .map(|k| (self.lock(k).1.len(), k))
                .max()
                .filter(|&(len, _)| len > 0)?
                .1;
            let mut run = self.lock(victim);
            let (first, slots) = std::mem::take(&mut *run);
            if slots.is_empty() {
                // Emptied since it was measured: look again.
                continue;
            }
            let keep = slots.len() / 2;
            let (kept, taken) = slots.split_at_mut(keep);
            *run = (first, kept);
            return Some((first + keep, taken));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashSet;
    use std::thread::ThreadId;

    fn workers(threads: usize) -> Workers {
        Workers::plain(threads)
    }

    #[test]
    fn every_query_is_answered_once_in_order() {
        for n in [0, 1, 2, 3, 7, 100, 1001] {
            for threads in [0, 1, 2, 3, 1000] {
                let calls = Mutex::new(Vec::new());
                let out = answer_all(
                    n,
                    workers(threads),
                    || (),
                    |_, i| {
                        calls.lock().unwrap().push(i);
                        Ok(3 * i + 1)
                    },
                )
                .unwrap();
                assert_eq!(out, (0..n).map(|i| 3 * i + 1).collect::<Vec<_>>());
                let mut calls = calls.into_inner().unwrap();
                calls.sort();
                assert_eq!(calls, (0..n).collect::<Vec<_>>());
            }
        }
    }

    #[test]
    fn chunks_cover_the_queries_in_order_on_one_thread() {
        let mut slots = vec![0u8; 1000];
        let shares = Shares::new(&mut slots, 1);
        let mut next = 0;
        let mut sizes = Vec::new();
        while let Some((first, chunk)) = shares.next(0) {
            assert_eq!(first, next);
            next += chunk.len();
            sizes.push(chunk.len());
        }
        assert_eq!(next, 1000);
        assert_eq!(sizes[0], 250);
        assert!(sizes.windows(2).all(|w| w[0] >= w[1]), "{sizes:?}");
        assert!(sizes.len() < 40, "{sizes:?}");
    }

    #[test]
    fn a_thread_whose_run_is_done_steals_the_back_half_of_another() {
        let mut slots = vec![0u8; 100];
        let shares = Shares::new(&mut slots, 3);
        // Runs of 33, 33 and 34 queries.
        assert_eq!(shares.next(0).map(|(f, c)| (f, c.len())), Some((0, 9)));
        while !shares.lock(0).1.is_empty() {
            shares.next(0);
        }
        // Thread 0 steals from the longest other run (thread 2's, 66..100): its back half.
        assert_eq!(shares.next(0).map(|(f, c)| (f, c.len())), Some((83, 5)));
        assert_eq!(shares.lock(2).0, 66);
        assert_eq!(shares.lock(2).1.len(), 17);
        // Every query is handed out exactly once, whoever asks.
        let mut seen: Vec<bool> = (0..100).map(|k| k < 33 || (83..88).contains(&k)).collect();
        let mut turn = 0;
        loop {
            let me = [1, 2, 0][turn % 3];
            turn += 1;
            let Some((first, chunk)) = shares.next(me) else {
                break;
            };
            for (i, s) in seen.iter_mut().enumerate().skip(first).take(chunk.len()) {
                assert!(!*s, "query {i} handed out twice");
                *s = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn threads_answer_long_runs_of_consecutive_queries() {
        // Each thread's state is the last query it answered; a query that does not follow it is
        // the start of a run. Runs start only where a thread starts or steals, a few per thread.
        if cores() < 2 {
            return;
        }
        let starts = Mutex::new(0usize);
        struct Last<'a>(Option<usize>, &'a Mutex<usize>);
        answer_all(
            1000,
            workers(2),
            || Last(None, &starts),
            |last, i| {
                if last.0.map(|l| l + 1) != Some(i) {
                    *last.1.lock().unwrap() += 1;
                }
                last.0 = Some(i);
                std::thread::sleep(std::time::Duration::from_micros(20));
                Ok(0u8)
            },
        )
        .unwrap();
        let starts = starts.into_inner().unwrap();
        assert!((2..=16).contains(&starts), "{starts} runs");
    }

    #[test]
    fn threads_are_capped_by_cores_and_queries() {
        let cores = cores();
        assert_eq!(workers(0).count(1000), cores);
        assert_eq!(workers(1000).count(1000), cores);
        assert_eq!(workers(1).count(1000), 1);
        assert_eq!(workers(0).count(1), 1);
        assert_eq!(workers(0).count(0), 1);
        assert_eq!(workers(2).count(1000), 2.min(cores));
    }

    #[test]
    fn several_threads_share_the_work() {
        let cores = cores();
        if cores < 2 {
            return;
        }
        let seen = Mutex::new(HashSet::<ThreadId>::new());
        answer_all(
            400,
            workers(2),
            || (),
            |_, _| {
                seen.lock().unwrap().insert(std::thread::current().id());
                // Long enough that the second thread starts before the first is done.
                std::thread::sleep(std::time::Duration::from_micros(200));
                Ok(0u8)
            },
        )
        .unwrap();
        assert_eq!(seen.into_inner().unwrap().len(), 2);
    }

    #[test]
    fn an_error_is_returned_and_no_answers() {
        let r = answer_all(
            50,
            workers(2),
            || (),
            |_, i| {
                if i == 30 {
                    Err(Error::Internal)
                } else {
                    Ok(1u8)
                }
            },
        );
        assert_eq!(r, Err(Error::Internal));
    }

    #[test]
    fn a_panic_in_a_started_thread_reaches_the_caller() {
        let main = std::thread::current().id();
        let caught = panic::catch_unwind(|| {
            answer_all(
                200,
                workers(2),
                || (),
                |_, _| {
                    std::thread::sleep(std::time::Duration::from_micros(100));
                    if std::thread::current().id() != main {
                        panic!("worker bug");
                    }
                    Ok(0u8)
                },
            )
        });
        let cores = cores();
        if cores >= 2 {
            let payload = caught.expect_err("the worker's panic is resumed");
            assert_eq!(payload.downcast_ref::<&str>(), Some(&"worker bug"));
        }
    }

    #[test]
    fn each_thread_keeps_its_own_state() {
        // The state counts the queries its thread answered: the counts add up to n.
        let totals = Mutex::new(Vec::new());
        struct Count<'a>(usize, &'a Mutex<Vec<usize>>);
        impl Drop for Count<'_> {
            fn drop(&mut self) {
                self.1.lock().unwrap().push(self.0);
            }
        }
        answer_all(
            300,
            workers(0),
            || Count(0, &totals),
            |c, _| {
                c.0 += 1;
                Ok(0u8)
            },
        )
        .unwrap();
        assert_eq!(totals.into_inner().unwrap().iter().sum::<usize>(), 300);
    }
}
