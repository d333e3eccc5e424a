#include "agent/supervisor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "agent/agent_error.hpp"
#include "agent/loop_monitor.hpp"

namespace upkie_rl {
namespace {

Supervisor make_supervisor(SupervisorLimits limits = {}) {
  return Supervisor(limits, RobotModel::default_model(), 0.005);
}

TEST(Supervisor, TransitionsOncePerChange) {
  Supervisor supervisor = make_supervisor();
  EXPECT_EQ(supervisor.state(), SupervisorState::kIdle);
  supervisor.transition(SupervisorState::kStarting, "test");
  supervisor.transition(SupervisorState::kStarting, "again");
  EXPECT_EQ(supervisor.state(), SupervisorState::kStarting);
  EXPECT_EQ(supervisor_state_name(SupervisorState::kStopping), "stopping");
}

TEST(Supervisor, AttitudeLimits) {
  const Supervisor supervisor = make_supervisor();
  Observation observation;
  EXPECT_NO_THROW(supervisor.check_observation(observation));
  observation.base_orientation.pitch = 1.1;
  EXPECT_THROW(supervisor.check_observation(observation), SupervisorTrip);
  observation.base_orientation.pitch = 0.0;
  observation.base_orientation.rotation_base_to_world =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()).toRotationMatrix();
  try {
    supervisor.check_observation(observation);
    FAIL() << "a roll of 0.7 rad passed";
  } catch (const SupervisorTrip& trip) {
    EXPECT_NE(std::string(trip.what()).find("roll 0.700 rad"), std::string::npos) << trip.what();
  }
}

TEST(Supervisor, JointPositionAndVelocityLimits) {
  const Supervisor supervisor = make_supervisor();
  const RobotModel& model = *RobotModel::default_model();
  Observation observation;
  observation.servo[kLeftKnee].position = model.servo_limits(kLeftKnee).upper + 0.2;
  EXPECT_THROW(supervisor.check_observation(observation), SupervisorTrip);
  observation.servo[kLeftKnee].position = 0.0;
  observation.servo[kRightWheel].velocity = model.servo_limits(kRightWheel).velocity * 1.3;
  EXPECT_THROW(supervisor.check_observation(observation), SupervisorTrip);
  observation.servo[kRightWheel].velocity = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(supervisor.check_observation(observation), SupervisorTrip);
}

TEST(Supervisor, PolicyOutputMustBeFiniteAndInItsSpace) {
  const Supervisor supervisor = make_supervisor();
  BoxSpace space;
  space.low = {-1.0f};
  space.high = {1.0f};
  space.names = {"ground_velocity"};
  const std::vector<float> fine = {0.5f};
  const std::vector<float> nan = {std::numeric_limits<float>::quiet_NaN()};
  const std::vector<float> out = {1.5f};
  EXPECT_NO_THROW(supervisor.check_policy_output(fine, space));
  EXPECT_THROW(supervisor.check_policy_output(nan, space), SupervisorTrip);
  EXPECT_THROW(supervisor.check_policy_output(out, space), SupervisorTrip);
}

TEST(Supervisor, RateLimitsAndTorqueCap) {
  SupervisorLimits limits;
  limits.max_torque = 0.5;
  limits.max_velocity_command_rate = 200.0;  // 1 rad/s per 5 ms cycle
  limits.max_position_command_rate = 2.0;    // 0.01 rad per cycle
  Supervisor supervisor = make_supervisor(limits);
  Observation observation;
  supervisor.reset_commands(observation);
  ServoAction action{};
  action[kLeftWheel].velocity = 10.0;
  action[kLeftHip].position = 1.0;
  supervisor.limit_commands(action);
  EXPECT_DOUBLE_EQ(action[kLeftWheel].velocity, 1.0);
  EXPECT_NEAR(action[kLeftHip].position, 0.01, 1e-12);
  for (const ServoCommand& command : action) EXPECT_LE(command.maximum_torque, 0.5);
  action[kLeftWheel].velocity = 10.0;
  supervisor.limit_commands(action);
  EXPECT_DOUBLE_EQ(action[kLeftWheel].velocity, 2.0);
}

TEST(Supervisor, StopActionHoldsLegsAndStopsWheels) {
  const Supervisor supervisor = make_supervisor();
  Observation observation;
  observation.servo[kLeftKnee].position = 0.3;
  const ServoAction stop = supervisor.stop_action(observation);
  EXPECT_DOUBLE_EQ(stop[kLeftKnee].position, 0.3);
  EXPECT_DOUBLE_EQ(stop[kLeftWheel].velocity, 0.0);
  EXPECT_TRUE(std::isnan(stop[kLeftWheel].position));
  const RobotModel& model = *RobotModel::default_model();
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    EXPECT_LE(stop[servo].maximum_torque, model.servo_limits(servo).effort);
  }
}

