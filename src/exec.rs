//! Deterministic parallel evaluation without threads in the core: a pass over an output
//! range is split into at most [`MAX_CHUNKS`] disjoint, contiguous chunks ([`Chunk`]), and an
//! [`Executor`] supplied by the caller runs one task per chunk, in any order, on any thread.
//! The core itself stays single-threaded ([`Serial`] runs the chunks one after the other);
//! the std layers (`threads/`, the command, the C ABI) bring the threads. A pass that
//! writes several arrays (the Möbius vertex pass: vertex points, per-vertex values and
//! candidate slots of a vertex range) hands each chunk its disjoint sub-slice of every
//! array instead of one output range.
//!
//! Every value a task writes depends only on its output index and on what earlier passes
//! wrote, never on the chunk boundaries, so the output is bit-identical for every thread
//! count and every chunking. Counts are summed over the chunks, "first element" fields take
//! the minimum, and when several chunks fail the error of the lowest chunk is returned: a
//! chunk stops at its first error, so that is the error the serial run reports first in the
//! same pass. Passes follow each other (a barrier between them) in the serial order.
//!
//! ```
//! use nlsubdiv::exec::{Chunk, Executor, Serial};
//! // An executor that runs the chunks in reverse order: the same output bits.
//! struct Reverse(usize);
//! impl Executor for Reverse {
//!     fn chunks(&self, len: usize) -> usize {
//!         self.0.min(len)
//!     }
//!     fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
//!         for c in chunks.iter_mut().rev() {
//!             task(c);
//!         }
//!     }
//! }
//! # let _ = Serial;
//! ```

use arrayvec::ArrayVec;

use crate::error::{internal, Result, NO_ELEMENT};
use crate::point::Point;

/// The largest number of chunks one pass is split into: 64 unless the build sets
/// `NLSUBDIV_MAX_CHUNKS` (a decimal number from 1 to 64; anything else stops the build).
///
/// A pass split into several chunks holds one descriptor per chunk on the stack (the
/// paths that split run out of line, `docs/firmware.md`, "Stack"), and the Möbius step's
/// workspaces in the scratch are sized for this many chunks. A firmware build on a single
/// core, which runs every pass on the calling thread, sets it to 1: the paths that split are
/// then never taken, the optimiser drops them, and the static stack bound is that of the
/// serial path. The output bits do not depend on it (nor on the chunking).
pub const MAX_CHUNKS: usize = crate::caps::parse(option_env!("NLSUBDIV_MAX_CHUNKS"), 64);

const _: () = assert!(
    MAX_CHUNKS >= 1 && MAX_CHUNKS <= 64,
    "NLSUBDIV_MAX_CHUNKS must be a decimal number from 1 to 64"
);

/// One chunk of a pass: a contiguous range of the pass's output (or, for a pass that
/// writes several arrays, the chunk's share of each) and the task's result.
/// Opaque: an [`Executor`] only hands it to the task.
pub struct Chunk<'a> {
    /// The index of `out[0]` in the pass's output.
    start: usize,
    out: &'a mut [Point],
    /// The chunk's share of a pass over several arrays, with its work ([`parts`]); `None`
    /// for a pass over `out`.
    part: Option<&'a mut (dyn RunPart + Send + Sync + 'a)>,
    /// The number of elements (output points, or the part's own count).
    len: usize,
    /// What the task returned; an internal error until the task has run (an executor that
    /// skips a chunk gives an error, never a silently unwritten range).
    result: Result<Tally>,
}

impl core::fmt::Debug for Chunk<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("Chunk")
            .field("start", &self.start)
            .field("len", &self.len)
            .field("result", &self.result)
            .finish_non_exhaustive()
    }
}

impl Chunk<'_> {
    /// The number of output elements of this chunk (for an executor that balances work).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the chunk has no output element.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// Runs the chunks of a pass. An implementation must call `task` exactly once on every
