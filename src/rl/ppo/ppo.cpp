#include "rl/ppo/ppo.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "policy/checkpoint_header.hpp"
#include "policy/diagonal_gaussian.hpp"
#include "rl/ppo/autograd_ppo_gradient.hpp"
#include "rl/ppo/ppo_gradient.hpp"
#include "rl/ppo/ppo_loss.hpp"

namespace upkie_rl {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Checked before the policy and the rollout buffer are allocated.
const TrainingConfig& validated(const TrainingConfig& config, const VectorEnv& env) {
  config.validate();
  if (config.ppo.mirror_augmentation && env.mirror_symmetry() == nullptr) {
    throw std::invalid_argument("config key 'ppo.mirror_augmentation': " + config.env_id +
                                " declares no left-right mirror of its observations and actions");
  }
  config.check_allocations(static_cast<std::int64_t>(env.observation_space().size()),
                           static_cast<std::int64_t>(env.action_space().size()));
  return config;
}

std::int64_t checked_size(std::size_t size, const char* what) {
  if (size == 0)
    throw std::invalid_argument(std::string("PPO: the environment has an empty ") + what);
  return static_cast<std::int64_t>(size);
}

// A fresh permutation of [0, size) by Fisher-Yates on our own generator (for
// reproducibility and checkpointing), written into `permutation`.
void shuffle(std::vector<std::int64_t>& permutation, std::mt19937_64& rng) {
  const auto size = static_cast<std::int64_t>(permutation.size());
  for (std::int64_t i = 0; i < size; ++i) permutation[i] = i;
  for (std::int64_t i = size - 1; i > 0; --i) {
    std::uniform_int_distribution<std::int64_t> pick(0, i);
    std::swap(permutation[i], permutation[pick(rng)]);
  }
}

// The whole rollout in the order of `permutation`, so that minibatches are slices.
PpoMinibatch shuffled_rollout(const RolloutBuffer& buffer, std::vector<std::int64_t>& permutation) {
  const torch::Tensor index = torch::from_blob(
      permutation.data(), {static_cast<std::int64_t>(permutation.size())}, torch::kInt64);
  return select_rows(buffer.flat(), index);
}

}  // namespace

Ppo::Ppo(VectorEnv& env, const TrainingConfig& config)
    : env_(env),
      config_(validated(config, env)),
      observation_size_(checked_size(env.observation_space().size(), "observation space")),
      action_size_(checked_size(env.action_space().size(), "action space")),
      num_envs_(static_cast<std::int64_t>(env.num_envs())),
      policy_(std::make_unique<ActorCritic>(observation_size_, action_size_, config.policy,
                                            config.seed)),
      optimizer_(policy_->flat_parameters(), policy_->flat_gradients(),
                 AdamConfig{config.ppo.learning_rate_initial, 0.9, 0.999, config.ppo.adam_eps}),
      learning_rate_{config.ppo.learning_rate_initial, config.ppo.learning_rate_final},
      buffer_(config.steps_per_env(), num_envs_, observation_size_, action_size_),
      inference_(*policy_, num_envs_),
      reward_terms_(env.reward_term_names().size()),
      rng_(config.seed),
      last_observations_(num_envs_ * observation_size_),
      clipped_actions_(num_envs_ * action_size_),
      last_values_(num_envs_),
      action_low_(env.action_space().low),
      action_high_(env.action_space().high) {
  if (num_envs_ != config.num_envs) {
    throw std::invalid_argument("PPO: the vector env has " + std::to_string(num_envs_) +
                                " envs but config key 'env.num_envs' says " +
                                std::to_string(config.num_envs));
  }
  if (action_low_.size() != static_cast<std::size_t>(action_size_) ||
      action_high_.size() != static_cast<std::size_t>(action_size_)) {
    throw std::invalid_argument("PPO: action space bounds do not match its size");
  }
  permutation_.resize(static_cast<std::size_t>(buffer_.size()));
  // At most one episode ends per environment and step: no allocation during rollouts.
  ended_episodes_.reserve(static_cast<std::size_t>(2 * num_envs_ * buffer_.num_steps()));
  // With mirror augmentation, each minibatch holds its samples and their images.
  const std::int64_t copies = config_.ppo.mirror_augmentation ? 2 : 1;
  if (config_.ppo.mirror_augmentation) mirrored_.emplace(*env.mirror_symmetry(), buffer_.size());
  if (upkie_rl::uses_hand_gradient(config_)) {
    gradient_.emplace(*policy_, copies * std::min(config_.ppo.batch_size, buffer_.size()),
                      PpoGradientKernel::kFastest, config_.ppo.update_threads);
  }
}