TEST(LoopMonitor, CountsMissesAndTripsOnOverrun) {
  using Clock = LoopMonitor::Clock;
  using std::chrono::microseconds;
  LoopMonitor monitor(0.005, 3, 10.0);
  Clock::time_point now{};
  monitor.on_cycle_start(now);
  for (int i = 0; i < 100; ++i) monitor.on_cycle_start(now += microseconds(5000));
  monitor.on_cycle_start(now += microseconds(9000));  // one miss
  monitor.on_cycle_start(now += microseconds(5000));
  LoopStatistics statistics = monitor.statistics();
  EXPECT_EQ(statistics.cycles, 102);
  EXPECT_EQ(statistics.deadline_misses, 1);
  EXPECT_NEAR(statistics.max_period, 0.009, 1e-9);
  EXPECT_NEAR(statistics.p99_period, 0.005, 1e-5);
  monitor.on_cycle_start(now += microseconds(8000));
  monitor.on_cycle_start(now += microseconds(8000));
  EXPECT_THROW(monitor.on_cycle_start(now += microseconds(8000)), SupervisorTrip);
  LoopMonitor single(0.005, 3, 10.0);
  single.on_cycle_start(now);
  EXPECT_THROW(single.on_cycle_start(now += microseconds(60000)), SupervisorTrip);
}

TEST(Supervisor, LimitsOutsideTheirRangesAreRefused) {
  EXPECT_NO_THROW(SupervisorLimits{}.validate());
  SupervisorLimits limits;
  limits.max_pitch = 1.6;  // beyond what an arcsine pitch can reach: a limit that never trips
  EXPECT_THROW(limits.validate(), AgentError);
  limits = {};
  limits.max_pitch = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(limits.validate(), AgentError);
  limits = {};
  limits.nb_stop_cycles = 2000000000;
  EXPECT_THROW(limits.validate(), AgentError);
  limits = {};
  limits.joint_position_margin = -1e9;
  EXPECT_THROW(limits.validate(), AgentError);
  limits = {};
  limits.max_torque = 1e300;
  EXPECT_THROW(limits.validate(), AgentError);
  limits.max_torque = 100.0;  // the top of each declared range is a limit still
  limits.nb_stop_cycles = 200;
  EXPECT_NO_THROW(limits.validate());
  limits.nb_stop_cycles = 201;
  try {
    limits.validate();
    FAIL() << "201 stop cycles";
  } catch (const AgentError& error) {
    EXPECT_NE(std::string(error.what()).find("stop_cycles"), std::string::npos) << error.what();
  }
}

TEST(Supervisor, EveryLimitIsDeclaredOnceWithTheDefaultInItsRange) {
  SupervisorLimits limits;
  OptionTable table;
  limits.declare_options(table);
  EXPECT_EQ(table.size(), 11u);
  for (const OptionInfo& info : table.info()) {
    EXPECT_LT(info.min, info.max) << info.name;
    EXPECT_FALSE(info.help.empty()) << info.name;
  }
  // The table writes the struct's fields: a value read by name reaches the supervisor.
  table.read("max_pitch", "0.7", "--max-pitch");
  EXPECT_EQ(limits.max_pitch, 0.7);
  table.read("stop_cycles", "12", "--stop-cycles");
  EXPECT_EQ(limits.nb_stop_cycles, 12);
}

}  // namespace
}  // namespace upkie_rl