/// chunk before returning; the order and the threads are free. [`Executor::chunks`] says
/// how many chunks a pass of `len` output elements should be split into (1 runs the pass
/// inline, without [`Executor::run`]); the core clamps it to `1..=`[`MAX_CHUNKS`].
pub trait Executor: Sync {
    /// The number of chunks wanted for a pass of `len` output elements.
    fn chunks(&self, len: usize) -> usize;
    /// Calls `task` once on every chunk.
    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync));
}

/// The single-threaded executor of the core: every pass in one chunk.
#[derive(Clone, Copy, Debug, Default)]
pub struct Serial;

impl Executor for Serial {
    fn chunks(&self, _len: usize) -> usize {
        1
    }

    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
        for c in chunks {
            task(c);
        }
    }
}

/// What a pass counts (fallbacks, guarded elements): a number and the smallest element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Tally {
    pub(crate) count: u32,
    pub(crate) first: u32,
}

impl Tally {
    pub(crate) const fn new() -> Tally {
        Tally {
            count: 0,
            first: NO_ELEMENT,
        }
    }

    /// Counts element `e`.
    pub(crate) fn add(&mut self, e: u32) {
        self.count = self.count.saturating_add(1);
        if self.first == NO_ELEMENT || e < self.first {
            self.first = e;
        }
    }

    /// The tally of two ranges.
    pub(crate) fn merge(self, o: Tally) -> Tally {
        Tally {
            count: self.count.saturating_add(o.count),
            first: if self.first == NO_ELEMENT {
                o.first
            } else if o.first == NO_ELEMENT {
                self.first
            } else {
                self.first.min(o.first)
            },
        }
    }
}

/// Runs `f(start, out_range, tally)` over disjoint chunks of `out` through `exec` and
/// combines the results (module docs): the tallies merged, or the error of the lowest chunk.
pub(crate) fn pass<F>(exec: &dyn Executor, out: &mut [Point], f: F) -> Result<Tally>
where
    F: Fn(usize, &mut [Point], &mut Tally) -> Result<()> + Sync,
{
    let n = out.len();
    let k = chunk_count(exec, n);
    if k <= 1 {
        return own_frame(|| {
            let mut t = Tally::new();
            f(0, out, &mut t)?;
            Ok(t)
        });
    }
    split_pass(exec, out, k, &f)
}

/// Runs `f` in a stack frame of its own, never inlined into its caller. The one-chunk path of
/// every pass calls its task through it, so that the task's locals are not added to the frame
/// of a function that runs several passes one after the other (a scheme's driver), whatever
/// the optimiser does with a task that has a single caller (in a build with [`MAX_CHUNKS`] =
/// 1 it has no other): the driver's stack is then its own plus the deepest pass's, not the sum
/// of all its passes' (`docs/firmware.md`, "Stack"). One call per pass.
#[inline(never)]
pub(crate) fn own_frame<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// The work of one chunk of a [`pass`]: its first output index, its output range, its tally.
type RangeFn<'f> = dyn Fn(usize, &mut [Point], &mut Tally) -> Result<()> + Sync + 'f;

/// [`pass`] in `k ≥ 2` chunks (out of line: the serial path keeps a small stack frame).
#[inline(never)]
fn split_pass(exec: &dyn Executor, out: &mut [Point], k: usize, f: &RangeFn<'_>) -> Result<Tally> {
    let size = out.len().div_ceil(k).max(1);
    let mut chunks = ArrayVec::<Chunk<'_>, MAX_CHUNKS>::new();
    let mut start = 0;
    for c in out.chunks_mut(size) {
        let len = c.len();
        chunks
            .try_push(Chunk {
                start,
                out: c,
                part: None,
                len,
                result: Err(internal()),
            })
            .map_err(|_| internal())?;
        start += len;
    }
    let task = |c: &mut Chunk<'_>| {
        let mut t = Tally::new();
        c.result = f(c.start, c.out, &mut t).map(|()| t);
    };
    exec.run(&mut chunks, &task);
    let mut total = Tally::new();
    for c in &chunks {
        total = total.merge(c.result?);
    }
    Ok(total)
}

