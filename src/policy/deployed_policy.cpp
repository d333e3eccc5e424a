#include "policy/deployed_policy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "policy/checkpoint_gate.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/policy_output_error.hpp"
#include "policy/space_json.hpp"

namespace upkie_rl {

namespace {

void check_size(std::size_t size, std::size_t expected, const char* what) {
  if (size != expected) {
    throw std::invalid_argument(std::string("DeployedPolicy: ") + what + " has " +
                                std::to_string(size) + " values, expected " +
                                std::to_string(expected));
  }
}

bool all_finite(std::span<const float> values) {
  return std::ranges::all_of(values, [](float value) { return std::isfinite(value); });
}

/// "component 3 (pitch_rate) is nan" for the first non-finite value of `values`, or "".
std::string first_non_finite(std::span<const float> values, const BoxSpace& space) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i])) continue;
    const std::string name = i < space.names.size() ? " (" + space.names[i] + ")" : "";
    const char* value = std::isnan(values[i]) ? "nan" : values[i] > 0.0f ? "inf" : "-inf";
    return "component " + std::to_string(i) + name + " is " + value;
  }
  return "";
}

}  // namespace

DeployedPolicy DeployedPolicy::load(const std::filesystem::path& path) {
  return from_checkpoint(read_checkpoint_file(path), "checkpoint " + path.string());
}

DeployedPolicy DeployedPolicy::from_checkpoint(const CheckpointFile& file,
                                               const std::string& where) {
  check_checkpoint(file, where);
  DeployedPolicy policy;
  try {
    const nlohmann::json& header = file.header;
    if (header.value(checkpoint_header::kFormat, "") != kCheckpointFormat) {
      throw CheckpointError("not an upkie-rl model");
    }
    policy.env_id_ = checkpoint_env_id(header);
    policy.env_options_ = checkpoint_env_options(header);
    policy.observation_space_ = space_from_json(header.at(checkpoint_header::kObservationSpace));
    policy.action_space_ = space_from_json(header.at(checkpoint_header::kActionSpace));
    policy.shape_ = policy_shape_from_json(header.at(checkpoint_header::kPolicy));
    const PolicyShape& shape = policy.shape_;
    if (shape.observation_size != static_cast<std::int64_t>(policy.observation_space_.size()) ||
        shape.action_size != static_cast<std::int64_t>(policy.action_space_.size())) {
      throw CheckpointError("policy sizes do not match the stored spaces");
    }
    const ActorCriticNetworks networks =
        actor_critic_networks(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                              shape.critic_hidden_sizes, shape.activation);
    policy.parameters_ = file.tensor(checkpoint_header::kPolicyParameters, networks.size).values;
    policy.actor_ = networks.actor;
    policy.normalizer_ = ObservationNormalizer::from_state(
        header.value(checkpoint_header::kNormalization, nlohmann::json()),
        policy.observation_space_.size());
  } catch (...) {
    rethrow_as_checkpoint_error(where);
  }
  policy.input_.resize(policy.observation_space_.size());
  policy.scratch_.resize(policy.actor_.scratch_size());
  return policy;
}

void DeployedPolicy::check_spaces(const BoxSpace& observation_space,
                                  const BoxSpace& action_space) const {
  check_same_space(observation_space_, observation_space, "observation space");
  check_same_space(action_space_, action_space, "action space");
}

void DeployedPolicy::act(std::span<const float> observation, std::span<float> action) {
  check_size(observation.size(), observation_space_.size(), "observation");
  check_size(action.size(), action_space_.size(), "action");
  // One pass over each vector when all is well; the messages are made only on failure.
  if (!all_finite(observation)) {
    throw std::invalid_argument("DeployedPolicy: observation " +
                                first_non_finite(observation, observation_space_));
  }
  normalizer_.normalize(observation, input_);
  actor_.forward(parameters_, input_, scratch_, action);
  if (!all_finite(action)) {
    throw PolicyOutputError(
        "policy action " + first_non_finite(action, action_space_) +
        ": the network overflows on this observation, outside the range the checkpoint "
        "gate proves finite");
  }
  for (std::size_t j = 0; j < action.size(); ++j) {
    action[j] = std::clamp(action[j], action_space_.low[j], action_space_.high[j]);
  }
}

void DeployedPolicy::act_batch(std::span<const float> observations, std::span<float> actions) {
  const std::size_t n_in = observation_space_.size();
  const std::size_t n_out = action_space_.size();
  if (observations.size() % n_in != 0 || observations.size() / n_in * n_out != actions.size()) {
    throw std::invalid_argument("DeployedPolicy: " + std::to_string(observations.size()) +
                                " observation values and " + std::to_string(actions.size()) +
                                " action values are not rows of " + std::to_string(n_in) + " and " +
                                std::to_string(n_out));
  }
  for (std::size_t row = 0; row < observations.size() / n_in; ++row) {
    act(observations.subspan(row * n_in, n_in), actions.subspan(row * n_out, n_out));
  }
}

}  // namespace upkie_rl
