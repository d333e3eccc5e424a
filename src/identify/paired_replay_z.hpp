#pragma once
/// @file
/// Whether one set of replay errors is worse than another beyond chance, replay by replay.
///
/// Why: a delay of d steps and a lag tau shift the commands alike to first order, so at
/// 5 ms steps a neighbouring delay with the lag refitted predicts a log nearly as well. On
/// the 60 s Bullet logs of identify_goals (seeds 1-5) the neighbours' short refits predicted
/// 6-26 % worse, or 3 % better on the seed whose delay ended one step short; what tells a
/// difference the log pins down from one it does not is whether it holds replay after replay
/// (z 3.5-5.5 on seeds 1 and 4, 1.0-1.8 on seeds 2 and 5), not its size.

#include <cstddef>
#include <span>

namespace upkie_rl {

/// The paired z statistic of `worse` against `better`: the mean over replays of each
/// replay's sum of squared errors under `worse` minus under `better`, divided by its
/// standard error. Both list replay after replay, `per_replay` errors each (the same
/// replays). Replays are the independent units: the errors within one are strongly
/// correlated. Positive when `worse` predicts worse; +infinity when every replay differs by
/// the same amount and it is positive, 0 when nothing differs.
/// @throws std::invalid_argument on sizes that do not match or fewer than 2 replays.
double paired_replay_z(std::span<const double> worse, std::span<const double> better,
                       std::size_t per_replay);

}  // namespace upkie_rl
