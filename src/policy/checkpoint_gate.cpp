#include "policy/checkpoint_gate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/number_text.hpp"
#include "base/setting_bounds.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/model_header.hpp"
#include "policy/network_limits.hpp"
#include "policy/network_output_bound.hpp"
#include "policy/observation_normalizer.hpp"
#include "policy/parameter_layout.hpp"
#include "policy/space_json.hpp"
#include "vec/normalization_state.hpp"
#include "vec/normalize_config.hpp"
#include "vec/running_mean_std.hpp"

namespace upkie_rl {

namespace {

void check_format(const nlohmann::json& header) {
  const auto format = header.find(checkpoint_header::kFormat);
  if (format == header.end() || *format != kCheckpointFormat) {
    throw CheckpointError("not an upkie-rl checkpoint (format " +
                          (format == header.end() ? std::string("missing") : format->dump()) + ")");
  }
  const auto version = header.find(checkpoint_header::kVersion);
  if (version == header.end() || !version->is_number_integer() || *version != kCheckpointVersion) {
    throw CheckpointError("checkpoint version " +
                          (version == header.end() ? std::string("missing") : version->dump()) +
                          " is not the version " + std::to_string(kCheckpointVersion) +
                          " this build reads");
  }
}

void check_space(const BoxSpace& space, const char* what, bool finite) {
  for (std::size_t i = 0; i < space.size(); ++i) {
    const float low = space.low[i];
    const float high = space.high[i];
    if (std::isnan(low) || std::isnan(high) || low > high ||
        (finite && !(std::isfinite(low) && std::isfinite(high)))) {
      throw CheckpointError(std::string(what) + " component " + std::to_string(i) +
                            " has bounds [" + std::to_string(low) + ", " + std::to_string(high) +
                            "]");
    }
  }
}

void check_tensors(const CheckpointFile& file, std::int64_t parameter_count) {
  file.tensor(checkpoint_header::kPolicyParameters, parameter_count);
  for (const char* moment :
       {checkpoint_header::kOptimizerExpAvg, checkpoint_header::kOptimizerExpAvgSq}) {
    if (file.tensors.contains(moment)) file.tensor(moment, parameter_count);
  }
  for (const auto& [name, tensor] : file.tensors) {
    for (std::size_t i = 0; i < tensor.values.size(); ++i) {
      if (!std::isfinite(tensor.values[i])) {
        throw CheckpointError("tensor '" + name + "' value " + std::to_string(i) + " is " +
                              std::to_string(tensor.values[i]));
      }
    }
  }
}

/// Adam's moments, when stored, are consistent (see kMaxAdamMomentRatio).
void check_optimizer_moments(const CheckpointFile& file) {
  if (!file.tensors.contains(checkpoint_header::kOptimizerExpAvg) ||
      !file.tensors.contains(checkpoint_header::kOptimizerExpAvgSq)) {
    return;
  }
  const std::vector<float>& first = file.tensor(checkpoint_header::kOptimizerExpAvg).values;
  const std::vector<float>& second = file.tensor(checkpoint_header::kOptimizerExpAvgSq).values;
  for (std::size_t i = 0; i < second.size(); ++i) {
    if (second[i] < 0.0f) {
      throw CheckpointError("tensor '" + std::string(checkpoint_header::kOptimizerExpAvgSq) +
                            "' value " + std::to_string(i) + " is " + shortest_text(second[i]) +
                            ": a second moment cannot be negative");
    }
    const double limit = std::sqrt(kMaxAdamMomentRatio * second[i]) + kAdamMomentSlack;
    if (std::abs(static_cast<double>(first[i])) > limit) {
      throw CheckpointError("tensor '" + std::string(checkpoint_header::kOptimizerExpAvg) +
                            "' value " + std::to_string(i) + " is " + shortest_text(first[i]) +
                            ": Adam allows at most " + shortest_text(limit) +
                            " beside a second moment of " + shortest_text(second[i]));
    }
  }
}

/// The observation normaliser the state makes (the identity for a null state).
ObservationNormalizer check_normalization(const nlohmann::json& state,
                                          std::size_t observation_size) {
  if (state.is_null()) return ObservationNormalizer(observation_size);
  try {
    ObservationNormalizer normalizer = ObservationNormalizer::from_state(state, observation_size);
    RunningMeanStd returns(1);
    returns.from_json(state.at(normalization_state::kReturnStatistics),
                      std::string(checkpoint_header::kNormalization) + "." +
                          normalization_state::kReturnStatistics);
    normalize_config_from_json(state.at(normalization_state::kConfig));
    return normalizer;
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(std::string("normalization: ") + error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(std::string("normalization: ") + error.what());
  }
}

/// Integer at `key` of `object`, when present, in [0, kMaxCheckpointCounter].
void check_counter(const nlohmann::json& object, const char* section, const char* key) {
  const auto found = object.find(key);
  if (found == object.end()) return;
  if (!found->is_number_integer()) {
    throw CheckpointError(std::string(section) + "." + key + " is not an integer");
  }
  check_setting(std::string(section) + "." + key, found->get<std::int64_t>(), 0,
                kMaxCheckpointCounter);
}

/// Sections and counters the trainer writes; a model made by another tool (an SB3 import)
/// may lack some, but what is there must be in range. Resuming needs them all
/// (restore_ppo_checkpoint says which is missing).
void check_counters(const nlohmann::json& header) {
  for (const auto& [section, keys] :
       {std::pair<const char*, std::vector<const char*>>{
            checkpoint_header::kCounters,
            {checkpoint_header::kNumTimesteps, checkpoint_header::kIterations,
             checkpoint_header::kNUpdates}},
        {checkpoint_header::kOptimizer, {checkpoint_header::kStepCount}},
        {checkpoint_header::kRun, {checkpoint_header::kCheckpointsSaved}}}) {
    const auto found = header.find(section);
    if (found == header.end()) continue;
    if (!found->is_object()) throw CheckpointError(std::string(section) + " is not an object");
    for (const char* key : keys) check_counter(*found, section, key);
  }
}

void check_contents(const CheckpointFile& file) {
  const nlohmann::json& header = file.header;
  check_format(header);
  checkpoint_env_id(header);
  checkpoint_env_options(header);
  const BoxSpace observation_space =
      space_from_json(header.at(checkpoint_header::kObservationSpace));
  const BoxSpace action_space = space_from_json(header.at(checkpoint_header::kActionSpace));
  check_space(observation_space, "observation space", false);
  check_space(action_space, "action space", true);
  const PolicyShape shape = policy_shape_from_json(header.at(checkpoint_header::kPolicy));
  if (shape.observation_size != static_cast<std::int64_t>(observation_space.size()) ||
      shape.action_size != static_cast<std::int64_t>(action_space.size())) {
    throw CheckpointError("policy sizes do not match the stored spaces");
  }
  const ActorCriticLayout layout =
      actor_critic_layout(shape.observation_size, shape.action_size, shape.actor_hidden_sizes,
                          shape.critic_hidden_sizes);
  check_tensors(file, layout.size);
  check_optimizer_moments(file);
  const ObservationNormalizer normalizer = check_normalization(
      header.value(checkpoint_header::kNormalization, nlohmann::json()), observation_space.size());
  // Finite weights can still overflow (the fuzz target's weights of 1e36 gave a NaN action):
  // both networks must stay finite for every input in range, and σ = exp(log σ) too.
  const std::vector<float>& parameters = file.tensor(checkpoint_header::kPolicyParameters).values;
  const std::vector<double> inputs = network_input_bounds(observation_space, normalizer);
  check_network_bound(parameters, layout.actor, inputs, "actor");
  check_network_bound(parameters, layout.critic, inputs, "critic");
  check_log_std(parameters, layout.log_std, shape.action_size);
  check_counters(header);
}

}  // namespace

void rethrow_as_checkpoint_error(const std::string& where) {
  try {
    throw;
  } catch (const CheckpointError& error) {
    throw CheckpointError(where + ": " + error.what());
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(where + ": " + error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(where + ": malformed header: " + error.what());
  }
}

void check_checkpoint(const CheckpointFile& file, const std::string& where) {
  try {
    check_contents(file);
  } catch (...) {
    rethrow_as_checkpoint_error(where);
  }
}

CheckpointFile read_checked_checkpoint(const std::filesystem::path& path) {
  CheckpointFile file = read_checkpoint_file(path);
  check_checkpoint(file, "checkpoint " + path.string());
  return file;
}

}  // namespace upkie_rl
