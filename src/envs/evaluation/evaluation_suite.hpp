#pragma once
/// @file
/// EvaluationSuite: named worlds to evaluate controllers in, read from a YAML file
/// (`upkie-rl evaluate --suite NAME|FILE`; the shipped ones are configs/suites/*.yaml).
///
/// Why a file: a robot owner asks "how will this policy fare on my floor?", and the answer
/// is a set of worlds (slippery tires, a payload, a slope, pushes, latency...) with the
/// same episodes for every controller. A file names them once, is versioned beside the
/// configs, and users write their own. The format, every key listed once in
/// evaluation_suite.cpp's readers:
///
///     name: reality                  # printed in the tables
///     description: worlds a real floor gives
///     envs: [Upkie-MuJoCo-Velocity, Upkie-Bullet-Velocity]   # each world on each
///     episodes: 20                   # per world, env and controller
///     seed: 0                        # episode e of every world uses seed + e
///     duration: 10                   # episode length [s], whatever a contender's rate
///     early_fall_time: 1.0           # falls before it are reported apart [s]
///     options: {command_start_delay: 1.0}   # every world's environment options
///     worlds:
///       - name: nominal
///       - name: tire friction 0.4
///         options: {floor_friction: 0.4}

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "envs/core/env_options.hpp"

namespace upkie_rl {

/// One world of a suite on one environment id: the suite's options, then the world's.
struct SuiteWorld {
  std::string name;    ///< As the file names it.
  std::string env_id;  ///< One of the suite's envs.
  EnvOptions options;  ///< Every option of the world, the suite's first.
  /// How many of `options`, at the front, are the suite's: an evaluation's own options go
  /// between them and the world's, so that they may change the suite's but not a world's.
  std::size_t suite_option_count = 0;
};

/// A suite as read and checked: worlds expanded over the envs (world-major order).
struct EvaluationSuite {
  std::string name;
  std::string description;
  std::vector<std::string> env_ids;
  int episodes = 20;
  std::uint64_t seed = 0;
  /// Episode length [agent steps] when `duration` is 0 (the file gives one or the other).
  int max_steps = 1000;
  /// Episode length [s] when positive: each contender gets as many steps as its rate makes
  /// of it (a 100 Hz policy twice the 50 Hz baseline's), and no environment time limit.
  /// Why: a length in steps gives contenders at different rates different seconds of the
  /// same world, and the shorter episodes fall less.
  double duration = 0.0;
  double early_fall_time = 1.0;  ///< [s]
  std::vector<SuiteWorld> worlds;
};

/// Largest suite file read [bytes]: a suite of a thousand worlds is about 100 kB.
inline constexpr std::uintmax_t kMaxSuiteFileBytes = 1 << 20;
/// Most worlds × envs a suite may expand to (each costs episodes × controllers episodes).
inline constexpr std::size_t kMaxSuiteWorlds = 1000;

/// The file of `name_or_path`: the path itself when it names a file, else
/// `configs/suites/<name>.yaml` under the working directory, then under `source_dir` (the
/// checkout the tool was built from).
/// @throws std::invalid_argument listing where it looked.
std::filesystem::path find_suite_file(const std::string& name_or_path,
                                      const std::filesystem::path& source_dir);

/// Checks one world (the tool makes its environment: an unknown option or a value out of
/// range throws std::invalid_argument naming the option).
using SuiteWorldCheck = std::function<void(const SuiteWorld&)>;

/// Reads and checks a suite: unknown keys, missing names, repeated world names and numbers
/// out of range are errors naming the file, the world and the key; then `check` runs on
/// every world, and its error is given the file's and the world's names.
/// @throws std::invalid_argument
EvaluationSuite read_evaluation_suite(const std::filesystem::path& path,
                                      const SuiteWorldCheck& check);

/// The same from YAML text; `where` names it in errors.
EvaluationSuite parse_evaluation_suite(const std::string& text, const std::string& where,
                                       const SuiteWorldCheck& check);

}  // namespace upkie_rl
