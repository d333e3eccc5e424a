#pragma once
/// @file
/// The random initial state that evaluations (`upkie-rl rollout`, `upkie-rl evaluate`,
/// `upkie_rl.evaluate`) start episodes from unless asked for the environment's exact start:
/// the pendulum's own start has no noise, so N seeded episodes would be one episode N
/// times.

#include <span>
#include <string>

#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// One initial-state randomisation bound of evaluations.
struct EvaluationStartBound {
  const char* option;  ///< An `init_rand_*` option of the registry.
  double value;        ///< Its bound in evaluations, in the option's SI unit.
};

/// The evaluations' bounds: initial pitch in ±0.05 rad, pitch rate in ±0.1 rad/s.
inline constexpr EvaluationStartBound kEvaluationStart[] = {{"init_rand_pitch", 0.05},
                                                            {"init_rand_omega_y", 0.1}};

/// Most episodes `upkie_rl.evaluate(episodes=...)` runs, so that a typo cannot start a run
/// that never ends: the bound of every command's --episodes too (add_episodes_option in
/// src/cli/common_flags.hpp; python/tests/test_arguments.py runs `upkie-rl evaluate`).
inline constexpr int kMaxEvaluationEpisodes = 1'000'000;

/// Help of the CLI's --exact-start flag (rollout, evaluate).
inline constexpr const char* kExactStartHelp =
    "Start episodes from the environment's own initial state (the seed's, for parity) "
    "instead of the evaluations' random one (initial pitch in +-0.05 rad, pitch rate in "
    "+-0.1 rad/s, for options left at 0)";

/// The options to add to `given` for `env_id`'s episodes to start from the evaluations'
/// random initial state: each bound of kEvaluationStart that the id accepts, whose default
/// is zero and that `given` does not set (a user's or a training configuration's value wins).
/// @throws std::invalid_argument on an unknown id.
EnvOptions evaluation_start_options(const std::string& env_id, const EnvOptions& given);

/// `given` followed by evaluation_start_options(env_id, given).
EnvOptions with_evaluation_start(const std::string& env_id, const EnvOptions& given);

/// Which start an evaluation's episodes had, for the lines that report it: "from random
/// starts" when one of kEvaluationStart's options is nonzero in `options` (the episodes'
/// options, the evaluations' start included) or by `env_id`'s default, else "from the exact
/// start (--exact-start)" when `exact_start`, else "from the environment's own start" (an
/// id without initial-state randomisation).
/// @throws std::invalid_argument on an unknown id.
std::string evaluation_start_words(const std::string& env_id, const EnvOptions& options,
                                   bool exact_start);

/// A warning when two or more episodes all had the same return and length (the episodes
/// of an environment without initial-state randomisation); empty otherwise.
std::string identical_episodes_warning(std::span<const double> returns,
                                       std::span<const int> lengths);

}  // namespace upkie_rl
