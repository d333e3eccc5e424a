#pragma once
/// @file
/// The --controller option of rollout, bench and evaluate: one help text, so that every
/// command lists the same choices and accepts each of them (resolve_controller_spec).

namespace upkie_rl::apps {

/// Help of --controller: every built-in controller spec.
inline constexpr const char* kControllerHelp =
    "zero (neutral action), linear:k1,k2,k3,k4 (ground velocity [m/s] = k.[theta [rad], p "
    "[m], theta_dot [rad/s], p_dot [m/s]]), lqr (designed on this environment; on a velocity task, "
    "its balancer designed "
    "on the pendulum of its backend) or lqr:theta_max,p_max,theta_dot_max,p_dot_max,u_max (Bryson "
    "weights, SI units)";

}  // namespace upkie_rl::apps
