#include "spine/servo_action_lag.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/error_message.hpp"
#include "model/joint_order.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Every servo at velocity `velocity` and position `position`.
ServoAction command(double velocity, double position = 0.0) {
  ServoAction action{};
  for (ServoCommand& servo : action) {
    servo.velocity = velocity;
    servo.position = position;
  }
  return action;
}

TEST(ServoActionLag, WithoutDelayOrLagTheCommandPassesAsSent) {
  ServoActionLag lag({});
  lag.reset(command(0.0));
  ServoAction sent = command(3.0, 0.2);
  sent[kLeftHip].kp_scale = 0.5;
  const ServoAction& applied = lag.apply(sent);
  EXPECT_EQ(applied[kLeftHip].velocity, 3.0);
  EXPECT_EQ(applied[kLeftHip].position, 0.2);
  EXPECT_EQ(applied[kLeftHip].kp_scale, 0.5);
}

TEST(ServoActionLag, TheFilterIsExactSoTheStepDoesNotChangeTheResponse) {
  // A unit step held 20 ms through τ = 30 ms, in twenty 1 ms steps and in one 20 ms step:
  // both 1 - exp(-20/30), as a motor of that time constant would answer.
  const double expected = 1.0 - std::exp(-0.02 / 0.03);
  ServoActionLag fine({0, 0.03, 0.001});
  fine.reset(command(0.0));
  double fine_velocity = 0.0;
  for (int step = 0; step < 20; ++step)
    fine_velocity = fine.apply(command(1.0))[kRightWheel].velocity;
  ServoActionLag coarse({0, 0.03, 0.02});
  coarse.reset(command(0.0));
  const double coarse_velocity = coarse.apply(command(1.0))[kRightWheel].velocity;
  EXPECT_NEAR(fine_velocity, expected, 1e-12);
  EXPECT_NEAR(coarse_velocity, expected, 1e-12);
}

TEST(ServoActionLag, DelayComesFirstThenTheLag) {
  ServoActionLag lag({3, 0.01, 0.001});
  lag.reset(command(0.0));
  for (int step = 0; step < 3; ++step) {
    EXPECT_EQ(lag.apply(command(1.0))[kLeftKnee].velocity, 0.0) << "step " << step;
  }
  EXPECT_NEAR(lag.apply(command(1.0))[kLeftKnee].velocity, 1.0 - std::exp(-0.1), 1e-12);
}

TEST(ServoActionLag, ANanPositionPassesAndTheFilterRestartsAfterIt) {
  ServoActionLag lag({0, 0.05, 0.001});
  lag.reset(command(0.0, 0.0));
  EXPECT_TRUE(std::isnan(lag.apply(command(0.0, kNaN))[kLeftWheel].position));
  // From "no position loop" to a target: the target at once, not a ramp from NaN.
  EXPECT_EQ(lag.apply(command(0.0, 0.4))[kLeftWheel].position, 0.4);
  EXPECT_LT(lag.apply(command(0.0, 1.0))[kLeftWheel].position, 0.5);
}

TEST(ServoActionLag, GainsAndLimitsAreDelayedNotFiltered) {
  ServoActionLag lag({1, 0.05, 0.001});
  lag.reset(command(0.0));
  ServoAction sent = command(0.0);
  sent[kRightHip].kd_scale = 2.0;
  sent[kRightHip].maximum_torque = 5.0;
  EXPECT_EQ(lag.apply(sent)[kRightHip].kd_scale, 1.0);
  const ServoAction& applied = lag.apply(sent);
  EXPECT_EQ(applied[kRightHip].kd_scale, 2.0);
  EXPECT_EQ(applied[kRightHip].maximum_torque, 5.0);
}

TEST(ServoActionLag, SettingsOutOfTheirDomainAreRefusedNamingTheValue) {
  const auto message = [](const ServoActionLagSettings& settings) {
    return testing::error_message<SpineError>([&] { ServoActionLag lag(settings); });
  };
  EXPECT_NE(message({-1, 0.0, 0.001}).find("action delay must be in [0, 100000]"),
            std::string::npos);
  EXPECT_NE(message({0, kNaN, 0.001}).find("action lag must be in [0, 10] s, got nan"),
            std::string::npos);
  EXPECT_NE(message({0, 0.0, 0.0}).find("simulation step must be positive"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
