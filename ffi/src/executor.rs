//! The host-driven parallel form of `nls_mesh_subdivide`: a host with its own thread pool
//! (TBB, OpenMP, a CAD kernel's scheduler) passes an `nls_executor` in the options, and the
//! library hands it the tasks of each pass (disjoint output ranges, `nlsubdiv::exec`). The
//! library starts no thread and allocates nothing; the output is bit-identical for every
//! executor, task count and order.

use core::ffi::c_void;
#[cfg(target_has_atomic = "8")]
use core::sync::atomic::{AtomicBool, Ordering};

use nlsubdiv::exec::{Chunk, Executor, MAX_CHUNKS};

/// The largest number of tasks one pass is split into by any build of the library; a build
/// may split into fewer (`nls_max_tasks()`). `nls_executor.max_tasks` above the build's
/// figure acts as it.
pub const NLS_MAX_TASKS: u32 = 64;
// The C value is a literal (cbindgen cannot write the core's constant into the header).
const _: () = assert!(MAX_CHUNKS <= NLS_MAX_TASKS as usize);

/// The largest number of tasks this build of the library splits one pass into: 64
/// (`NLS_MAX_TASKS`) unless it was built with `NLSUBDIV_MAX_CHUNKS` (1 to 64; a firmware
/// build on one core sets 1, `docs/firmware.md`). With 1, every pass runs on the calling
/// thread and an `nls_executor`'s `run` is never called.
#[unsafe(no_mangle)]
pub extern "C" fn nls_max_tasks() -> u32 {
    MAX_CHUNKS as u32
}

/// One task of a pass: the library's function the host calls with the `task_context` it was
/// given and a task index below `task_count`.
#[allow(non_camel_case_types)] // the C name
pub type nls_task_fn = Option<unsafe extern "C" fn(task_context: *mut c_void, task_index: u32)>;

/// A host's thread pool. `run(host_context, task_count, task, task_context)` must call
/// `task(task_context, i)` once for every `i` in `[0, task_count)` — in any order, on any
/// threads, concurrently or not — starting them after `run` was called and returning only
/// after every call has returned (the pool's submit and join are what make the library's
/// data visible to the tasks and the tasks' writes visible to the library). `run` must not
/// throw (a C++ exception through the library is undefined behaviour) and must not touch the
/// buffers of the call. The library calls `run` once per pass of each level, from the thread
/// that called `nls_mesh_subdivide`, never from inside a task. A task never blocks, allocates
/// or calls back into the host.
///
/// Each task checks its thread's floating-point environment as the call checks the calling
/// thread's: a pool thread with flush-to-zero, denormals-are-zero or a non-default rounding
/// mode makes the call fail with `NLS_STATUS_FP_ENVIRONMENT`, and its unmasked exception
/// traps are masked for the task and restored after it.
///
/// Contained breaches: a task index out of range or called a second time is ignored (on
/// targets with atomic swap; other targets refuse an executor with
/// `NLS_STATUS_INVALID_ARGUMENT`), and a task never called makes the call fail with
/// `NLS_STATUS_INVALID_ARGUMENT`. Undefined behaviour, as for any callback: calling a task
/// after `run` has returned, returning from `run` while a task still runs, throwing.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct nls_executor {
    /// Runs the tasks of one pass (never NULL in a used executor).
    pub run: Option<
        unsafe extern "C" fn(
            host_context: *mut c_void,
            task_count: u32,
            task: nls_task_fn,
            task_context: *mut c_void,
        ),
    >,
    /// Passed to `run` as is.
    pub host_context: *mut c_void,
    /// How many tasks a pass should be split into, at most `nls_max_tasks()` (usually the pool's
    /// thread count, or a few times it for balance); 0 or 1 runs every pass on the calling
    /// thread without calling `run`.
    pub max_tasks: u32,
}

/// The host's executor as the core's [`Executor`].
pub(crate) struct HostExecutor {
    e: nls_executor,
    /// Set by a task that found its thread's floating-point environment changed: the call
    /// fails with `FpEnvironment` (the task did not run, so the core fails the pass).
    #[cfg(target_has_atomic = "8")]
    fp_refused: AtomicBool,
}

// SAFETY: `Sync` lets the core share `&HostExecutor` with the tasks (the `Executor` bound).
// The tasks only touch `fp_refused`, an atomic; `run` and `host_context` are used only by
// `Executor::run`, which the core calls from the calling thread, never from a task (the core
// runs no pass inside a pass).
unsafe impl Sync for HostExecutor {}

