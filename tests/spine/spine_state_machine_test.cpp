#include "spine/spine_state_machine.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

constexpr auto kNone = static_cast<std::uint32_t>(Request::kNone);
constexpr auto kAction = static_cast<std::uint32_t>(Request::kAction);
constexpr auto kStart = static_cast<std::uint32_t>(Request::kStart);
constexpr auto kStop = static_cast<std::uint32_t>(Request::kStop);
constexpr auto kError = static_cast<std::uint32_t>(Request::kError);

/// Runs idle stop cycles until Start is accepted.
void run_stop_cycles(SpineStateMachine& machine, int count) {
  for (int i = 0; i < count; ++i) {
    EXPECT_EQ(machine.on_cycle_beginning(kNone), std::nullopt);
    EXPECT_EQ(machine.on_cycle_end(), std::nullopt);
  }
}

TEST(SpineStateMachine, StartsInSendStops) {
  SpineStateMachine machine;
  EXPECT_EQ(machine.state(), SpineState::kSendStops);
  EXPECT_TRUE(machine.is_stopped());
}

TEST(SpineStateMachine, StartStaysPendingUntilFiveStopCycles) {
  SpineStateMachine machine;
  for (int cycle = 0; cycle < 5; ++cycle) {
    EXPECT_EQ(machine.on_cycle_beginning(kStart), std::nullopt) << cycle;
    EXPECT_EQ(machine.state(), SpineState::kSendStops);
    machine.on_cycle_end();
  }
  EXPECT_EQ(machine.on_cycle_beginning(kStart), std::nullopt);
  EXPECT_EQ(machine.state(), SpineState::kReset);
  EXPECT_EQ(machine.on_cycle_end(), Request::kNone);  // entering Idle clears the request
  EXPECT_EQ(machine.state(), SpineState::kIdle);
}

TEST(SpineStateMachine, IdleTransitions) {
  SpineStateMachine machine;
  run_stop_cycles(machine, 5);
  machine.on_cycle_beginning(kStart);
  machine.on_cycle_end();
  ASSERT_EQ(machine.state(), SpineState::kIdle);

  EXPECT_EQ(machine.on_cycle_beginning(kNone), std::nullopt);
  EXPECT_EQ(machine.state(), SpineState::kIdle);
  machine.on_cycle_end();

  EXPECT_EQ(machine.on_cycle_beginning(kAction), std::nullopt);
  EXPECT_EQ(machine.state(), SpineState::kStep);
  EXPECT_EQ(machine.on_cycle_end(), Request::kNone);
  EXPECT_EQ(machine.state(), SpineState::kIdle);

  EXPECT_EQ(machine.on_cycle_beginning(kStart), Request::kNone);  // warn, clear, stay
  EXPECT_TRUE(machine.start_ignored());
  EXPECT_EQ(machine.state(), SpineState::kIdle);
  machine.on_cycle_end();

  EXPECT_EQ(machine.on_cycle_beginning(17), Request::kError);  // unknown code
  EXPECT_EQ(machine.state(), SpineState::kIdle);
  EXPECT_EQ(machine.on_cycle_beginning(kError), Request::kError);
  machine.on_cycle_end();

  EXPECT_EQ(machine.on_cycle_beginning(kStop), Request::kNone);
  EXPECT_EQ(machine.state(), SpineState::kSendStops);
}

TEST(SpineStateMachine, SendStopsRefusesActionsAndRestartsOnStop) {
  SpineStateMachine machine;
  run_stop_cycles(machine, 3);
  EXPECT_EQ(machine.on_cycle_beginning(kAction), Request::kError);
  EXPECT_EQ(machine.state(), SpineState::kSendStops);
  machine.on_cycle_end();
  EXPECT_EQ(machine.on_cycle_beginning(kError), std::nullopt);  // stays for the agent
  machine.on_cycle_end();
  // 5 cycles spent; a Stop resets the counter.
  EXPECT_EQ(machine.on_cycle_beginning(kStop), Request::kNone);
  machine.on_cycle_end();
  EXPECT_EQ(machine.on_cycle_beginning(kStart), std::nullopt);
  EXPECT_EQ(machine.state(), SpineState::kSendStops);
  EXPECT_EQ(machine.on_cycle_beginning(0xdeadbeef), Request::kError);
}

TEST(SpineStateMachine, InterruptShutsDownAfterFiveCycles) {
  SpineStateMachine machine;
  run_stop_cycles(machine, 5);
  machine.on_cycle_beginning(kStart);
  machine.on_cycle_end();
  machine.on_interrupt();
  EXPECT_EQ(machine.state(), SpineState::kShutdown);
  EXPECT_TRUE(machine.is_stopped());
  for (int cycle = 0; cycle < 4; ++cycle) {
    EXPECT_EQ(machine.on_cycle_beginning(kAction), std::nullopt);  // requests ignored
    machine.on_cycle_end();
    EXPECT_EQ(machine.state(), SpineState::kShutdown) << cycle;
  }
  machine.on_cycle_beginning(kNone);
  machine.on_cycle_end();
  EXPECT_TRUE(machine.is_over());
  machine.on_interrupt();  // no way back
  EXPECT_TRUE(machine.is_over());
}

TEST(SpineStateMachine, AbortEndsOnlyAShutdown) {
  SpineStateMachine machine;
  machine.abort();  // not shutting down: nothing to abort
  EXPECT_EQ(machine.state(), SpineState::kSendStops);
  machine.on_interrupt();
  machine.abort();
  EXPECT_TRUE(machine.is_over());
}

TEST(SpineStateMachine, StateNames) {
  EXPECT_EQ(spine_state_name(SpineState::kSendStops), "SendStops");
  EXPECT_EQ(spine_state_name(SpineState::kOver), "Over");
  EXPECT_EQ(static_cast<int>(SpineState::kStep), 3);
}

}  // namespace
}  // namespace upkie_rl
