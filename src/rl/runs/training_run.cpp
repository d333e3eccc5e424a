#include "rl/runs/training_run.hpp"

#include <ATen/Parallel.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "envs/registry/registry.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/observation_normalizer.hpp"
#include "policy/provenance.hpp"
#include "rl/distributed/rank_agreement.hpp"
#include "rl/runs/checkpoint.hpp"
#include "rl/runs/ppo_checkpoint.hpp"
#include "rl/runs/run_directory_lock.hpp"
#include "rl/runs/run_file_error.hpp"
#include "rl/runs/torchscript_export.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl {

namespace {

using Clock = std::chrono::steady_clock;

// The provenance "source" of the models a training writes.
constexpr const char* kTrainingSource = "upkie-rl train";

/// The header entries of a training run besides the trainer's (make_ppo_checkpoint).
nlohmann::json run_header_entries(std::int64_t checkpoints_saved) {
  return {{checkpoint_header::kRun, {{checkpoint_header::kCheckpointsSaved, checkpoints_saved}}},
          {checkpoint_header::kProvenance, new_provenance(kTrainingSource)}};
}

double wall_time() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// Whether `run_dir` holds a checkpoint or a final model (a run worth keeping).
bool holds_checkpoints(const std::filesystem::path& run_dir) {
  std::error_code error;
  for (const std::filesystem::path& directory : {run_dir, run_dir / "checkpoints"}) {
    for (const auto& entry : std::filesystem::directory_iterator(directory, error)) {
      if (entry.path().extension() == ".ckpt") return true;
    }
  }
  return false;
}

/// The run directory a checkpoint belongs to: the parent of its checkpoints/ folder, or
/// the folder of a final model.
std::filesystem::path own_run_dir(const std::filesystem::path& checkpoint) {
  const std::filesystem::path directory = checkpoint.parent_path();
  return directory.filename() == "checkpoints" ? directory.parent_path() : directory;
}

/// Whether resuming `checkpoint` in `run_dir` would write into another, non-empty run.
bool is_other_run(const std::filesystem::path& checkpoint, const std::filesystem::path& run_dir) {
  std::error_code error;
  if (!std::filesystem::exists(run_dir, error) || std::filesystem::is_empty(run_dir, error)) {
    return false;
  }
  const std::filesystem::path own = own_run_dir(checkpoint);
  return !std::filesystem::equivalent(own.empty() ? "." : own, run_dir, error);
}

std::string checkpoint_name(std::int64_t timesteps) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "checkpoint_%09lld_steps.ckpt",
                static_cast<long long>(timesteps));
  return buffer;
}

// What train() reports after an iteration: `elapsed` seconds since it started, at
// `start_timesteps`.
TrainingProgress progress_of(const Ppo& ppo, std::int64_t total, std::int64_t start_timesteps,
                             double elapsed, const PpoUpdateStatistics& update) {
  TrainingProgress progress;
  progress.timesteps = ppo.num_timesteps();
  progress.total_timesteps = total;
  progress.iterations = ppo.iterations();
  progress.elapsed_seconds = elapsed;
  progress.steps_per_second =
      static_cast<double>(progress.timesteps - start_timesteps) / std::max(elapsed, 1e-9);
  progress.mean_return = ppo.episodes().mean_return();
  progress.mean_length = ppo.episodes().mean_length();
  progress.update = update;
  return progress;
}

// The scalars logged after an iteration (TensorBoard and progress.csv), into `scalars`.
void collect_scalars(const TrainingProgress& progress, const Ppo& ppo,
                     std::span<const std::string_view> reward_term_names,
                     std::vector<ScalarValue>& scalars) {
  const PpoUpdateStatistics& update = progress.update;
  const PpoTimings& timings = ppo.timings();
  auto f = [](double value) { return static_cast<float>(value); };
  scalars = {{"time/total_timesteps", f(progress.timesteps)},
             {"time/iterations", f(progress.iterations)},
             {"time/fps", f(std::floor(progress.steps_per_second))},
             {"time/time_elapsed", f(progress.elapsed_seconds)},
             {"train/loss", f(update.loss)},
             {"train/policy_gradient_loss", f(update.policy_gradient_loss)},
             {"train/value_loss", f(update.value_loss)},
             {"train/entropy_loss", f(update.entropy_loss)},
             {"train/approx_kl", f(update.approx_kl)},
             {"train/clip_fraction", f(update.clip_fraction)},
             {"train/explained_variance", f(update.explained_variance)},
             {"train/learning_rate", f(update.learning_rate)},
             {"train/std", f(update.std)},
             {"train/clip_range", f(update.clip_range)},
             {"train/n_updates", f(static_cast<double>(update.n_updates))},
             {"time/env_seconds", f(timings.env_seconds)},
             {"time/inference_seconds", f(timings.inference_seconds)},
             {"time/update_seconds", f(timings.update_seconds)}};
  if (ppo.episodes().size() > 0) {
    scalars.push_back({"rollout/ep_rew_mean", f(progress.mean_return)});
    scalars.push_back({"rollout/ep_len_mean", f(progress.mean_length)});
  }
  const RewardTermStatistics& terms = ppo.reward_terms();
  if (terms.size() > 0) {
    for (std::size_t k = 0; k < reward_term_names.size(); ++k) {
      scalars.push_back({TrainingRun::reward_term_tag(reward_term_names[k]), f(terms.mean(k))});
    }
  }
}

}  // namespace

