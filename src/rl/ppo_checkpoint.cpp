#include "rl/ppo_checkpoint.hpp"

#include "policy/checkpoint_gate.hpp"

namespace upkie_rl {

namespace {

nlohmann::json policy_shape(const Ppo& ppo) {
  const PolicyConfig& config = ppo.policy().config();
  return policy_shape_to_json({ppo.policy().observation_size(), ppo.policy().action_size(),
                               config.actor_hidden_sizes, config.critic_hidden_sizes,
                               config.activation});
}

}  // namespace

Checkpoint make_ppo_checkpoint(const Ppo& ppo, const nlohmann::json& normalization,
                               const nlohmann::json& extra) {
  Checkpoint checkpoint;
  checkpoint.header = extra;
  checkpoint.header["format"] = kCheckpointFormat;
  checkpoint.header["version"] = kCheckpointVersion;
  checkpoint.header["config"] = to_yaml(ppo.config());
  checkpoint.header["counters"] = ppo.counters_state();
  checkpoint.header["optimizer"] = {{"step_count", ppo.optimizer().step_count()}};
  checkpoint.header["normalization"] = normalization;
  checkpoint.header["policy"] = policy_shape(ppo);
  checkpoint.header["observation_space"] = space_to_json(ppo.env().observation_space());
  checkpoint.header["action_space"] = space_to_json(ppo.env().action_space());
  checkpoint.tensors["policy.parameters"] = ppo.policy().flat_parameters().detach().clone();
  checkpoint.tensors["optimizer.exp_avg"] = ppo.optimizer().exp_avg().clone();
  checkpoint.tensors["optimizer.exp_avg_sq"] = ppo.optimizer().exp_avg_sq().clone();
  return checkpoint;
}

void restore_ppo_checkpoint(Ppo& ppo, const Checkpoint& checkpoint) {
  const nlohmann::json& header = checkpoint.header;
  if (header.value("format", "") != kCheckpointFormat ||
      header.value("version", 0) != kCheckpointVersion) {
    throw CheckpointError("not an upkie-rl checkpoint of version " +
                          std::to_string(kCheckpointVersion));
  }
  if (!header.contains("policy") || header.at("policy") != policy_shape(ppo)) {
    throw CheckpointError("the checkpoint's policy " +
                          header.value("policy", nlohmann::json()).dump() +
                          " differs from the configured one " + policy_shape(ppo).dump());
  }
  check_same_space(space_from_json(header.at("observation_space")), ppo.env().observation_space(),
                   "observation space");
  check_same_space(space_from_json(header.at("action_space")), ppo.env().action_space(),
                   "action space");
  const std::int64_t count = ppo.policy().flat_parameters().numel();
  const torch::Tensor& parameters = checkpoint.tensor("policy.parameters", count);
  const torch::Tensor& exp_avg = checkpoint.tensor("optimizer.exp_avg", count);
  const torch::Tensor& exp_avg_sq = checkpoint.tensor("optimizer.exp_avg_sq", count);
  try {
    ppo.optimizer().load_state(exp_avg, exp_avg_sq,
                               header.at("optimizer").at("step_count").get<std::int64_t>());
    ppo.load_counters_state(header.at("counters"));
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(std::string("malformed checkpoint header: ") + error.what());
  }
  torch::NoGradGuard no_grad;
  ppo.policy().flat_parameters().copy_(parameters.view({-1}));
}

}  // namespace upkie_rl
