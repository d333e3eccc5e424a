// CompanionThread: a job beside the caller, on one thread made once; exceptions and the
// floating-point modes reach across.

#include "base/companion_thread.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cfenv>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "common/allocation_counter.hpp"

namespace upkie_rl {
namespace {

// Raises `mine`, then waits for `other` to be raised: true when it was, false when it was
// still down after a minute (the two sides do not run at the same time).
bool meet(std::atomic<bool>& mine, const std::atomic<bool>& other) {
  mine.store(true, std::memory_order_release);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  while (!other.load(std::memory_order_acquire)) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::yield();
  }
  return true;
}

// Runs `job` on the companion for sure: the caller's side waits until it has started there
// (else, done first, the caller would take the job back). False if it never started.
template <typename Job>
bool run_on_companion(CompanionThread& companion, Job job) {
  std::atomic<bool> here_started{false}, there_started{false};
  bool started = false;
  companion.run_beside([&] { started = meet(here_started, there_started); },
                       [&] {
                         there_started.store(true, std::memory_order_release);
                         job();
                       });
  return started;
}

TEST(CompanionThread, RunsTheJobOnItsThreadWhileTheCallerRunsTheOther) {
  CompanionThread companion;
  EXPECT_NE(companion.id(), std::this_thread::get_id());
  std::atomic<bool> here_started{false}, there_started{false};
  bool here_met = false, there_met = false;
  std::thread::id here_thread, there_thread;
  companion.run_beside(
      [&] {
        here_thread = std::this_thread::get_id();
        here_met = meet(here_started, there_started);
      },
      [&] {
        there_thread = std::this_thread::get_id();
        there_met = meet(there_started, here_started);
      });
  // Each side saw the other running: they overlapped.
  EXPECT_TRUE(here_met);
  EXPECT_TRUE(there_met);
  EXPECT_EQ(here_thread, std::this_thread::get_id());
  EXPECT_EQ(there_thread, companion.id());
}

// Whichever side runs the job (the caller takes back a job the companion has not started by
// the time it is done with its own), it runs once per call.
TEST(CompanionThread, EachJobRunsExactlyOnceOnEitherThread) {
  CompanionThread companion;
  const std::thread::id caller = std::this_thread::get_id();
  int on_companion = 0, on_caller = 0;
  for (int round = 0; round < 20000; ++round) {
    int runs = 0;
    std::thread::id runner;
    companion.run_beside([] {},
                         [&] {
                           ++runs;
                           runner = std::this_thread::get_id();
                         });
    ASSERT_EQ(runs, 1) << "round " << round;
    if (runner == companion.id()) {
      ++on_companion;
    } else {
      ASSERT_EQ(runner, caller) << "round " << round;
      ++on_caller;
    }
  }
  EXPECT_EQ(on_companion + on_caller, 20000);
  RecordProperty("jobs_on_companion", on_companion);
  RecordProperty("jobs_taken_back", on_caller);
}

// Many jobs in a row on one companion: each sees what the caller wrote before the call, and the
// caller sees what it wrote, with nothing allocated per call.
TEST(CompanionThread, ServesManyJobsWithoutAllocating) {
  CompanionThread companion;
  std::vector<std::int64_t> here_values(64), there_values(64);
  const std::size_t allocations = testing::all_threads_allocations.load();
  for (std::int64_t round = 0; round < 5000; ++round) {
    // The caller writes both halves' inputs; each side then rewrites its own half.
    for (std::size_t i = 0; i < here_values.size(); ++i) {
      here_values[i] = round;
      there_values[i] = -round;
    }
    companion.run_beside(
        [&] {
          for (std::int64_t& value : here_values) value = 2 * value + 1;
        },
        [&] {
          for (std::int64_t& value : there_values) value = 3 * value - 1;
        });
    for (std::size_t i = 0; i < here_values.size(); ++i) {
      ASSERT_EQ(here_values[i], 2 * round + 1) << "round " << round;
      ASSERT_EQ(there_values[i], -3 * round - 1) << "round " << round;
    }
  }
  EXPECT_EQ(testing::all_threads_allocations.load(), allocations);
}

// Either side's exception reaches the caller once both have finished; with both throwing,
// the caller's own (what running here then there on one thread would raise). The companion
// goes on serving afterwards.
TEST(CompanionThread, ExceptionsReachTheCallerAfterBothSidesFinished) {
  CompanionThread companion;
  bool here_done = false, there_done = false;
  const auto here = [&] { here_done = true; };
  const auto there = [&] { there_done = true; };
  const auto here_throws = [] { throw std::runtime_error("here failed"); };
  const auto there_throws = [] { throw std::invalid_argument("there failed"); };
  const auto message = [&](const auto& left, const auto& right) {
    here_done = there_done = false;
    try {
      companion.run_beside(left, right);
    } catch (const std::exception& error) {
      return std::string(error.what());
    }
    return std::string("nothing thrown");
  };
  EXPECT_EQ(message(here, there_throws), "there failed");
  EXPECT_TRUE(here_done);
  EXPECT_THROW(companion.run_beside(here, there_throws), std::invalid_argument);
  EXPECT_EQ(message(here_throws, there), "here failed");
  EXPECT_TRUE(there_done);
  EXPECT_EQ(message(here_throws, there_throws), "here failed");
  EXPECT_EQ(message(here, there), "nothing thrown");
  EXPECT_TRUE(here_done);
  EXPECT_TRUE(there_done);

  // Thrown on the companion thread itself: the caller's side waits until it has started.
  std::atomic<bool> here_started{false}, there_started{false};
  std::thread::id thrower;
  const auto there_throws_on_companion = [&] {
    there_started.store(true, std::memory_order_release);
    thrower = std::this_thread::get_id();
    throw std::invalid_argument("there failed");
  };
  EXPECT_EQ(message([&] { meet(here_started, there_started); }, there_throws_on_companion),
            "there failed");
  EXPECT_EQ(thrower, companion.id());
  here_started = there_started = false;
  thrower = {};
  const auto here_meets_then_throws = [&] {
    meet(here_started, there_started);
    throw std::runtime_error("here failed");
  };
  EXPECT_EQ(message(here_meets_then_throws, there_throws_on_companion), "here failed");
  EXPECT_EQ(thrower, companion.id());
  EXPECT_EQ(message(here, there), "nothing thrown");
}

// Restores the calling thread's floating-point environment on scope exit.
class FloatingPointEnvironmentGuard {
 public:
  FloatingPointEnvironmentGuard() {
    std::fegetenv(&saved_);
#if defined(__SSE__)
    mxcsr_ = _mm_getcsr();
#endif
  }
  ~FloatingPointEnvironmentGuard() {
    std::fesetenv(&saved_);
#if defined(__SSE__)
    _mm_setcsr(mxcsr_);
#endif
  }

