// nlsubdiv_pool.hh: a persistent std::thread pool that runs the kernel's passes
// (nls_executor of nlsubdiv.h), for the OpenMesh and CGAL wrappers and for any C++ host.
//
//   nlsubdiv::ThreadPool pool(4);               // 0: std::thread::hardware_concurrency()
//   nls_subdivide_options o = nls_subdivide_default_options();
//   o.executor = pool.executor();               // NULL for one thread: the calling thread
//
// The kernel splits each pass of a level into disjoint output ranges whose values do not
// depend on the split (docs/architecture.md, "Parallel evaluation"), so the output, the
// report and the errors are the same bits for every thread count. The pool only decides
// where the tasks run: its workers are started once, in the constructor, and wait on a
// condition variable between passes (a pass costs a wake-up, not a thread start); the thread
// that calls the kernel takes tasks too. Calls from several host threads that share one pool
// are serialised; each host thread may also own its pool.
#ifndef NLSUBDIV_POOL_HH
#define NLSUBDIV_POOL_HH

#include <nlsubdiv.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace nlsubdiv {

class ThreadPool {
 public:
  /// `threads` threads in all, the calling thread included (0: the hardware's thread count,
  /// 1 when it is unknown). Starts `threads − 1` workers; throws what std::thread throws
  /// when a worker cannot be started (nothing is left running then).
  explicit ThreadPool(unsigned threads = 0) : threads_(threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads) {
    exec_.run = &ThreadPool::run;
    exec_.host_context = this;
    // One task per thread: the kernel's ranges are of equal size, and more tasks than
    // threads only add wake-ups (the output is the same for every task count).
    exec_.max_tasks = std::min<uint32_t>(threads_, nls_max_tasks());
    try {
      for (unsigned i = 1; i < threads_; ++i) workers_.emplace_back([this] { work(); });
    } catch (...) {
      stop();
      throw;
    }
  }
  ~ThreadPool() { stop(); }
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// The number of threads, the calling thread included.
  unsigned threads() const { return threads_; }

  /// The executor to put into nls_subdivide_options::executor: NULL with one thread (every
  /// pass on the calling thread, without the pool), otherwise this pool. Valid while the
  /// pool lives.
  const nls_executor* executor() const { return threads_ > 1 ? &exec_ : nullptr; }

 private:
  /// nls_executor::run: publishes the pass, takes tasks on the calling thread, and returns
  /// once every task has returned (the mutex and the condition variables order the
  /// library's writes before the tasks and the tasks' writes before the return). `noexcept`:
  /// should waiting itself fail, the process ends rather than return while tasks run.
  static void run(void* host, uint32_t count, nls_task_fn task, void* ctx) noexcept {
    ThreadPool& p = *static_cast<ThreadPool*>(host);
    std::unique_lock<std::mutex> call(p.call_m_, std::defer_lock);
    try {
      call.lock();
      {
        std::lock_guard<std::mutex> g(p.m_);
        p.task_ = task;
        p.ctx_ = ctx;
        p.count_ = count;
        p.next_.store(0, std::memory_order_relaxed);
        p.active_ = static_cast<unsigned>(p.workers_.size());
        ++p.generation_;
      }
      p.start_.notify_all();
    } catch (...) {
      // No worker has seen this pass (it is published under the lock, then announced): run
      // it here. `run` must not throw (nlsubdiv.h).
      for (uint32_t i = 0; i < count; ++i) task(ctx, i);
      return;
    }
    p.take(task, ctx, count);
    std::unique_lock<std::mutex> g(p.m_);
    p.done_.wait(g, [&p] { return p.active_ == 0; });
  }

  /// Runs tasks of the current pass until none is left.
  void take(nls_task_fn task, void* ctx, uint32_t count) {
    for (uint32_t i = next_.fetch_add(1, std::memory_order_relaxed); i < count; i = next_.fetch_add(1, std::memory_order_relaxed))
      task(ctx, i);
  }

  /// A worker: waits for a pass (or the stop), takes its tasks, reports that it is done.
  void work() {
    uint64_t seen = 0;
    std::unique_lock<std::mutex> g(m_);
    for (;;) {
      start_.wait(g, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      const nls_task_fn task = task_;
      void* const ctx = ctx_;
      const uint32_t count = count_;
      g.unlock();
      take(task, ctx, count);
      g.lock();
      if (--active_ == 0) done_.notify_one();
    }
  }

  void stop() {
    {
      std::lock_guard<std::mutex> g(m_);
      stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : workers_)
      if (t.joinable()) t.join();
    workers_.clear();
  }

  const unsigned threads_;
  nls_executor exec_{};
  std::vector<std::thread> workers_;
  std::mutex call_m_;  // one pass at a time per pool
  std::mutex m_;       // guards everything below but next_
  std::condition_variable start_, done_;
  uint64_t generation_ = 0;
  bool stop_ = false;
  nls_task_fn task_ = nullptr;
  void* ctx_ = nullptr;
  uint32_t count_ = 0;
  unsigned active_ = 0;
  std::atomic<uint32_t> next_{0};
};

}  // namespace nlsubdiv

#endif