void Ppo::reset_environments(std::uint64_t seed) {
  const auto start = Clock::now();
  const std::span<const float> observations = env_.reset(seed);
  if (observations.size() != last_observations_.size()) {
    throw std::logic_error("PPO: reset returned " + std::to_string(observations.size()) +
                           " observation values, expected " +
                           std::to_string(last_observations_.size()));
  }
  std::copy(observations.begin(), observations.end(), last_observations_.begin());
  timings_.env_seconds += seconds_since(start);
  started_ = true;
}

void Ppo::collect_rollout() {
  if (!started_) throw std::logic_error("PPO: call reset_environments() before collecting");
  // σ is constant during a rollout.
  std::vector<double> stds(action_size_);
  const std::span<const float> log_std(policy_->log_std().data_ptr<float>(),
                                       static_cast<std::size_t>(action_size_));
  for (std::int64_t j = 0; j < action_size_; ++j) {
    stds[j] = std::exp(static_cast<double>(log_std[j]));
  }
  // The sampled noise is z of policy/diagonal_gaussian.hpp's log π.
  const double log_normaliser = gaussian_log_normaliser(log_std);
  for (std::int64_t t = 0; t < buffer_.num_steps(); ++t) {
    auto start = Clock::now();
    sample_actions(t, stds, log_normaliser);
    timings_.inference_seconds += seconds_since(start);

    start = Clock::now();
    const VectorStep& step = env_.step(clipped_actions_);
    timings_.env_seconds += seconds_since(start);
    if (step_observer_) step_observer_(step, clipped_actions_);

    start = Clock::now();
    record_step(t, step);
    std::copy(step.observations.begin(), step.observations.end(), last_observations_.begin());
    num_timesteps_ += num_envs_ * communicator_->world_size();
    timings_.inference_seconds += seconds_since(start);
  }
  const auto start = Clock::now();
  inference_.run_critic(last_observations_);
  std::copy(inference_.values().begin(), inference_.values().end(), last_values_.begin());
  buffer_.compute_returns_and_advantages(last_values_, config_.ppo.gamma, config_.ppo.gae_lambda);
  if (mirrored_) mirrored_->fill(buffer_, *policy_);
  gather_ended_episodes();
  ++iterations_;
  timings_.update_seconds += seconds_since(start);
}

void Ppo::sample_actions(std::int64_t t, std::span<const double> stds, double log_normaliser) {
  inference_.run(last_observations_);
  const std::span<const float> means = inference_.means();
  const std::span<const float> values = inference_.values();
  float* actions = buffer_.actions(t);
  float* log_probs = buffer_.log_probs(t);
  for (std::int64_t i = 0; i < num_envs_; ++i) {
    double squared_noise = 0.0;
    for (std::int64_t j = 0; j < action_size_; ++j) {
      const std::size_t k = static_cast<std::size_t>(i * action_size_ + j);
      const double noise = normal_(rng_);
      squared_noise += noise * noise;
      const float action = static_cast<float>(means[k] + stds[j] * noise);
      actions[k] = action;
      clipped_actions_[k] = std::clamp(action, action_low_[j], action_high_[j]);
    }
    log_probs[i] = static_cast<float>(gaussian_log_probability(squared_noise, log_normaliser));
  }
  std::memcpy(buffer_.observations(t), last_observations_.data(),
              last_observations_.size() * sizeof(float));
  std::memcpy(buffer_.values(t), values.data(), values.size_bytes());
}

