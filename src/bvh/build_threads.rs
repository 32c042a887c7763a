//! The build on several threads: subtrees handed to idle threads as the build splits them.
//!
//! Scoped std threads around a shared stack of subtrees (a mutex and a condition variable): a
//! build runs once per model, its tasks are a few dozen subtrees, and a thread pool crate would add
//! a dependency for nothing the build uses. Every builder, on finding a child's subtree big enough
//! (at least [`GRAIN`] triangles) while some thread is idle, hands it over and goes on with the
//! other child. What a subtree's nodes are depends only on its triangles, never on which thread
//! builds it (see `build.rs`), so the hierarchy is the same whatever the thread count.

use crate::error::Error;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::{Condvar, Mutex, MutexGuard};

/// Fewest triangles of a subtree worth handing to another thread (a few hundred microseconds of
/// work); smaller ones are built where they were split.
pub(crate) const GRAIN: usize = 4096;

/// Subtrees (tasks `T`) waiting for a thread, how many threads are building one, and the first
/// error.
struct State<T> {
    queue: Vec<T>,
    busy: usize,
    error: Option<Error>,
}

/// The shared stack of subtrees (`T`: what the builder needs of one) of one build.
pub(super) struct Pool<T> {
    state: Mutex<State<T>>,
    wake: Condvar,
    threads: usize,
}