std::string local_timestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y%m%d-%H%M%S", &local);
  return buffer;
}

std::string TrainingRun::reward_term_tag(std::string_view term) {
  return "episode/reward_" + std::string(term);
}

std::vector<std::string> TrainingRun::logged_tags() {
  return {"time/total_timesteps",
          "time/iterations",
          "time/fps",
          "time/time_elapsed",
          "rollout/ep_rew_mean",
          "rollout/ep_len_mean",
          "train/loss",
          "train/policy_gradient_loss",
          "train/value_loss",
          "train/entropy_loss",
          "train/approx_kl",
          "train/clip_fraction",
          "train/explained_variance",
          "train/learning_rate",
          "train/std",
          "train/clip_range",
          "train/n_updates",
          "time/env_seconds",
          "time/inference_seconds",
          "time/update_seconds"};
}

namespace {

/// `run_dir`, unless rank 0 would start a new run there among a user's files: a non-empty
/// directory that is not an upkie-rl run (its config.yaml or progress.csv would be
/// overwritten). Checked before the lock creates anything.
const std::filesystem::path& checked_fresh_run_dir(const std::filesystem::path& run_dir,
                                                   const Communicator* communicator,
                                                   bool allow_non_run_dir) {
  std::error_code error;
  const bool writer = communicator == nullptr || communicator->rank() == 0;
  if (writer && !allow_non_run_dir && std::filesystem::is_directory(run_dir, error) &&
      !std::filesystem::is_empty(run_dir, error) && !is_run_directory(run_dir)) {
    throw std::invalid_argument("run directory " + run_dir.string() +
                                " is not empty and is not an upkie-rl run (no .lock); choose a "
                                "new or empty one, or pass --force-run-dir to train there");
  }
  return run_dir;
}

}  // namespace

namespace {

/// `config` whose env.options name every option whose default changed since former
/// checkpoints (envs/registry/registry.hpp with_pinned_defaults), so that its checkpoints are read
/// back with the defaults it ran with.
TrainingConfig with_pinned_env_defaults(TrainingConfig config) {
  try {
    config.env_options = with_pinned_defaults(config.env_id, config.env_options);
  } catch (const std::invalid_argument&) {
    // An unknown id: validate() says so.
  }
  return config;
}

}  // namespace

TrainingRun::TrainingRun(const TrainingConfig& config, const std::filesystem::path& run_dir,
                         std::shared_ptr<Communicator> communicator, bool allow_non_run_dir)
    : TrainingRun(ResumeTag{}, with_pinned_env_defaults(config),
                  checked_fresh_run_dir(run_dir, communicator.get(), allow_non_run_dir),
                  std::move(communicator)) {
  if (!writes_outputs()) return;
  if (std::filesystem::exists(run_dir_ / "config.yaml")) {
    if (holds_checkpoints(run_dir_)) {
      throw RunFileError("run directory " + run_dir_.string() +
                         " already holds a run; choose another --run-dir or --resume a "
                         "checkpoint");
    }
    // A run killed before its first checkpoint: nothing to resume, so it starts over and
    // its logs, which describe steps about to be redone, go.
    for (const auto& entry : std::filesystem::directory_iterator(run_dir_)) {
      const std::string name = entry.path().filename().string();
      if (name == "progress.csv" || name.rfind("events.out.tfevents.", 0) == 0) {
        std::filesystem::remove(entry.path());
      }
    }
  }
  std::filesystem::create_directories(run_dir_);
  lock_->note_created(run_dir_ / "config.yaml");
  std::ofstream file(run_dir_ / "config.yaml");
  file << to_yaml(config_);
  if (!file) throw RunFileError("cannot write " + (run_dir_ / "config.yaml").string());
}

