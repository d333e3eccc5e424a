#pragma once
/// @file
/// What a world's count of falls says about its fall rate: the one-sided upper confidence
/// bound of the rate, and whether one contender falls more often than another.
///
/// Why: a suite runs 20 episodes per world. No fall in 20 still allows a fall rate of up to
/// 13.9 % (95 % confidence), and one fall where the baseline has none is what two equal
/// controllers give half the time (p 0.50): the suite prints both, so that a robot owner
/// reads its counts with their margin. Boost.Math's distributions (header-only, libboost-dev)
/// do the arithmetic; each call costs microseconds and runs once per world.

namespace upkie_rl::apps {

/// The confidence of the bounds and tests the suite prints.
inline constexpr double kFallConfidence = 0.95;

/// The largest fall rate that `falls` in `episodes` leave plausible at `confidence`
/// (Clopper-Pearson, one-sided): 0 of 20 -> 0.139, 1 of 20 -> 0.216; 1 when every episode
/// fell; NaN without episodes.
double fall_rate_upper_bound(int falls, int episodes, double confidence = kFallConfidence);

/// One-sided Fisher exact test that `a` falls more often than `b`: the probability, were
/// their fall rates equal, that `a` would take at least `a_falls` of the falls both had
/// (1/20 against 0/20: 0.5; 15/20 against 1/20: 5e-6). 1 when `a` has no fall; NaN without
/// episodes.
double more_falls_p_value(int a_falls, int a_episodes, int b_falls, int b_episodes);

}  // namespace upkie_rl::apps
