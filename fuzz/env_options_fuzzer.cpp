/// @file
/// libFuzzer target: environment options, through the path `--env-option key=value` takes
/// (parse_env_options, then the registry; Python's keyword arguments reach the same
/// registry). An input's first line is the environment: a byte b < 250 picks registered id
/// b % 25, anything else is taken as an id as written; each further line is one
/// `--env-option` string. For every id the options are parsed and checked as make_env
/// does (parse_env_settings), and carried to another id as a rollout carries a policy's
/// task options (task_options). On the Mock backend (no physics engine, cheap)
/// the environment is made, reset and stepped: its observations and rewards must be finite.
/// Bullet and MuJoCo environments are not made (their engines cost milliseconds per input),
/// nor Spine ones (they would wait for a spine). Refusing an input with
/// std::invalid_argument (an option mistake, as registry.hpp documents) is the expected
/// outcome; a crash, a hang, a sanitizer report or another exception is a bug.

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "envs/registry/env_factory.hpp"
#include "envs/registry/env_settings.hpp"
#include "envs/registry/registry.hpp"

namespace {

void check_finite(const std::vector<float>& values) {
  for (float value : values) {
    if (!std::isfinite(value)) std::abort();
  }
}

/// Makes the Mock environment, resets it and takes a few steps with actions inside, on and
/// outside the bounds (they are clamped).
void run_mock(const std::string& id, const upkie_rl::EnvOptions& options) {
  const std::unique_ptr<upkie_rl::Env> env = upkie_rl::make_env(id, options);
  const upkie_rl::BoxSpace& actions = env->action_space();
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(actions.size());
  env->reset(7, observation);
  check_finite(observation);
  for (int step = 0; step < 3; ++step) {
    for (std::size_t i = 0; i < action.size(); ++i) {
      const float low = std::isfinite(actions.low[i]) ? actions.low[i] : -1.0f;
      const float high = std::isfinite(actions.high[i]) ? actions.high[i] : 1.0f;
      action[i] = step == 0 ? 0.5f * (low + high) : (step == 1 ? high : 2.0f * low - high);
    }
    const upkie_rl::StepResult result = env->step(action, observation);
    check_finite(observation);
    if (!std::isfinite(result.reward)) std::abort();
    if (result.terminated || result.truncated) env->reset(std::nullopt, observation);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<std::string> ids = upkie_rl::registered_env_ids();
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  std::string first;
  std::getline(lines, first);
  const auto pick = first.empty() ? 0u : static_cast<unsigned char>(first[0]);
  const std::string id = pick < 250 ? ids[pick % ids.size()] : first;
  std::vector<std::string> key_values;
  for (std::string line; std::getline(lines, line);) key_values.push_back(line);
  upkie_rl::EnvOptions options;
  try {
    options = upkie_rl::parse_env_options(key_values);
    const upkie_rl::EnvId parsed = upkie_rl::parse_env_id(id);
    upkie_rl::parse_env_settings(parsed, id, options);
    upkie_rl::task_options(id, options, ids[(pick * 7 + 3) % ids.size()]);
    if (parsed.backend == upkie_rl::EnvBackend::kMock) run_mock(id, options);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
