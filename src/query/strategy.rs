//! How a distance or tolerance query searches: the [`Strategy`] (the order of the visits) and the
//! [`Search`] options around it. Plain settings, below every part of the search that reads them.

use crate::error::Error;

/// The order in which a search visits the BVTT.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Strategy {
    /// The fastest measured for the query (BENCHMARKS.md): [`Priority`](Strategy::Priority) for
    /// distance, which then expands no more nodes than any search can; [`DepthFirst`](Strategy::DepthFirst)
    /// for tolerance, which stops at the first pair within the tolerance and so wants to reach
    /// triangle pairs soon.
    Auto,
    /// Depth-first, nearer child first: PQP 1.3's search for a queue size of 1 or 2.
    DepthFirst,
    /// Level by level (first in, first out).
    BreadthFirst,
    /// Priority-directed: pending pairs in a queue ordered by bound, the nearest expanded first. The
    /// queue holds at most [`Search::qsize`] pairs; a pair that does not fit is searched depth-first
    /// at once (PQP 1.3's search for a queue size above 2).
    Priority,
}

/// How a distance or tolerance query searches.
///
/// The default, [`Strategy::Auto`] with a queue of [`Search::DEFAULT_QSIZE`] pairs and triangle
/// caching, was chosen from the measurements in BENCHMARKS.md: it does the least bounding-volume
/// work for distance (or close to it), reaches an answer soonest for tolerance, and caching makes
/// coherent motion cheap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Search {
    /// The visiting order.
    pub strategy: Strategy,
    /// [`Strategy::Priority`] (and `Auto` when it chooses it) only: the most pairs the queue holds
    /// (>= 1; `usize::MAX`: unbounded).
    pub qsize: usize,
    /// Start from the closest triangle pair of the last query on the same two models (kept in the
    /// result), so that under coherent motion the first answer is already nearly the final one.
    /// A priority-directed distance query also starts from the last query's BVTT front (kept in
    /// the result too) when the models moved little since, which skips most of its bound tests
    /// (on the tumbling tori, 476 bound tests a frame instead of 1,294 from the root).
    pub triangle_cache: bool,
}

impl Default for Search {
    fn default() -> Self {
        Search {
            strategy: Strategy::Auto,
            qsize: Search::DEFAULT_QSIZE,
            triangle_cache: true,
        }
    }
}

impl Search {
    /// The default queue size. Large enough that on every benchmark workload but the nested shells
    /// the queue never fills, so the search does the minimal work; small enough that where the
    /// bounds cannot tell pairs apart (nested shells: about a million pairs with bound 0) the queue
    /// stays in cache and the overflow, searched depth-first, finds a good answer soon.
    pub const DEFAULT_QSIZE: usize = 1024;

    /// PQP 1.3's own search for its queue size `qsize`: depth-first for 1 or 2, else a priority
    /// queue of `qsize` pairs; with triangle caching.
    pub fn pqp(qsize: usize) -> Search {
        Search {
            strategy: if qsize <= 2 {
                Strategy::DepthFirst
            } else {
                Strategy::Priority
            },
            qsize: qsize.max(1),
            triangle_cache: true,
        }
    }

    /// The strategy it runs, `auto` standing for the query's choice.
    pub(crate) fn resolve(&self, auto: Strategy) -> Strategy {
        match self.strategy {
            Strategy::Auto => auto,
            s => s,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Error> {
        if self.qsize >= 1 {
            Ok(())
        } else {
            Err(Error::InvalidArgument)
        }
    }
}
