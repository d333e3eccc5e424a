#include "envs/evaluation/episode_runner.hpp"

#include <cmath>

namespace upkie_rl {

EpisodeOutcome run_episode(Env& env, Controller& controller, std::uint64_t seed, int max_steps,
                           std::span<float> observation, std::span<float> action) {
  env.reset(seed, observation);
  controller.reset();
  const VelocityEnv* velocity = find_velocity_env(env);
  EpisodeOutcome outcome;
  while (outcome.length < max_steps) {
    controller.act(observation, action);
    const StepResult step = env.step(action, observation);
    outcome.total_reward += step.reward;
    ++outcome.length;
    if (velocity != nullptr) outcome.tracking.add(*velocity, step.terminated);
    if (step.terminated || step.truncated) {
      outcome.terminated = step.terminated;
      break;
    }
  }
  return outcome;
}

EpisodeSummary summarize_episodes(const std::vector<EpisodeOutcome>& outcomes) {
  EpisodeSummary summary;
  summary.episodes = static_cast<int>(outcomes.size());
  if (outcomes.empty()) return summary;
  const double n = static_cast<double>(outcomes.size());
  for (const EpisodeOutcome& outcome : outcomes) {
    summary.successes += outcome.terminated ? 0 : 1;
    summary.mean_return += outcome.total_reward / n;
    summary.mean_length += outcome.length / n;
    summary.tracking += outcome.tracking;
  }
  summary.has_tracking = summary.tracking.active;
  summary.fall_rate = static_cast<double>(summary.episodes - summary.successes) / n;
  double variance = 0.0;
  for (const EpisodeOutcome& outcome : outcomes) {
    variance += (outcome.total_reward - summary.mean_return) *
                (outcome.total_reward - summary.mean_return) / n;
  }
  summary.std_return = std::sqrt(variance);
  return summary;
}

}  // namespace upkie_rl
