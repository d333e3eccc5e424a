#include "vec/env_batch.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace upkie_rl {

EnvBatch::EnvBatch(std::vector<std::unique_ptr<Env>> envs, AutoresetMode autoreset_mode)
    : envs_(std::move(envs)), autoreset_mode_(autoreset_mode) {
  if (envs_.empty()) throw std::invalid_argument("vector env: needs at least one environment");
  for (const auto& env : envs_) {
    if (!env) throw std::invalid_argument("vector env: null environment");
  }
  observation_size_ = envs_.front()->observation_space().size();
  action_size_ = envs_.front()->action_space().size();
  for (const auto& env : envs_) {
    if (env->observation_space().size() != observation_size_ ||
        env->action_space().size() != action_size_) {
      throw std::invalid_argument("vector env: environments have different space sizes");
    }
  }
  const std::size_t n = envs_.size();
  result_.observations.assign(n * observation_size_, 0.0f);
  result_.rewards.assign(n, 0.0f);
  result_.terminated.assign(n, 0);
  result_.truncated.assign(n, 0);
  result_.final_observations.assign(n * observation_size_, 0.0f);
  result_.episode_returns.assign(n, 0.0);
  result_.episode_lengths.assign(n, 0);
  running_returns_.assign(n, 0.0);
  running_lengths_.assign(n, 0);
  needs_reset_.assign(n, 0);
  num_terms_ = envs_.front()->reward_term_names().size();
  result_.episode_reward_terms.assign(n * num_terms_, 0.0);
  running_terms_.assign(n * num_terms_, 0.0);
}

void EnvBatch::reset(std::size_t begin, std::size_t end, std::optional<std::uint64_t> seed) {
  for (std::size_t i = begin; i < end; ++i) {
    std::span<float> row(result_.observations.data() + i * observation_size_, observation_size_);
    envs_[i]->reset(seed ? std::optional<std::uint64_t>(*seed + i) : std::nullopt, row);
    running_returns_[i] = 0.0;
    running_lengths_[i] = 0;
    std::fill_n(running_terms_.begin() + static_cast<std::ptrdiff_t>(i * num_terms_), num_terms_,
                0.0);
    result_.terminated[i] = 0;
    result_.truncated[i] = 0;
    needs_reset_[i] = 0;
  }
}

void EnvBatch::check_step(std::span<const float> actions) const {
  if (!was_reset_) throw std::logic_error("vector env: step() called before reset()");
  if (actions.size() != envs_.size() * action_size_) {
    throw std::invalid_argument("vector env: actions have " + std::to_string(actions.size()) +
                                " components, expected " + std::to_string(envs_.size()) + " x " +
                                std::to_string(action_size_));
  }
}

void EnvBatch::accumulate_reward_terms(std::size_t i) {
  if (num_terms_ == 0) return;
  const std::span<const double> terms = envs_[i]->reward_terms();
  if (terms.size() != num_terms_) {
    throw std::logic_error("vector env: environment " + std::to_string(i) + " gave " +
                           std::to_string(terms.size()) + " reward terms, expected " +
                           std::to_string(num_terms_));
  }
  double* sums = running_terms_.data() + i * num_terms_;
  for (std::size_t k = 0; k < num_terms_; ++k) sums[k] += terms[k];
}

void EnvBatch::step(std::size_t begin, std::size_t end, std::span<const float> actions) {
  for (std::size_t i = begin; i < end; ++i) {
    float* observation = result_.observations.data() + i * observation_size_;
    std::span<float> row(observation, observation_size_);
    result_.episode_returns[i] = 0.0;
    result_.episode_lengths[i] = 0;
    if (needs_reset_[i]) {  // kNextStep: this step is the reset; the action is ignored.
      needs_reset_[i] = 0;
      envs_[i]->reset(std::nullopt, row);
      result_.rewards[i] = 0.0f;
      result_.terminated[i] = 0;
      result_.truncated[i] = 0;
      continue;
    }
    const StepResult step = envs_[i]->step(actions.subspan(i * action_size_, action_size_), row);
    result_.rewards[i] = static_cast<float>(step.reward);
    result_.terminated[i] = step.terminated;
    result_.truncated[i] = step.truncated;
    running_returns_[i] += step.reward;
    running_lengths_[i] += 1;
    accumulate_reward_terms(i);
    if (step.terminated || step.truncated) {
      std::copy(observation, observation + observation_size_,
                result_.final_observations.data() + i * observation_size_);
      result_.episode_returns[i] = running_returns_[i];
      result_.episode_lengths[i] = running_lengths_[i];
      running_returns_[i] = 0.0;
      running_lengths_[i] = 0;
      double* terms = running_terms_.data() + i * num_terms_;
      std::copy(terms, terms + num_terms_, result_.episode_reward_terms.data() + i * num_terms_);
      std::fill(terms, terms + num_terms_, 0.0);
      if (autoreset_mode_ == AutoresetMode::kSameStep) {
        envs_[i]->reset(std::nullopt, row);
      } else {
        needs_reset_[i] = 1;
      }
    }
  }
}

}  // namespace upkie_rl
