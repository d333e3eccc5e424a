#pragma once
/// @file
/// The classical baseline of configs/velocity.yaml, for the tests that drive its robot.

namespace upkie_rl::testing {

/// configs/velocity.yaml's base controller: `--controller lqr` designed on MuJoCo, the base
/// of its residual policies.
inline constexpr const char* kVelocityBaseline =
    "balancer:10.3236647,0.264768692,2.80279398,0.601664129,0.0183275488,0.0133529685,"
    "-0.000164539185,1.00066929,0.0579007226,0.13798033";

}  // namespace upkie_rl::testing
