// The options of the seed's balance reward and termination (balance_reward.hpp,
// balance_termination.hpp), shared by the pendulum and the servos task.

#include "envs/core/shared_options.hpp"
#include "envs/tasks/balance_reward.hpp"
#include "envs/tasks/balance_termination.hpp"

namespace upkie_rl {

void BalanceTermination::declare_options(OptionTable& table) {
  table.add_real(kFallPitchOption, &fall_pitch);
  table.add_real("max_position_drift", &max_position_drift, 0.0, kOptionHuge,
                 "terminate when |p - p0| exceeds it [m]");
  table.add_real("max_angular_velocity", &max_angular_velocity, 0.0, kOptionHuge,
                 "terminate when |pitch rate| exceeds it [rad/s]");
  table.add_real("max_linear_velocity", &max_linear_velocity, 0.0, kOptionHuge,
                 "terminate when |ground velocity| exceeds it [m/s]");
}

void BalanceRewardWeights::declare_options(OptionTable& table) {
  table.add_real("w_theta", &w_theta, -kOptionHuge, kOptionHuge, "reward weight of pitch^2");
  table.add_real("w_theta_dot", &w_theta_dot, -kOptionHuge, kOptionHuge,
                 "reward weight of pitch rate^2");
  table.add_real("w_p_dot", &w_p_dot, -kOptionHuge, kOptionHuge,
                 "reward weight of ground velocity^2");
  table.add_real("w_a", &w_a, -kOptionHuge, kOptionHuge, "reward weight of action^2");
  table.add_real("w_s", &w_s, -kOptionHuge, kOptionHuge, "reward weight of (action change)^2");
  table.add_real("w_accel", &w_accel, -kOptionHuge, kOptionHuge,
                 "reward weight of (second action difference)^2");
}

}  // namespace upkie_rl
