#include "rl/runs/ppo_checkpoint.hpp"

#include "policy/checkpoint_gate.hpp"
#include "policy/checkpoint_header.hpp"

namespace upkie_rl {

namespace {

PolicyShape policy_shape(const Ppo& ppo) {
  const PolicyConfig& config = ppo.policy().config();
  return {ppo.policy().observation_size(), ppo.policy().action_size(), config.actor_hidden_sizes,
          config.critic_hidden_sizes, config.activation};
}

/// Refuses a checkpoint whose policy entry is not the configured shape.
void check_policy_shape(const nlohmann::json& header, const PolicyShape& configured) {
  const auto stored = header.find(checkpoint_header::kPolicy);
  bool same = false;
  if (stored != header.end()) {
    try {
      same = policy_shape_from_json(*stored) == configured;
    } catch (const std::exception&) {
      same = false;  // an unreadable entry is reported as a different one, as it shows
    }
  }
  if (!same) {
    throw CheckpointError("the checkpoint's policy " +
                          header.value(checkpoint_header::kPolicy, nlohmann::json()).dump() +
                          " differs from the configured one " +
                          policy_shape_to_json(configured).dump());
  }
}

}  // namespace

Checkpoint make_ppo_checkpoint(const Ppo& ppo, const nlohmann::json& normalization,
                               const nlohmann::json& extra) {
  Checkpoint checkpoint;
  checkpoint.header = extra;
  namespace key = checkpoint_header;
  checkpoint.header[key::kFormat] = kCheckpointFormat;
  checkpoint.header[key::kVersion] = kCheckpointVersion;
  checkpoint.header[key::kConfig] = to_yaml(ppo.config());
  checkpoint.header[key::kCounters] = ppo.counters_state();
  checkpoint.header[key::kOptimizer] = {{key::kStepCount, ppo.optimizer().step_count()}};
  checkpoint.header[key::kNormalization] = normalization;
  checkpoint.header[key::kPolicy] = policy_shape_to_json(policy_shape(ppo));
  checkpoint.header[key::kObservationSpace] = space_to_json(ppo.env().observation_space());
  checkpoint.header[key::kActionSpace] = space_to_json(ppo.env().action_space());
  checkpoint.tensors[key::kPolicyParameters] = ppo.policy().flat_parameters().detach().clone();
  checkpoint.tensors[key::kOptimizerExpAvg] = ppo.optimizer().exp_avg().clone();
  checkpoint.tensors[key::kOptimizerExpAvgSq] = ppo.optimizer().exp_avg_sq().clone();
  return checkpoint;
}

void restore_ppo_checkpoint(Ppo& ppo, const Checkpoint& checkpoint) {
  namespace key = checkpoint_header;
  const nlohmann::json& header = checkpoint.header;
  if (header.value(key::kFormat, "") != kCheckpointFormat ||
      header.value(key::kVersion, 0) != kCheckpointVersion) {
    throw CheckpointError("not an upkie-rl checkpoint of version " +
                          std::to_string(kCheckpointVersion));
  }
  check_policy_shape(header, policy_shape(ppo));
  check_same_space(space_from_json(header.at(key::kObservationSpace)),
                   ppo.env().observation_space(), "observation space");
  check_same_space(space_from_json(header.at(key::kActionSpace)), ppo.env().action_space(),
                   "action space");
  const std::int64_t count = ppo.policy().flat_parameters().numel();
  const torch::Tensor& parameters = checkpoint.tensor(key::kPolicyParameters, count);
  const torch::Tensor& exp_avg = checkpoint.tensor(key::kOptimizerExpAvg, count);
  const torch::Tensor& exp_avg_sq = checkpoint.tensor(key::kOptimizerExpAvgSq, count);
  try {
    ppo.optimizer().load_state(exp_avg, exp_avg_sq,
                               header.at(key::kOptimizer).at(key::kStepCount).get<std::int64_t>());
    ppo.load_counters_state(header.at(key::kCounters));
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(std::string("malformed checkpoint header: ") + error.what());
  }
  torch::NoGradGuard no_grad;
  ppo.policy().flat_parameters().copy_(parameters.view({-1}));
}

}  // namespace upkie_rl
