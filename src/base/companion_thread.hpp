#pragma once
/// @file
/// CompanionThread: one thread, made once, that runs a job beside the calling thread, for
/// work that splits into two independent halves (the actor's and the critic's parts of the
/// hand-written PPO gradient, rl/ppo/ppo_gradient.hpp). A call creates no thread and
/// allocates nothing: the job is handed over by address through atomic counters, and the
/// waiting side spins briefly then sleeps (base/spin_then_wait.hpp).

#include <atomic>
#include <cstdint>
#include <exception>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>

#if !defined(__SSE__)
#include <cfenv>
#endif

namespace upkie_rl {

/// Runs one job at a time on its own thread while the caller runs another, then waits for
/// both. When the thread has not started the job by the time the caller is done with its
/// own (every core busy: the thread is waiting for one), the caller takes the job back and
/// runs it itself, so that a busy machine costs little more than running both in turn.
/// The job runs under the caller's floating-point control modes (rounding; on x86 also
/// flush-to-zero and denormals-are-zero), read at every call, so that its results do not
/// depend on the thread that runs it. An exception of either job reaches the caller, once
/// both have finished (never std::terminate), and the thread goes on serving.
/// One caller at a time: run_beside() is not re-entrant, and a job must not call it on the
/// object that runs it.
class CompanionThread {
 public:
  /// Starts the thread, which sleeps until the first job.
  /// @throws std::system_error when no thread can be started.
  CompanionThread();
  /// Stops the thread and joins it.
  ~CompanionThread();
  CompanionThread(const CompanionThread&) = delete;
  CompanionThread& operator=(const CompanionThread&) = delete;

  /// Calls `here()` on the calling thread and `there()` on the companion thread at the same
  /// time (or after here() on the calling thread, when the companion has not started it by
  /// then), and returns when both have returned. The two must not write what the other
  /// reads or writes. When either throws, its exception is re-thrown here after both have
  /// finished; when both throw, here()'s (the one `here(); there();` would raise).
  template <typename Here, typename There>
  void run_beside(Here&& here, There&& there) {
    using Job = std::remove_reference_t<There>;
    post(&call<Job>, const_cast<void*>(static_cast<const void*>(std::addressof(there))));
    std::exception_ptr here_error, there_error;
    try {
      std::forward<Here>(here)();
    } catch (...) {
      here_error = std::current_exception();
    }
    if (take_back()) {
      try {
        std::forward<There>(there)();
      } catch (...) {
        there_error = std::current_exception();
      }
    } else {
      there_error = wait_for_job();
    }
    if (here_error) std::rethrow_exception(here_error);
    if (there_error) std::rethrow_exception(there_error);
  }

  /// The companion's thread id: where run_beside's `there` runs unless taken back.
  std::thread::id id() const { return thread_.get_id(); }

 private:
  /// A thread's floating-point control modes, without its exception flags.
  struct FloatingPointModes {
    static FloatingPointModes of_this_thread();
    void apply_to_this_thread() const;
#if defined(__SSE__)
    unsigned int mxcsr = 0;  ///< SSE control and status register (the flags ignored).
#else
    std::fenv_t environment{};
#endif
  };

  template <typename Job>
  static void call(void* job) {
    (*static_cast<Job*>(job))();
  }
  /// Hands `job` to the thread (run_job(job_argument)) and wakes it.
  void post(void (*run_job)(void*), void* job_argument);
  /// Claims the posted job for the caller: true when the thread had not claimed it.
  bool take_back();
  /// Waits until the thread has run the posted job; its exception, or null.
  std::exception_ptr wait_for_job();
  /// The thread's loop: waits for a job, claims it unless the caller did, runs it, reports
  /// it done; until stopping_.
  void serve();

  // The job, written by the caller before posted_ is bumped (release), read by the thread
  // after it sees the new count (acquire) and claims the job.
  void (*run_job_)(void*) = nullptr;
  void* job_argument_ = nullptr;
  FloatingPointModes caller_modes_;
  // Written by the thread before finished_ is bumped, read by the caller after.
  std::exception_ptr job_error_;
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> posted_{0};    ///< Jobs posted so far (and the stop).
  std::atomic<std::uint64_t> claimed_{0};   ///< The last job claimed, by either side.
  std::atomic<std::uint64_t> finished_{0};  ///< The last job the thread has run.
  std::thread thread_;                      ///< Last: starts once the rest exists.
};

}  // namespace upkie_rl