TrainingRun::TrainingRun(ResumeTag, TrainingConfig config, std::filesystem::path run_dir,
                         std::shared_ptr<Communicator> communicator)
    : config_(std::move(config)),
      run_dir_(std::move(run_dir)),
      communicator_(communicator ? std::move(communicator) : std::make_shared<SoloCommunicator>()) {
  config_.validate();
  // Before anything whose shape depends on the settings meets the other ranks.
  check_ranks_agree(agreement_settings(config_), *communicator_);
  if (writes_outputs()) {
    lock_ = std::make_unique<RunDirectoryLock>(run_dir_);
    remove_stale_temporaries(run_dir_);
  }
  // The networks are tiny (minibatches of 128 through 64x64 layers): intra-op threads
  // would cost more in synchronisation than they save, and the cores are needed by the
  // environment workers. One thread also makes reductions independent of the machine.
  at::set_num_threads(static_cast<int>(config_.torch_threads));
  make_learner();
}

void TrainingRun::make_learner() {
  auto inner = make_mixed_vector_env(
      config_.env_id, config_.mix_env_id, static_cast<std::size_t>(config_.mix_envs),
      config_.env_options, static_cast<std::size_t>(config_.num_envs),
      static_cast<std::size_t>(config_.env_threads));
  auto normalize = std::make_unique<VecNormalize>(std::move(inner), config_.normalize);
  // Mirrored normalised observations are the normalised mirrored ones only when the
  // statistics are symmetric (Ppo refuses the option when there is no mirror).
  if (const MirrorSymmetry* mirror = normalize->mirror_symmetry();
      config_.ppo.mirror_augmentation && mirror != nullptr) {
    normalize->set_statistics_mirror(mirror->observation);
  }
  normalize_ = normalize.get();
  env_ = std::move(normalize);
  ppo_ = std::make_unique<Ppo>(*env_, config_);
  ppo_->set_communicator(communicator_.get());
}

void TrainingRun::observe_env(std::size_t index, EnvObserver observer) {
  if (index >= env_->num_envs()) {
    throw std::invalid_argument("environment " + std::to_string(index) + " is not one of the " +
                                std::to_string(env_->num_envs()) + " of the run");
  }
  const std::size_t action_size = env_->action_space().size();
  ppo_->set_step_observer([this, index, action_size, observer = std::move(observer)](
                              const VectorStep& step, std::span<const float> actions) {
    const Observation* observation = env_->full_observation(index);
    if (observation == nullptr) return;
    const double reward =
        normalize_ ? normalize_->raw_rewards()[index] : static_cast<double>(step.rewards[index]);
    observer(*observation, actions.subspan(index * action_size, action_size), reward,
             step.terminated[index] != 0 || step.truncated[index] != 0);
  });
}

std::unique_ptr<TrainingRun> TrainingRun::resume(const std::filesystem::path& checkpoint_path,
                                                 std::optional<std::filesystem::path> run_dir,
                                                 std::shared_ptr<Communicator> communicator,
                                                 bool allow_other_run_dir) {
  if (run_dir && !allow_other_run_dir && is_other_run(checkpoint_path, *run_dir)) {
    throw std::invalid_argument(
        "run directory " + run_dir->string() + " is not empty and is not the checkpoint's run (" +
        own_run_dir(checkpoint_path).string() + "); choose an empty one, or pass --force-run-dir");
  }
  const Checkpoint checkpoint = load_checkpoint(checkpoint_path);
  TrainingConfig config;
  try {
    config = parse_training_config(checkpoint_config_yaml(checkpoint.header));
  } catch (const std::invalid_argument& error) {
    throw CheckpointError("checkpoint " + checkpoint_path.string() +
                          ": bad configuration: " + error.what());
  }
  // A checkpoint made before an option's default changed resumes with its former default.
  config.env_options = with_recorded_defaults(config.env_id, config.env_options);
  if (!run_dir) run_dir = own_run_dir(checkpoint_path);
  std::unique_ptr<TrainingRun> run(
      new TrainingRun(ResumeTag{}, config, *run_dir, std::move(communicator)));
  if (run->writes_outputs()) std::filesystem::create_directories(run->run_dir_);
  const std::string where = "checkpoint " + checkpoint_path.string() + ": ";
  try {
    restore_ppo_checkpoint(*run->ppo_, checkpoint);
    namespace key = checkpoint_header;
    run->normalize_->load_state(checkpoint.header.at(key::kNormalization));
    run->checkpoints_saved_ =
        checkpoint.header.at(key::kRun).at(key::kCheckpointsSaved).get<std::int64_t>();
  } catch (const CheckpointError& error) {
    throw CheckpointError(where + error.what());
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(where + "normalisation statistics: " + error.what());
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(where + "malformed header: " + error.what());
  }
  run->resumed_at_ = run->ppo_->num_timesteps();
  if (run->writes_outputs() && !std::filesystem::exists(run->run_dir_ / "config.yaml")) {
    run->lock_->note_created(run->run_dir_ / "config.yaml");
    std::ofstream(run->run_dir_ / "config.yaml") << to_yaml(config);
  }
  return run;
}