impl<T: Send> Pool<T> {
    /// Builds `root` on `threads` threads (this one and `threads - 1` scoped ones; fewer if the
    /// system will not start them): `work` builds a subtree with a thread's scratch (made by
    /// `scratch`), handing subtrees to the pool as it goes. This thread builds `root`; while it
    /// does (there is nothing else to build until the root splits), the first other thread runs
    /// `side` (work of the build that does not wait for the hierarchy), and every other thread
    /// makes its scratch. `side` runs on this thread afterwards if no thread could be started.
    /// The first error of any thread (or of `side`), once every thread has stopped.
    pub fn run<S>(
        threads: usize,
        root: T,
        work: impl Fn(&mut S, T, &Pool<T>) -> Result<(), Error> + Sync,
        scratch: impl Fn() -> Result<S, Error> + Sync,
        side: impl FnOnce() -> Result<(), Error> + Send,
    ) -> Result<(), Error> {
        let pool = Pool {
            state: Mutex::new(State {
                queue: Vec::new(),
                // The root, which this thread takes.
                busy: 1,
                error: None,
            }),
            wake: Condvar::new(),
            threads,
        };
        let side = Mutex::new(Some(side));
        let take_side = || side.lock().unwrap_or_else(|e| e.into_inner()).take();
        std::thread::scope(|s| {
            for _ in 1..threads {
                // A thread that cannot be started leaves its share to the others.
                let _ = std::thread::Builder::new().spawn_scoped(s, || {
                    if let Some(side) = take_side() {
                        pool.report(
                            catch_unwind(AssertUnwindSafe(side)).unwrap_or(Err(Error::Internal)),
                        );
                    }
                    pool.worker(None, &work, &scratch)
                });
            }
            pool.worker(Some(root), &work, &scratch);
        });
        if let Some(side) = take_side() {
            pool.report(side());
        }
        match pool.lock().error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Keeps `result`'s error if it is the first.
    fn report(&self, result: Result<(), Error>) {
        if let Err(e) = result {
            let mut st = self.lock();
            st.error.get_or_insert(e);
            self.wake.notify_all();
        }
    }

    fn lock(&self) -> MutexGuard<'_, State<T>> {
        // No code panics while holding the lock; should one, the state is still consistent.
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// One thread's loop: builds `first` (a task already counted busy) if any, then takes
    /// subtrees until none is left and no thread is building one (so no more can come), or an
    /// error stops the build. A thread without a first task makes its scratch before it waits.
    fn worker<S>(
        &self,
        first: Option<T>,
        work: &(impl Fn(&mut S, T, &Pool<T>) -> Result<(), Error> + Sync),
        scratch: &(impl Fn() -> Result<S, Error> + Sync),
    ) {
        let mut mine: Option<S> = None;
        let mut task = first;
        if task.is_none() {
            // While the first thread builds the root: the scratch is then ready when a subtree
            // comes.
            match catch_unwind(AssertUnwindSafe(scratch)).unwrap_or(Err(Error::Internal)) {
                Ok(s) => mine = Some(s),
                Err(e) => self.report(Err(e)),
            }
        }
        let mut st = self.lock();
        loop {
            if st.error.is_some() {
                if task.is_some() {
                    st.busy -= 1;
                    self.wake.notify_all();
                }
                return;
            }
            if task.is_none() {
                task = st.queue.pop();
                if task.is_some() {
                    st.busy += 1;
                }
            }
            if let Some(task) = task.take() {
                drop(st);
                // A panic (none is expected) becomes an error rather than a thread that never
                // reports back, which would leave the others waiting.
                let result = catch_unwind(AssertUnwindSafe(|| {
                    let s = match &mut mine {
                        Some(s) => s,
                        empty => empty.insert(scratch()?),
                    };
                    work(s, task, self)
                }))
                .unwrap_or(Err(Error::Internal));
                st = self.lock();
                st.busy -= 1;
                if let Err(e) = result {
                    st.error.get_or_insert(e);
                }
                if st.error.is_some() || (st.busy == 0 && st.queue.is_empty()) {
                    self.wake.notify_all();
                }
                continue;
            }
            if st.busy == 0 {
                self.wake.notify_all();
                return;
            }
            st = self.wake.wait(st).unwrap_or_else(|e| e.into_inner());
        }
    }

    /// Whether a subtree handed over now would likely find an idle thread.
    pub fn wants(&self) -> bool {
        let st = self.lock();
        st.error.is_none() && st.queue.len() + st.busy < self.threads
    }

    /// Takes `sub` for an idle thread (`None`), or gives it back to build here.
    pub fn offer(&self, sub: T) -> Option<T> {
        let mut st = self.lock();
        if st.error.is_none() && st.queue.len() + st.busy < self.threads {
            st.queue.push(sub);
            self.wake.notify_one();
            None
        } else {
            Some(sub)
        }
    }
}

/// `work(state, task)` for every one of `tasks`, on up to `threads` threads (this one and scoped
/// ones; fewer if the system will not start them), each thread with its own `state` (made by
/// `state` on its first task), and the results in the order of the tasks, or the first error (of
/// the first task in order that failed). For the build's passes outside the recursion, split
/// into tasks of fixed content: what a task computes does not depend on the thread running it.
pub(super) fn run_tasks<T: Send, R: Send, S>(
    threads: usize,
    tasks: Vec<T>,
    work: impl Fn(&mut S, T) -> Result<R, Error> + Sync,
    state: impl Fn() -> Result<S, Error> + Sync,
) -> Result<Vec<R>, Error> {
    let count = tasks.len();
    let queue = Mutex::new(tasks.into_iter().enumerate());
    let done: Mutex<Vec<(usize, Result<R, Error>)>> = Mutex::new(Vec::new());
    let worker = || {
        let mut mine: Option<S> = None;
        loop {
            // No code panics while holding these locks; should one, the state is still whole.
            let next = queue.lock().unwrap_or_else(|e| e.into_inner()).next();
            let Some((k, task)) = next else { return };
            let result = catch_unwind(AssertUnwindSafe(|| {
                let s = match &mut mine {
                    Some(s) => s,
                    empty => empty.insert(state()?),
                };
                work(s, task)
            }))
            .unwrap_or(Err(Error::Internal));
            done.lock()
                .unwrap_or_else(|e| e.into_inner())
                .push((k, result));
        }
    };
    std::thread::scope(|s| {
        for _ in 1..threads.min(count) {
            // A thread that cannot be started leaves its share to the others.
            let _ = std::thread::Builder::new().spawn_scoped(s, worker);
        }
        worker();
    });
    let mut done = done.into_inner().unwrap_or_else(|e| e.into_inner());
    done.sort_unstable_by_key(|&(k, _)| k);
    done.into_iter().map(|(_, r)| r).collect()
}