/// The number of chunks a pass of `len` elements is split into by `exec`: what
/// [`Executor::chunks`] wants, clamped to `1..=`[`MAX_CHUNKS`] and to `len` ([`pass`] and
/// [`parts`] split the same way).
pub(crate) fn chunk_count(exec: &dyn Executor, len: usize) -> usize {
    exec.chunks(len).clamp(1, MAX_CHUNKS).min(len.max(1))
}

/// The element range `[start, end)` of chunk `i` of `k` over `len` elements: the ranges of
/// [`pass`] (`chunks_mut` of `len.div_ceil(k)`), possibly empty at the end.
pub(crate) fn chunk_range(len: usize, k: usize, i: usize) -> (usize, usize) {
    let size = len.div_ceil(k.max(1)).max(1);
    let start = size.saturating_mul(i).min(len);
    (start, start.saturating_add(size).min(len))
}

/// The first `n` elements of `*rest`, leaving the others in `*rest`: how a pass over several
/// arrays carves each chunk's disjoint sub-slice off the front ([`parts`]). An internal error
/// when fewer than `n` are left.
pub(crate) fn take_front<'a, T>(rest: &mut &'a mut [T], n: usize) -> Result<&'a mut [T]> {
    let (head, tail) = core::mem::take(rest)
        .split_at_mut_checked(n)
        .ok_or(internal())?;
    *rest = tail;
    Ok(head)
}

/// The work of one chunk of a pass over several arrays: its share of each array and the
/// function that fills them ([`parts`]).
pub(crate) trait RunPart {
    /// Runs the chunk's work; its tally.
    fn run(&mut self) -> Result<Tally>;
}

/// One part bound to the pass's function.
struct Bound<'f, 'p, P, F> {
    part: &'p mut P,
    f: &'f F,
}

impl<P, F> RunPart for Bound<'_, '_, P, F>
where
    F: Fn(&mut P, &mut Tally) -> Result<()>,
{
    fn run(&mut self) -> Result<Tally> {
        let mut t = Tally::new();
        (self.f)(self.part, &mut t).map(|()| t)
    }
}

/// Runs `f(part, tally)` on every part through `exec` and combines the results as [`pass`]
/// does: the tallies merged, or the error of the lowest part that failed. For a pass whose
/// chunks write several arrays (each part holds its disjoint sub-slices, made by the caller
/// with [`chunk_count`] and [`chunk_range`]); `len(part)` is its element count for the
/// executor. One part runs inline.
pub(crate) fn parts<P, F>(
    exec: &dyn Executor,
    parts: &mut [P],
    len: impl Fn(&P) -> usize,
    f: F,
) -> Result<Tally>
where
    P: Send + Sync,
    F: Fn(&mut P, &mut Tally) -> Result<()> + Sync,
{
    if let [one] = parts {
        return own_frame(|| {
            let mut t = Tally::new();
            f(one, &mut t)?;
            Ok(t)
        });
    }
    let mut bound = ArrayVec::<Bound<'_, '_, P, F>, MAX_CHUNKS>::new();
    let mut sizes = ArrayVec::<usize, MAX_CHUNKS>::new();
    for p in parts.iter_mut() {
        sizes.try_push(len(p)).map_err(|_| internal())?;
        bound
            .try_push(Bound { part: p, f: &f })
            .map_err(|_| internal())?;
    }
    let mut chunks = ArrayVec::<Chunk<'_>, MAX_CHUNKS>::new();
    for (i, (b, n)) in bound.iter_mut().zip(sizes.iter()).enumerate() {
        chunks
            .try_push(Chunk {
                start: i,
                out: &mut [],
                part: Some(b),
                len: *n,
                result: Err(internal()),
            })
            .map_err(|_| internal())?;
    }
    let task = |c: &mut Chunk<'_>| {
        if let Some(p) = c.part.as_mut() {
            c.result = p.run();
        }
    };
    exec.run(&mut chunks, &task);
    let mut total = Tally::new();
    for c in &chunks {
        total = total.merge(c.result?);
    }
    Ok(total)
}

