#include "cli/contender_evaluation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "cli/policy_controller.hpp"
#include "envs/controllers/builtin_controllers.hpp"
#include "envs/evaluation/evaluation_start.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl::apps {

namespace {

/// "label=value" splits at the first '=' when a label is given; else the label is derived.
std::pair<std::string, std::string> labelled(const std::string& item, bool is_model) {
  const std::size_t equal = item.find('=');
  if (equal != std::string::npos && equal > 0) {
    return {item.substr(0, equal), item.substr(equal + 1)};
  }
  return {is_model ? std::filesystem::path(item).stem().string() : item, item};
}

/// The plan's episode length in steps of `env`.
int max_steps_on(const EpisodePlan& plan, const Env& env) {
  if (plan.duration <= 0.0) return plan.max_steps;
  return std::max(1, static_cast<int>(std::lround(plan.duration / env.timestep())));
}

/// Runs the episodes of one cell: success = the episode was not terminated (it reached the
/// time limit or the plan's length).
CellResult evaluate_cell(const EpisodePlan& plan, const Contender& contender,
                         const EnvFactory& make_cell_env) {
  std::unique_ptr<Env> env = make_cell_env();
  const int max_steps = max_steps_on(plan, *env);
  std::unique_ptr<Controller> controller = contender.model.empty()
                                               ? make_builtin_controller(contender.spec, *env)
                                               : make_policy_controller(contender.model, *env);
  std::vector<float> observation(env->observation_space().size());
  std::vector<float> action(env->action_space().size());
  std::vector<EpisodeOutcome> outcomes;
  outcomes.reserve(static_cast<std::size_t>(std::max(0, plan.episodes)));
  for (int episode = 0; episode < plan.episodes; ++episode) {
    outcomes.push_back(run_episode(*env, *controller,
                                   plan.seed + static_cast<std::uint64_t>(episode), max_steps,
                                   observation, action));
  }
  const EpisodeSummary summary = summarize_episodes(outcomes);
  std::vector<double> returns;
  std::vector<int> lengths;
  CellResult result;
  for (const EpisodeOutcome& outcome : outcomes) {
    returns.push_back(outcome.total_reward);
    lengths.push_back(outcome.length);
    const bool early = outcome.length * env->timestep() < plan.early_fall_time;
    result.early_falls += outcome.terminated && early ? 1 : 0;
  }
  result.identical = !identical_episodes_warning(returns, lengths).empty();
  result.successes = summary.successes;
  result.mean_return = summary.mean_return;
  result.mean_length = summary.mean_length;
  result.summary = summary;
  return result;
}

}  // namespace

std::vector<Contender> make_contenders(const std::string& env_id,
                                       const std::vector<std::string>& models,
                                       const std::vector<std::string>& controllers,
                                       const EnvOptions& base) {
  std::vector<Contender> contenders;
  for (const std::string& item : models) {
    auto [label, path] = labelled(item, true);
    if (!std::filesystem::exists(path)) throw std::invalid_argument("model " + path + " not found");
    contenders.push_back({label, path, "", options_for_model(path, env_id, base)});
  }
  for (const std::string& item : controllers) {
    auto [label, spec] = labelled(item, false);
    const std::string resolved = resolve_controller_spec(spec, design_env_factory(env_id, base));
    if (resolved != spec) std::cout << label << ": " << resolved << std::endl;
    contenders.push_back({label, "", resolved, base});
  }
  if (contenders.empty()) {
    throw std::invalid_argument("nothing to evaluate: give --model and/or --controller");
  }
  for (std::size_t i = 0; i < contenders.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (contenders[i].label == contenders[j].label)
        contenders[i].label += "_" + std::to_string(i);
    }
  }
  return contenders;
}

std::vector<std::vector<CellResult>> evaluate_all(
    const EpisodePlan& plan, const std::vector<Contender>& contenders,
    const std::vector<std::vector<EnvFactory>>& factories) {
  const std::size_t num_cells = factories.front().size();
  std::vector<std::vector<CellResult>> results(contenders.size(),
                                               std::vector<CellResult>(num_cells));
  const std::size_t tasks = contenders.size() * num_cells;
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto work = [&] {
    for (std::size_t task = next++; task < tasks; task = next++) {
      const std::size_t c = task / num_cells;
      const std::size_t k = task % num_cells;
      try {
        results[c][k] = evaluate_cell(plan, contenders[c], factories[c][k]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = tasks;  // the others stop after their current cell
      }
    }
  };
  const unsigned threads = static_cast<unsigned>(std::max(1, plan.threads));
  std::vector<std::thread> workers;
  for (unsigned t = 1; t < std::min<std::size_t>(threads, tasks); ++t) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);
  return results;
}

/// The episodes of every cell as one summary (tracking errors pooled over their steps).
EpisodeSummary pooled_summary(const std::vector<CellResult>& results) {
  EpisodeSummary pooled;
  int falls = 0;
  for (const CellResult& cell : results) {
    pooled.episodes += cell.summary.episodes;
    pooled.successes += cell.summary.successes;
    falls += cell.summary.episodes - cell.summary.successes;
    pooled.tracking += cell.summary.tracking;
  }
  pooled.has_tracking = pooled.tracking.active;
  pooled.fall_rate = pooled.episodes > 0 ? static_cast<double>(falls) / pooled.episodes : 0.0;
  return pooled;
}

void warn_identical_cells(const EpisodePlan& plan,
                          const std::vector<std::vector<CellResult>>& results) {
  if (plan.episodes < 2) return;
  std::size_t identical = 0;
  std::size_t cells = 0;
  for (const auto& contender : results) {
    for (const CellResult& cell : contender) identical += cell.identical ? 1 : 0;
    cells += contender.size();
  }
  if (identical == 0) return;
  std::cerr << "upkie-rl: warning: in " << identical << " of " << cells << " cells, all "
            << plan.episodes
            << " episodes were identical: their environment starts every episode from the same "
               "state (add an initial-state randomisation, or leave out --exact-start)"
            << std::endl;
}

}  // namespace upkie_rl::apps