 private:
  std::fenv_t saved_{};
#if defined(__SSE__)
  unsigned int mxcsr_ = 0;
#endif
};

std::uint32_t bits(float value) {
  std::uint32_t result = 0;
  std::memcpy(&result, &value, sizeof(result));
  return result;
}

// 1/3 in float: rounded to nearest, 0x3eaaaaab; toward zero, 0x3eaaaaaa. Volatile, so that it
// is computed at run time under the thread's rounding mode.
float one_third() {
  volatile float one = 1.0f, three = 3.0f;
  return one / three;
}

TEST(CompanionThread, TheJobRunsUnderTheCallersRoundingMode) {
  CompanionThread companion;
  const float nearest = one_third();
  FloatingPointEnvironmentGuard guard;
  ASSERT_EQ(std::fesetround(FE_TOWARDZERO), 0);
  const float toward_zero = one_third();
  ASSERT_NE(bits(toward_zero), bits(nearest));
  float there = 0.0f;
  ASSERT_TRUE(run_on_companion(companion, [&] { there = one_third(); }));
  EXPECT_EQ(bits(there), bits(toward_zero));
  // And back to the default when the caller goes back to it.
  ASSERT_EQ(std::fesetround(FE_TONEAREST), 0);
  ASSERT_TRUE(run_on_companion(companion, [&] { there = one_third(); }));
  EXPECT_EQ(bits(there), bits(nearest));
}

#if defined(__SSE__)
// Flush-to-zero (libtorch's set_flush_denormal, say) is the caller's choice too.
TEST(CompanionThread, TheJobFlushesDenormalsWhenTheCallerDoes) {
  CompanionThread companion;
  volatile float tiny = 1e-30f, scale = 1e-10f;
  const auto product = [&] { return tiny * scale; };  // 1e-40: a denormal
  ASSERT_NE(product(), 0.0f);
  FloatingPointEnvironmentGuard guard;
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  ASSERT_EQ(product(), 0.0f);
  float there = 1.0f;
  ASSERT_TRUE(run_on_companion(companion, [&] { there = product(); }));
  EXPECT_EQ(there, 0.0f);
}
#endif

}  // namespace
}  // namespace upkie_rl
