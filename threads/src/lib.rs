//! # nlsubdiv-threads
//!
//! The std layer of nlsubdiv's deterministic parallel evaluation: [`Threads`], an
//! [`Executor`] that runs the chunks of every pass on the calling thread and `n − 1` worker
//! threads (a persistent pool, or threads scoped to each pass with [`Threads::scoped`]), and
//! [`subdivide`], the core's
//! [`nlsubdiv::subdivide_with`] with a thread count. The core stays `no_std` and
//! single-threaded; it only splits each pass into disjoint output ranges. The output, the
//! report and the errors are bit-identical for every thread count.
//!
//! ```
//! use nlsubdiv::{plan, Mesh, MeshOut, Options, Scheme, Scratch};
//! let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let mesh = Mesh::new(&p, &[0, 4], &[0, 1, 2, 3]);
//! let opts = Options::new(Scheme::CatmullClark).levels(3);
//! let mut u32s = vec![0u32; 4096];
//! let pl = plan(mesh, &opts, &mut u32s).unwrap();
//! let o = pl.output();
//! let mut points = vec![[0.0; 3]; pl.scratch.points];
//! let (mut pos, mut offs, mut idx) =
//!     (vec![[0.0; 3]; o.vertices], vec![0u32; o.faces + 1], vec![0u32; o.indices]);
//! let mut out = MeshOut::new(&mut pos, &mut offs, &mut idx);
//! let scratch = Scratch::new(&mut u32s, &mut points);
//! nlsubdiv_threads::subdivide(mesh, &opts, scratch, &mut out, 2).unwrap();
//! ```

use std::sync::{Arc, Mutex, PoisonError};

use rayon_core::{ThreadPool, ThreadPoolBuilder};

use nlsubdiv::exec::{Chunk, Executor};
use nlsubdiv::{Mesh, MeshOut, Options, Report, Result, Scratch};

/// The smallest number of output elements per chunk worth a thread: waking a pool thread
/// costs microseconds, and a point between a fraction of a microsecond (linear rules) and a
/// few (Möbius). With 512 the small first levels of a Möbius call split too: its serial share
/// at 2 threads fell from 7.2 % to 3.3 % (Catmull–Clark spot_quad, 3 levels) and 10.1 % to
/// 6.6 % (Loop epcot, 4) of the instructions against 2048, with no change of the 2-thread
/// times beyond their spread (`benches/serial_share.sh`, `benches/threads.rs`).
pub const MIN_CHUNK: usize = 512;

/// The smallest number of rows per chunk of differential-space subdivision's passes
/// ([`differential_subdivide`]): a row of the reconstruction's sparse products costs a few
/// nanoseconds, and the solve runs tens of passes per iteration, so only the finest levels
/// are worth splitting.
pub const DIFFERENTIAL_MIN_CHUNK: usize = 32768;

/// Chunks per thread of a pass long enough ([`MIN_CHUNK`] elements each): the threads take
/// the next chunk as they finish one, so a range that costs more than its length says (the
/// fold guard's distrusted stars, which a level keeps among its first, old vertices) is
/// shared out instead of left to one thread.
pub const CHUNKS_PER_THREAD: usize = 4;

/// Runs every pass on up to `n` threads: the calling thread and `n − 1` workers each take
/// the next chunk not yet taken until none is left, so the work balances while every chunk
/// still writes only its own range (the output does not depend on which thread ran which
/// chunk, nor on their order).
///
/// The workers of [`Threads::new`] are a process-wide pool, started by the first pass that
/// needs them and kept, parked, for the next (`n − 1` of them, grown when a later call asks
/// for more; a child process made by `fork` builds its own): a pass wakes them instead of
/// spawning threads, which on a 2-core Linux machine cost about 35 µs a thread, tens of times
/// a call (`benches/threads.rs` compares the two). [`Threads::scoped`] spawns them for each
/// pass instead ([`std::thread::scope`]), for a host that wants no thread of the library to
/// outlive a call. Both give the same bits.
///
/// The bits assume the default floating-point environment (round to nearest, no
/// flush-to-zero) on every thread, as Rust itself does; the C ABI checks it on every thread
/// and refuses another. A pool worker keeps the environment of the thread that built the
/// pool, a scoped worker takes the calling thread's.
#[derive(Clone, Copy, Debug)]
pub struct Threads {
    n: usize,
    /// Workers scoped to each pass instead of the pool.
    scoped: bool,
    /// A fixed number of chunks per pass (tests of odd chunkings), or `None`: up to
    /// [`CHUNKS_PER_THREAD`] chunks per thread, each of at least `min_chunk` elements.
    fixed: Option<usize>,
    /// The smallest chunk without `fixed` ([`MIN_CHUNK`] unless set).
    min_chunk: usize,
}

impl Threads {
    /// `n` threads (0 is taken as 1), chunks of at least [`MIN_CHUNK`] elements.
    pub fn new(n: usize) -> Threads {
        Threads {
            n: n.max(1),
            scoped: false,
            fixed: None,
            min_chunk: MIN_CHUNK,
        }
    }

    /// `n` threads (0 is taken as 1) of which `n − 1` are spawned for each pass and joined
    /// before it returns ([`std::thread::scope`]): no thread outlives the pass, at the cost of
    /// a spawn per worker and pass. The same bits as [`Threads::new`].
    pub fn scoped(n: usize) -> Threads {
        Threads {
            scoped: true,
            ..Threads::new(n)
        }
    }