std::uint64_t TrainingRun::segment_seed() const {
  const auto world = static_cast<std::int64_t>(communicator_->world_size());
  const auto rank = static_cast<std::int64_t>(communicator_->rank());
  return config_.seed +
         static_cast<std::uint64_t>((checkpoints_saved_ * world + rank) * config_.num_envs);
}

void TrainingRun::start_segment() {
  ppo_->reset_environments(segment_seed());
  ppo_->reseed_rank_stream(static_cast<std::uint64_t>(checkpoints_saved_));
}

void TrainingRun::save_checkpoint_now() {
  ++checkpoints_saved_;
  if (!writes_outputs()) return;
  const nlohmann::json extra = run_header_entries(checkpoints_saved_);
  const std::filesystem::path path =
      run_dir_ / "checkpoints" / checkpoint_name(ppo_->num_timesteps());
  save_checkpoint(make_ppo_checkpoint(*ppo_, normalize_->state(), extra), path);
  last_checkpoint_ = path;
}

std::filesystem::path TrainingRun::save_final_model() {
  if (!writes_outputs()) return {};
  const nlohmann::json extra = run_header_entries(checkpoints_saved_);
  const std::string stem = "model_" + local_timestamp();
  std::filesystem::path path = run_dir_ / (stem + ".ckpt");
  const Checkpoint checkpoint = make_ppo_checkpoint(*ppo_, normalize_->state(), extra);
  save_checkpoint(checkpoint, path);
  torchscript_path_ = run_dir_ / (stem + ".pt");
  export_torchscript(
      ppo_->policy(),
      ObservationNormalizer::from_state(normalize_->state(), env_->observation_space().size()),
      env_->observation_space(), env_->action_space(), config_.env_id, torchscript_path_,
      model_provenance(checkpoint.header));
  return path;
}

std::filesystem::path TrainingRun::train(
    const std::function<void(const TrainingProgress&)>& on_progress) {
  // Rank 0 alone logs.
  std::optional<TensorBoardWriter> events;
  std::optional<ScalarCsvWriter> csv;
  if (writes_outputs()) {
    lock_->keep();  // the run has started: a failure from here on leaves it to resume
    events.emplace(run_dir_);
    std::vector<std::string> tags = logged_tags();
    for (const std::string_view name : env_->reward_term_names()) {
      tags.push_back(reward_term_tag(name));
    }
    csv.emplace(run_dir_ / "progress.csv", tags, resumed_at_);
  }
  const auto sum_over_ranks = [this](std::span<double> values) {
    communicator_->sum(torch::from_blob(values.data(), {static_cast<std::int64_t>(values.size())},
                                        torch::kFloat64));
  };
  const std::int64_t total = config_.ppo.total_timesteps;
  const std::int64_t every = config_.checkpoint_every;
  const std::int64_t start_timesteps = ppo_->num_timesteps();
  // The first multiple of `every` past both the saved checkpoints and the start, computed
  // rather than stepped to: a resumed counter may be far ahead (the gate bounds it).
  std::int64_t next_checkpoint = std::numeric_limits<std::int64_t>::max();
  if (every > 0) {
    next_checkpoint = std::max(checkpoints_saved_ + 1, start_timesteps / every + 1) * every;
  }
  const auto start = Clock::now();
  env_->set_randomization_scale(config_.randomization_scale(ppo_->num_timesteps()));
  start_segment();
  std::vector<ScalarValue> scalars;
  while (ppo_->num_timesteps() < total) {
    env_->set_randomization_scale(config_.randomization_scale(ppo_->num_timesteps()));
    const PpoUpdateStatistics update = ppo_->iterate();
    if (communicator_->world_size() > 1) normalize_->merge_statistics(sum_over_ranks);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const TrainingProgress progress = progress_of(*ppo_, total, start_timesteps, elapsed, update);
    collect_scalars(progress, *ppo_, env_->reward_term_names(), scalars);
    if (events) {
      events->add_scalars(progress.timesteps, scalars, wall_time());
      csv->write_row(scalars);
    }

    if (progress.timesteps >= next_checkpoint && progress.timesteps < total) {
      if (events) events->flush();
      save_checkpoint_now();
      next_checkpoint = (progress.timesteps / every + 1) * every;
      // Start fresh episodes so that a run resumed from this checkpoint continues
      // exactly like this one.
      start_segment();
    }
    if (on_progress) on_progress(progress);
  }
  if (events) events->flush();
  return save_final_model();
}

}  // namespace upkie_rl
