#include "base/companion_thread.hpp"

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "base/spin_then_wait.hpp"

namespace upkie_rl {

namespace {

#if defined(__SSE__)
// MXCSR's sticky exception flags (bits 0-5): state of a thread's past operations, not modes.
constexpr unsigned int kMxcsrFlags = 0x3f;
#endif

}  // namespace

CompanionThread::FloatingPointModes CompanionThread::FloatingPointModes::of_this_thread() {
  FloatingPointModes modes;
#if defined(__SSE__)
  modes.mxcsr = _mm_getcsr() & ~kMxcsrFlags;
#else
  std::fegetenv(&modes.environment);
#endif
  return modes;
}

void CompanionThread::FloatingPointModes::apply_to_this_thread() const {
#if defined(__SSE__)
  const unsigned int current = _mm_getcsr();
  if ((current & ~kMxcsrFlags) != mxcsr) _mm_setcsr((current & kMxcsrFlags) | mxcsr);
#else
  std::fesetenv(&environment);
#endif
}

CompanionThread::CompanionThread() : thread_([this] { serve(); }) {}

CompanionThread::~CompanionThread() {
  stopping_.store(true, std::memory_order_relaxed);
  posted_.fetch_add(1, std::memory_order_release);
  posted_.notify_one();
  thread_.join();
}

void CompanionThread::post(void (*run_job)(void*), void* job_argument) {
  run_job_ = run_job;
  job_argument_ = job_argument;
  caller_modes_ = FloatingPointModes::of_this_thread();
  posted_.fetch_add(1, std::memory_order_release);
  posted_.notify_one();
}

bool CompanionThread::take_back() {
  const std::uint64_t posted = posted_.load(std::memory_order_relaxed);
  std::uint64_t unclaimed = posted - 1;
  return claimed_.compare_exchange_strong(unclaimed, posted, std::memory_order_acq_rel);
}

std::exception_ptr CompanionThread::wait_for_job() {
  const std::uint64_t posted = posted_.load(std::memory_order_relaxed);
  spin_then_wait(finished_, [posted](std::uint64_t finished) { return finished == posted; });
  return std::exchange(job_error_, nullptr);
}

void CompanionThread::serve() {
  std::uint64_t seen = 0;
  while (true) {
    spin_then_wait(posted_, [seen](std::uint64_t posted) { return posted != seen; });
    // The newest job: a job the caller took back is not posted again, and the caller posts
    // the next one only once this one is done, by either side.
    seen = posted_.load(std::memory_order_acquire);
    if (stopping_.load(std::memory_order_relaxed)) return;
    std::uint64_t unclaimed = seen - 1;
    if (!claimed_.compare_exchange_strong(unclaimed, seen, std::memory_order_acq_rel)) {
      continue;  // The caller runs it.
    }
    caller_modes_.apply_to_this_thread();
    try {
      run_job_(job_argument_);
    } catch (...) {
      job_error_ = std::current_exception();
    }
    finished_.store(seen, std::memory_order_release);
    finished_.notify_one();
  }
}

}  // namespace upkie_rl