void Ppo::record_step(std::int64_t t, const VectorStep& step) {
  float* rewards = buffer_.rewards(t);
  float* dones = buffer_.dones(t);
  bool any_truncated = false;
  for (std::int64_t i = 0; i < num_envs_; ++i) {
    const bool terminated = step.terminated[i] != 0;
    const bool truncated = step.truncated[i] != 0 && !terminated;
    rewards[i] = step.rewards[i];
    dones[i] = (terminated || truncated) ? 1.0f : 0.0f;
    any_truncated = any_truncated || truncated;
    if (terminated || step.truncated[i] != 0) {
      const std::size_t num_terms = reward_terms_.num_terms();
      if (num_terms > 0) {
        reward_terms_.add(std::span<const double>(step.episode_reward_terms)
                              .subspan(static_cast<std::size_t>(i) * num_terms, num_terms));
      }
      ended_episodes_.push_back(step.episode_returns[i]);
      ended_episodes_.push_back(static_cast<double>(step.episode_lengths[i]));
    }
  }
  if (!any_truncated) return;
  // Time limits are not failures: bootstrap with the current critic's value of the
  // episode's last observation.
  inference_.run_critic(step.final_observations);
  const std::span<const float> final_values = inference_.values();
  for (std::int64_t i = 0; i < num_envs_; ++i) {
    if (step.truncated[i] != 0 && step.terminated[i] == 0) {
      rewards[i] = static_cast<float>(rewards[i] + config_.ppo.gamma * final_values[i]);
    }
  }
}

void Ppo::set_communicator(Communicator* communicator) {
  if (started_) throw std::logic_error("Ppo::set_communicator after the first rollout");
  communicator_ = communicator != nullptr ? communicator : &solo_;
  reseed_rank_stream(0);
  torch::NoGradGuard no_grad;
  communicator_->broadcast(policy_->flat_parameters(), 0);
}

void Ppo::reseed_rank_stream(std::uint64_t segment) {
  const auto rank = static_cast<std::uint64_t>(communicator_->rank());
  if (rank == 0) return;
  // Other noise and minibatches than rank 0's: same seed, a stream per (rank, segment).
  rng_.seed(config_.seed ^ (0x9E3779B97F4A7C15ULL * rank) ^ (0xBF58476D1CE4E5B9ULL * segment));
  normal_.reset();
}

template <typename Values>
void Ppo::average_over_ranks(Values values) {
  const auto start = Clock::now();
  communicator_->average(values);
  timings_.communication_seconds += seconds_since(start);
}

void Ppo::gather_ended_episodes() {
  // In rank order, so that the episode statistics are the same on every rank.
  communicator_->gather(ended_episodes_, [this](std::span<const double> rank_episodes) {
    for (std::size_t i = 0; i + 1 < rank_episodes.size(); i += 2) {
      episodes_.add(rank_episodes[i], static_cast<std::int64_t>(rank_episodes[i + 1]));
    }
  });
  ended_episodes_.clear();
}

double Ppo::learning_rate_at(std::int64_t timesteps) const {
  return learning_rate_(LinearSchedule::progress_remaining(timesteps, config_.ppo.total_timesteps));
}

