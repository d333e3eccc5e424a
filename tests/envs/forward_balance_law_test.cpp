// ForwardBalanceLaw: the velocity task's wheel law apart from its observation layout, and
// the filter gains it is given at another rate.

#include "envs/controllers/forward_balance_law.hpp"

#include <gtest/gtest.h>

namespace upkie_rl {
namespace {

VelocityBalancerGains test_gains() {
  VelocityBalancerGains gains;
  gains.feedback = {10.0, 0.5, 2.0, 0.7};
  gains.pitch_offset = 0.02;
  gains.command_offset = 0.01;
  gains.command_per_velocity = 1.0;
  return gains;
}

TEST(ForwardBalanceLaw, AtRestCommandsTheOffsetsOfItsSteadyState) {
  ForwardBalanceLaw law(test_gains(), 0.02, 0.15, 0.3);
  // Standing at the steady pitch: u = command_offset, nothing else.
  EXPECT_DOUBLE_EQ(law.ground_velocity({.pitch = 0.02}), 0.01);
  // Leaning 0.1 rad further forward: the wheels roll under the body.
  EXPECT_NEAR(law.ground_velocity({.pitch = 0.12}), 0.01 + 10.0 * 0.1, 1e-12);
}

TEST(ForwardBalanceLaw, ReferenceRampsTowardTheCommand) {
  const double timestep = 0.02;
  ForwardBalanceLaw law(test_gains(), timestep, 1.0, 1.0);
  // One step toward a 1 m/s command moves the reference by kMaxAcceleration·dt only, and
  // the (unfiltered, at rest) velocity error is then -reference.
  const double reference = ForwardBalanceLaw::kMaxAcceleration * timestep;
  const double expected = 0.01 + 1.0 * reference + 10.0 * (0.0 - 0.02) + 2.0 * (0.0 - reference) +
                          0.7 * (0.0 - reference) * timestep;
  EXPECT_NEAR(law.ground_velocity({.command = 1.0}), expected, 1e-12);
}

TEST(ForwardBalanceLaw, ExcitationAddsToTheGroundVelocityAndResetClears) {
  ForwardBalanceLaw law(test_gains(), 0.02, 0.15, 0.3);
  law.set_excitation(0.3);
  EXPECT_NEAR(law.ground_velocity({.pitch = 0.02}), 0.31, 1e-12);
  law.ground_velocity({.command = 1.0, .odometry_velocity = 0.5});
  EXPECT_GT(law.filtered_velocity(), 0.0);
  law.reset();
  EXPECT_EQ(law.filtered_velocity(), 0.0);
  EXPECT_EQ(law.last_ground_velocity(), 0.0);
}

TEST(ForwardBalanceLaw, FilterGainAtAnotherRateKeepsTheTimeConstant) {
  EXPECT_EQ(filter_gain_at_rate(0.15, 0.02, 0.02), 0.15);  // to the bit
  // Four steps of 5 ms leave what one step of 20 ms leaves of a step input.
  const double gain = filter_gain_at_rate(0.15, 0.02, 0.005);
  double filtered = 0.0;
  for (int step = 0; step < 4; ++step) filtered += gain * (1.0 - filtered);
  EXPECT_NEAR(filtered, 0.15, 1e-12);
}

}  // namespace
}  // namespace upkie_rl