/// The largest value of `values` (0 when empty), chunk by chunk: one branch-free pass per
/// chunk (vectorised by the compiler), then the largest of the chunks'.
pub(crate) fn largest(exec: &dyn Executor, values: &[u32]) -> Result<u32> {
    let k = chunk_count(exec, values.len());
    if k <= 1 {
        return Ok(largest_of(values));
    }
    split_largest(exec, values, k)
}

/// The largest value of a slice, 0 when empty.
fn largest_of(values: &[u32]) -> u32 {
    values.iter().fold(0u32, |m, &i| m.max(i))
}

/// [`largest`] in `k ≥ 2` chunks (out of line: the one-chunk path keeps a small stack
/// frame).
#[inline(never)]
fn split_largest(exec: &dyn Executor, values: &[u32], k: usize) -> Result<u32> {
    /// One chunk: its values and, once run, their largest.
    struct Part<'a> {
        values: &'a [u32],
        largest: u32,
    }
    let mut ranges = ArrayVec::<Part<'_>, MAX_CHUNKS>::new();
    for i in 0..k {
        let (a, b) = chunk_range(values.len(), k, i);
        let part = Part {
            values: values.get(a..b).ok_or(internal())?,
            largest: 0,
        };
        ranges.try_push(part).map_err(|_| internal())?;
    }
    parts(
        exec,
        &mut ranges,
        |p| p.values.len(),
        |p, _| {
            p.largest = largest_of(p.values);
            Ok(())
        },
    )?;
    Ok(ranges.iter().fold(0, |m, p| m.max(p.largest)))
}

/// The index of the first point of `pos` with a NaN or infinite coordinate, found chunk by
/// chunk. A branch-free test per chunk first (`|x| ≤ f64::MAX` is false exactly for NaN and
/// ±∞), the search only in a chunk where it fails.
pub(crate) fn first_non_finite(exec: &dyn Executor, pos: &mut [Point]) -> Result<Option<usize>> {
    let t = pass(exec, pos, |start, out, t| {
        let finite = out
            .as_flattened()
            .iter()
            .fold(true, |ok, x| ok & (x.abs() <= f64::MAX));
        if !finite {
            if let Some(i) = out.iter().position(|p| !crate::point::is_finite(p)) {
                t.add((start + i) as u32);
            }
        }
        Ok(())
    })?;
    Ok((t.count > 0).then_some(t.first as usize))
}

/// What the unit tests of the passes share: an executor that runs the chunks in reverse,
/// and the arenas their buffers are carved from (no allocation in the core, not even in its
/// tests).
#[cfg(test)]
pub(crate) mod testing {
    use super::{Chunk, Executor};

    /// `k` chunks per pass, run last to first.
    pub(crate) struct Reverse(pub(crate) usize);

    impl Executor for Reverse {
        fn chunks(&self, _len: usize) -> usize {
            self.0
        }
        fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
            chunks.iter_mut().rev().for_each(task);
        }
    }

    /// Takes the first `n` elements of `*arena`, leaving the rest there.
    pub(crate) fn take<'a, T>(arena: &mut &'a mut [T], n: usize) -> &'a mut [T] {
        let (head, rest) = core::mem::take(arena).split_at_mut(n);
        *arena = rest;
        head
    }
}

#[cfg(test)]
mod tests {
    use super::testing::Reverse;
    use super::*;

    #[test]
    fn the_largest_value_is_found_in_every_chunking() {
        let mut values = [0u32; 1000];
        let mut x = 7u32;
        for v in values.iter_mut() {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            *v = x >> 12;
        }
        let want = values.iter().copied().max().unwrap_or(0);
        for n in [0, 1, 2, 5, 999, 1000] {
            // The largest value at every place a chunk boundary can put it.
            let mut v = values;
            if let Some(last) = v.get_mut(n.min(999)) {
                *last = u32::MAX - 1;
            }
            for k in [1, 2, 3, 7, 64] {
                assert_eq!(largest(&Reverse(k), &v).unwrap(), u32::MAX - 1, "{n} {k}");
                assert_eq!(largest(&Reverse(k), &values).unwrap(), want, "{k}");
                assert_eq!(largest(&Reverse(k), &[]).unwrap(), 0);
            }
        }
    }
}