PpoUpdateStatistics Ppo::update() {
  const auto start = Clock::now();
  const PpoConfig& ppo = config_.ppo;
  PpoUpdateStatistics statistics;
  statistics.learning_rate = learning_rate_at(num_timesteps_);
  optimizer_.set_learning_rate(statistics.learning_rate);
  statistics.clip_range = ppo.clip_range;

  const std::int64_t size = buffer_.size();
  double sum_pg = 0.0, sum_value = 0.0, sum_entropy = 0.0, sum_kl = 0.0, sum_clip = 0.0;
  std::int64_t minibatches = 0;
  for (std::int64_t epoch = 0; epoch < ppo.n_epochs; ++epoch) {
    shuffle(permutation_, rng_);
    const PpoMinibatch shuffled = mirrored_
                                      ? mirrored_->paired_shuffle(permutation_, ppo.batch_size)
                                      : shuffled_rollout(buffer_, permutation_);
    const PpoMinibatchView shuffled_view = view_minibatch(shuffled);
    const std::int64_t copies = mirrored_ ? 2 : 1;  // samples and their images
    for (std::int64_t begin = 0; begin < size; begin += ppo.batch_size) {
      const std::int64_t length = std::min(ppo.batch_size, size - begin);
      // compute_ppo_loss(...).total.backward(), hand-written or by autograd: either
      // overwrites the flat gradients.
      const PpoMinibatchView minibatch = shuffled_view.rows(copies * begin, copies * length);
      const PpoLossStatistics loss = gradient_ ? gradient_->compute(minibatch, *policy_, ppo)
                                               : autograd_ppo_gradient(minibatch, *policy_, ppo);
      // DD-PPO: the gradient of the minibatch of every rank together.
      average_over_ranks(policy_->flat_gradients());
      clip_gradient_norm(policy_->flat_gradients(), ppo.max_grad_norm);
      optimizer_.step();
      sum_pg += loss.policy_gradient_loss;
      sum_value += loss.value_loss;
      sum_entropy += loss.entropy_loss;
      sum_kl += loss.approx_kl;
      sum_clip += loss.clip_fraction;
      statistics.loss = loss.total;
      ++minibatches;
    }
  }
  n_updates_ += ppo.n_epochs;
  // Report the losses of every rank's minibatches, the same on every rank.
  std::array<double, 5> sums{sum_pg, sum_value, sum_entropy, sum_kl, sum_clip};
  average_over_ranks(std::span<double>(sums));
  sum_pg = sums[0], sum_value = sums[1], sum_entropy = sums[2], sum_kl = sums[3],
  sum_clip = sums[4];
  const double count = static_cast<double>(minibatches);
  statistics.policy_gradient_loss = sum_pg / count;
  statistics.value_loss = sum_value / count;
  statistics.entropy_loss = sum_entropy / count;
  statistics.approx_kl = sum_kl / count;
  statistics.clip_fraction = sum_clip / count;
  statistics.explained_variance = explained_variance(buffer_.flat_values(), buffer_.flat_returns());
  {
    torch::NoGradGuard no_grad;
    statistics.std = torch::exp(policy_->log_std()).mean().item<double>();
  }
  statistics.n_updates = n_updates_;
  timings_.update_seconds += seconds_since(start);
  return statistics;
}

PpoUpdateStatistics Ppo::iterate() {
  collect_rollout();
  return update();
}

nlohmann::json Ppo::counters_state() const {
  std::ostringstream random_state;
  random_state << rng_ << ' ' << normal_;
  return {{checkpoint_header::kNumTimesteps, num_timesteps_},
          {checkpoint_header::kIterations, iterations_},
          {checkpoint_header::kNUpdates, n_updates_},
          {checkpoint_header::kRandomState, random_state.str()},
          {checkpoint_header::kEpisodes, episodes_.state()}};
}

void Ppo::load_counters_state(const nlohmann::json& state) {
  try {
    const auto num_timesteps = state.at(checkpoint_header::kNumTimesteps).get<std::int64_t>();
    const auto iterations = state.at(checkpoint_header::kIterations).get<std::int64_t>();
    const auto n_updates = state.at(checkpoint_header::kNUpdates).get<std::int64_t>();
    std::istringstream random_state(state.at(checkpoint_header::kRandomState).get<std::string>());
    std::mt19937_64 rng;
    std::normal_distribution<double> normal;
    random_state >> rng >> normal;
    if (!random_state) throw std::invalid_argument("unreadable random_state");
    if (num_timesteps < 0 || iterations < 0 || n_updates < 0) {
      throw std::invalid_argument("negative counter");
    }
    EpisodeStatistics episodes;
    episodes.load_state(state.at(checkpoint_header::kEpisodes));
    num_timesteps_ = num_timesteps;
    iterations_ = iterations;
    n_updates_ = n_updates;
    rng_ = rng;
    normal_ = normal;
    episodes_ = episodes;
  } catch (const nlohmann::json::exception& error) {
    throw std::invalid_argument(std::string("training counters: ") + error.what());
  }
}

}  // namespace upkie_rl