impl HostExecutor {
    /// The executor of the options, `None` for NULL. `Err` when it cannot be used: `run` NULL
    /// with `max_tasks > 1`, or a target without atomic swap.
    ///
    /// # Safety
    /// `p` is NULL or points to a readable `nls_executor`.
    pub(crate) unsafe fn read(
        p: *const nls_executor,
    ) -> Result<Option<HostExecutor>, nlsubdiv::Status> {
        crate::guard::check_ptr(p, usize::from(!p.is_null()))?;
        if p.is_null() {
            return Ok(None);
        }
        // SAFETY: non-NULL and aligned (checked); readable by the caller's contract.
        let e = unsafe { p.read() };
        if e.max_tasks > 1 && (e.run.is_none() || !cfg!(target_has_atomic = "8")) {
            return Err(nlsubdiv::Status::InvalidArgument);
        }
        Ok(Some(HostExecutor {
            e,
            #[cfg(target_has_atomic = "8")]
            fp_refused: AtomicBool::new(false),
        }))
    }

    /// Whether a task refused to run in a non-default floating-point environment.
    pub(crate) fn fp_refused(&self) -> bool {
        #[cfg(target_has_atomic = "8")]
        {
            self.fp_refused.load(Ordering::Acquire)
        }
        #[cfg(not(target_has_atomic = "8"))]
        {
            false
        }
    }
}

/// What `run` hands the trampoline: the chunks of the pass, the task, and one claim flag per
/// chunk so that a chunk runs at most once whatever the host does.
#[cfg(target_has_atomic = "8")]
struct Tasks<'a, 'c> {
    chunks: *mut Chunk<'c>,
    count: usize,
    task: &'a (dyn Fn(&mut Chunk<'c>) + Sync),
    claimed: [AtomicBool; MAX_CHUNKS],
    fp_refused: &'a AtomicBool,
}

impl Executor for HostExecutor {
    fn chunks(&self, _len: usize) -> usize {
        // The core clamps this to 1..=MAX_CHUNKS and to the pass's length.
        self.e.max_tasks as usize
    }

    fn run(&self, chunks: &mut [Chunk<'_>], task: &(dyn Fn(&mut Chunk<'_>) + Sync)) {
        let Some(run) = self.e.run else {
            // Checked by `read`; a chunk left unrun makes the call fail.
            return;
        };
        #[cfg(target_has_atomic = "8")]
        {
            let tasks = Tasks {
                chunks: chunks.as_mut_ptr(),
                count: chunks.len().min(MAX_CHUNKS),
                task,
                claimed: [const { AtomicBool::new(false) }; MAX_CHUNKS],
                fp_refused: &self.fp_refused,
            };
            // SAFETY: the host's contract; `tasks` outlives the call (the host returns after
            // every task has returned), and the trampoline is the only user of the pointer.
            unsafe {
                run(
                    self.e.host_context,
                    tasks.count as u32,
                    Some(trampoline),
                    core::ptr::from_ref(&tasks).cast_mut().cast::<c_void>(),
                );
            }
        }
        #[cfg(not(target_has_atomic = "8"))]
        {
            // Refused by `read`.
            let _ = (run, chunks, task);
        }
    }
}

/// The library's task function: runs chunk `i` once.
#[cfg(target_has_atomic = "8")]
unsafe extern "C" fn trampoline(task_context: *mut c_void, task_index: u32) {
    if task_context.is_null() {
        return;
    }
    // SAFETY: `task_context` is the `Tasks` of the pass in progress (the host passes back
    // what `run` was given, while `run` has not returned).
    let tasks = unsafe { &*task_context.cast_const().cast::<Tasks<'_, '_>>() };
    let i = task_index as usize;
    let Some(flag) = tasks.claimed.get(i) else {
        return;
    };
    if i >= tasks.count || flag.swap(true, Ordering::AcqRel) {
        return;
    }
    // The calling thread's checks, on this thread: the default modes (else the call fails
    // with FP_ENVIRONMENT), the host's unmasked traps masked for the task and restored.
    let _traps = crate::guard::FpTrapGuard::mask_traps();
    if !crate::guard::fp_env_is_default() {
        tasks.fp_refused.store(true, Ordering::Release);
        return;
    }
    // SAFETY: `i < count` chunks live at `chunks`; the claim flag gives this call the only
    // reference to chunk `i` (every other task touches another chunk).
    let chunk = unsafe { &mut *tasks.chunks.add(i) };
    (tasks.task)(chunk);
}
