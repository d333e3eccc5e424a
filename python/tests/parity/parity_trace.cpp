// parity_trace: the C++ side of the Python package's parity test (test_numpy_parity.py).
// For one environment id it runs the registry's Env with a seed and a fixed action sequence
// and writes, as JSON, what the Python package must return for the same calls: every
// observation, reward and end flag, the actions of a policy on those observations, and the
// raw bytes of a rendered frame. No pybind11, no NumPy: the reference the bindings are
// checked against.
//
// Usage: parity_trace ID SEED STEPS [--policy CHECKPOINT] [--frame FILE WIDTH HEIGHT]

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "envs/registry/env_factory.hpp"
#include "policy/deployed_policy.hpp"
#include "render/robot_renderer.hpp"

namespace {

using upkie_rl::BoxSpace;

/// The action of `step`: each component at a fraction (7 step + 3 i mod 11) / 10 of its
/// range, infinite bounds taken as -1 and 1. test_numpy_parity.py computes the same
/// numbers in double precision, then rounds them to float32, as here.
std::vector<float> scripted_action(const BoxSpace& space, int step) {
  std::vector<float> action(space.size());
  for (std::size_t i = 0; i < space.size(); ++i) {
    const double low = std::isfinite(space.low[i]) ? space.low[i] : -1.0;
    const double high = std::isfinite(space.high[i]) ? space.high[i] : 1.0;
    const double fraction = static_cast<double>((7 * step + 3 * static_cast<int>(i)) % 11) / 10.0;
    action[i] = static_cast<float>(low + fraction * (high - low));
  }
  return action;
}

struct Arguments {
  std::string id;
  std::uint64_t seed = 0;
  int steps = 0;
  std::string policy_path;
  std::string frame_path;
  int frame_width = 0;
  int frame_height = 0;
};

Arguments parse_arguments(int argc, char** argv) {
  if (argc < 4)
    throw std::invalid_argument("usage: parity_trace ID SEED STEPS [--policy P] [--frame F W H]");
  Arguments arguments{argv[1], std::stoull(argv[2]), std::stoi(argv[3])};
  for (int i = 4; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--policy" && i + 1 < argc) {
      arguments.policy_path = argv[++i];
    } else if (flag == "--frame" && i + 3 < argc) {
      arguments.frame_path = argv[++i];
      arguments.frame_width = std::stoi(argv[++i]);
      arguments.frame_height = std::stoi(argv[++i]);
    } else {
      throw std::invalid_argument("parity_trace: unknown or incomplete flag " + flag);
    }
  }
  return arguments;
}

/// Writes the frame of the environment's last state, when it has a simulator's ground truth.
void write_frame(const upkie_rl::Env& env, const Arguments& arguments) {
  const upkie_rl::Observation* observation = env.full_observation();
  if (observation == nullptr || !observation->has_sim) return;
  upkie_rl::RenderConfig config;
  config.width = arguments.frame_width;
  config.height = arguments.frame_height;
  upkie_rl::RobotRenderer renderer(upkie_rl::RobotModel::default_model(), config);
  const auto frame = renderer.render(upkie_rl::robot_pose(*observation));
  std::ofstream(arguments.frame_path, std::ios::binary)
      .write(reinterpret_cast<const char*>(frame.data()),
             static_cast<std::streamsize>(frame.size()));
}

nlohmann::json trace(const Arguments& arguments) {
  // The Python package asks for no time limit of its own (Gymnasium's TimeLimit does it).
  const auto env = upkie_rl::make_env(arguments.id, {{"max_episode_steps", "0"}});
  std::optional<upkie_rl::DeployedPolicy> policy;
  if (!arguments.policy_path.empty())
    policy = upkie_rl::DeployedPolicy::load(arguments.policy_path);
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> policy_action(policy ? policy->action_space().size() : 0);
  nlohmann::json out = {{"observations", nlohmann::json::array()},
                        {"rewards", nlohmann::json::array()},
                        {"terminated", nlohmann::json::array()},
                        {"truncated", nlohmann::json::array()},
                        {"policy_actions", nlohmann::json::array()}};
  // Every observation the env returns, in order (the reset after an episode's end too).
  const auto record = [&] {
    out["observations"].push_back(observation);
    if (!policy) return;
    policy->act(observation, policy_action);
    out["policy_actions"].push_back(policy_action);
  };
  env->reset(arguments.seed, observation);
  record();
  for (int step = 0; step < arguments.steps; ++step) {
    const upkie_rl::StepResult result =
        env->step(scripted_action(env->action_space(), step), observation);
    record();
    out["rewards"].push_back(result.reward);
    out["terminated"].push_back(result.terminated);
    out["truncated"].push_back(result.truncated);
    if (!result.terminated && !result.truncated) continue;
    env->reset(std::nullopt, observation);
    record();
  }
  if (!arguments.frame_path.empty()) write_frame(*env, arguments);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::cout << trace(parse_arguments(argc, argv)).dump() << '\n';
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "parity_trace: " << error.what() << '\n';
    return 1;
  }
}