    /// The same threads with chunks of at least `min` elements (1 at least): a pass shorter
    /// than `2 · min` runs on the calling thread.
    pub fn min_chunk(self, min: usize) -> Threads {
        Threads {
            min_chunk: min.max(1),
            ..self
        }
    }

    /// `n` threads and `k` chunks per pass whatever its size (down to one element a chunk):
    /// for tests of odd chunkings.
    pub fn with_chunks(n: usize, k: usize) -> Threads {
        Threads {
            fixed: Some(k.max(1)),
            ..Threads::new(n)
        }
    }

    /// The number of threads.
    pub fn threads(&self) -> usize {
        self.n
    }

    /// The number of threads the machine offers ([`std::thread::available_parallelism`]),
    /// 1 when unknown.
    pub fn available() -> usize {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

impl Executor for Threads {
    fn chunks(&self, len: usize) -> usize {
        match self.fixed {
            Some(k) => k,
            None => (len / self.min_chunk).clamp(1, self.n.saturating_mul(CHUNKS_PER_THREAD)),
        }
    }

    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
        let workers = self.n.min(chunks.len());
        if workers <= 1 {
            chunks.iter_mut().for_each(task);
            return;
        }
        // The chunks not yet taken; a worker holds the lock only to take one. The core never
        // panics, so a poisoned lock cannot happen; were it to, the queue is still sound.
        let queue = Mutex::new(chunks.iter_mut());
        let work = || loop {
            let next = queue.lock().unwrap_or_else(PoisonError::into_inner).next();
            match next {
                Some(c) => task(c),
                None => break,
            }
        };
        // The pool's workers (sized for the whole call, `n − 1`, so that a later, longer pass
        // does not build it again), unless scoped or the pool cannot be had (the OS refused
        // a thread): then workers spawned for this pass. A worker the OS refuses is simply
        // not there: the calling thread takes every chunk the others do not, so the output
        // is the same and nothing panics.
        match (!self.scoped).then(|| pool(self.n - 1)).flatten() {
            Some(pool) => pool.in_place_scope(|s| {
                for _ in 1..workers {
                    s.spawn(|_| work());
                }
                work();
            }),
            None => std::thread::scope(|s| {
                for _ in 1..workers {
                    // An error leaves the chunks to the threads there are.
                    let _ = std::thread::Builder::new().spawn_scoped(s, work);
                }
                work();
            }),
        }
    }
}

/// The process-wide pool with at least `workers` threads, and the process it was built in:
/// the one kept, or a larger one that replaces it (the old one's threads end when the last
/// pass using it has returned). A child process made by `fork` inherits the kept pool but
/// not its threads, so a pool built in another process is left alone (never dropped: its
/// drop would signal threads that do not exist here) and a new one is built. `None` when the
/// OS refuses a thread.
fn pool(workers: usize) -> Option<Arc<ThreadPool>> {
    static POOL: Mutex<Option<(u32, Arc<ThreadPool>)>> = Mutex::new(None);
    let mut kept = POOL.lock().unwrap_or_else(PoisonError::into_inner);
    let pid = std::process::id();
    match kept.take() {
        Some((p, pool)) if p == pid && pool.current_num_threads() >= workers => {
            *kept = Some((p, Arc::clone(&pool)));
            return Some(pool);
        }
        Some((p, pool)) if p != pid => std::mem::forget(pool),
        _ => {}
    }
    let pool = ThreadPoolBuilder::new()
        .num_threads(workers)
        .thread_name(|i| format!("nlsubdiv-{i}"))
        .build()
        .ok()
        .map(Arc::new)?;
    *kept = Some((pid, Arc::clone(&pool)));
    Some(pool)
}

/// [`nlsubdiv::subdivide`] on `threads` std threads (0 or 1: the calling thread only): the
/// same output, report and errors, bit for bit, for every thread count.
///
/// # Errors
/// Those of [`nlsubdiv::subdivide`].
pub fn subdivide(
    mesh: Mesh<'_>,
    opts: &Options,
    scratch: Scratch<'_>,
    out: &mut MeshOut<'_>,
    threads: usize,
) -> Result<Report> {
    nlsubdiv::subdivide_with(mesh, opts, scratch, out, &Threads::new(threads))
}

/// [`nlsubdiv::differential::subdivide`] on `threads` std threads (0 or 1: the calling
/// thread only), through [`nlsubdiv::differential::subdivide_with`]: the linear steps of the
/// fields and the reconstruction's row-wise sparse products are split over the threads in
/// chunks of at least [`DIFFERENTIAL_MIN_CHUNK`] rows; the reductions and the Gauss–Seidel
/// sweeps stay serial. The same output, report and errors,
/// bit for bit, for every thread count.
///
/// # Errors
/// Those of [`nlsubdiv::differential::subdivide`].
pub fn differential_subdivide(
    mesh: Mesh<'_>,
    opts: &nlsubdiv::differential::DifferentialOptions<'_>,
    scratch_u32: &mut [u32],
    scratch_points: &mut [nlsubdiv::Point],
    out: &mut MeshOut<'_>,
    report: &mut nlsubdiv::differential::DifferentialReport,
    threads: usize,
) -> Result<nlsubdiv::MeshSizes> {
    nlsubdiv::differential::subdivide_with(
        mesh,
        opts,
        scratch_u32,
        scratch_points,
        out,
        report,
        &Threads::new(threads).min_chunk(DIFFERENTIAL_MIN_CHUNK),
    )
}
