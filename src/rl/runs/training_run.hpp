#pragma once
/// @file
/// A training run: the environments (vector env + VecNormalize), the PPO learner, and the
/// run directory with the resolved config, TensorBoard events, a CSV of the same scalars,
/// periodic checkpoints and the final model.
///
/// Run directory layout:
///   config.yaml                        the resolved configuration
///   events.out.tfevents.*              TensorBoard scalars (SB3 tag names)
///   progress.csv                       the same scalars, one row per update
///   checkpoints/checkpoint_<N>_steps.ckpt  every `checkpoint_every` timesteps
///   model_<YYYYmmdd-HHMMSS>.ckpt       the final model (a full checkpoint)
///   model_<YYYYmmdd-HHMMSS>.pt         the deterministic policy as TorchScript
///
/// Resuming: every environment is reset (with a seed derived from the run's seed and the
/// checkpoint count) right after each checkpoint, in uninterrupted runs too. A run resumed
/// from a checkpoint therefore continues exactly as the uninterrupted run did, given the
/// same thread counts.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "rl/logging/scalar_csv_writer.hpp"
#include "rl/logging/tensorboard_writer.hpp"
#include "rl/ppo/ppo.hpp"
#include "rl/runs/run_directory_lock.hpp"
#include "rl/runs/training_config.hpp"
#include "vec/vec_normalize.hpp"

namespace upkie_rl {

/// The local time as YYYYmmdd-HHMMSS, as in the default names of runs and models.
std::string local_timestamp();

/// What the run reports after each update (for progress bars).
struct TrainingProgress {
  std::int64_t timesteps = 0;
  std::int64_t total_timesteps = 0;
  std::int64_t iterations = 0;
  double elapsed_seconds = 0.0;   ///< Since this process started training.
  double steps_per_second = 0.0;  ///< Over this process's training.
  double mean_return = 0.0;       ///< Raw, last 100 episodes; NaN before the first.
  double mean_length = 0.0;       ///< NaN before the first episode.
  PpoUpdateStatistics update;     ///< The last update's statistics.
};

class TrainingRun {
 public:
  /// Prepares a new run in `run_dir` (created if needed) and locks it (RunDirectoryLock)
  /// until destroyed. Throws std::invalid_argument on a bad config or environment,
  /// std::runtime_error if `run_dir` already holds a run with a checkpoint or a final model
  /// or another trainer holds it. A run directory whose run stopped before its first
  /// checkpoint is started over (its progress.csv and events files are removed).
  ///
  /// With a `communicator` of several ranks, the run is one rank of a data-parallel run
  /// (Ppo::set_communicator): each rank steps config.num_envs environments of its own
  /// (environment i of rank r takes seed + r·num_envs + i), the normalisation statistics
  /// are merged over the ranks after each iteration, and rank 0 alone writes the run
  /// directory (config, logs, checkpoints, final model). Timesteps count every rank's.
  ///
  /// A non-empty `run_dir` that is not an upkie-rl run (is_run_directory: a user's files)
  /// is refused with std::invalid_argument, touching nothing, unless `allow_non_run_dir`.
  /// A start refused after the directory was created (a bad environment option, a viewer
  /// that cannot start) removes what it created when the TrainingRun is destroyed before
  /// train().
  TrainingRun(const TrainingConfig& config, const std::filesystem::path& run_dir,
              std::shared_ptr<Communicator> communicator = nullptr, bool allow_non_run_dir = false);

  /// Continues the run saved in `checkpoint`, in `run_dir` (default: the run directory the
  /// checkpoint belongs to). Throws CheckpointError on a bad checkpoint,
  /// std::invalid_argument when `run_dir` is another run's non-empty directory (unless
  /// `allow_other_run_dir`), std::runtime_error when another trainer holds it.
  /// Every rank of a data-parallel run reads the same checkpoint (rank 0's); the world size
  /// may differ from the one that wrote it.
  static std::unique_ptr<TrainingRun> resume(const std::filesystem::path& checkpoint,
                                             std::optional<std::filesystem::path> run_dir = {},
                                             std::shared_ptr<Communicator> communicator = nullptr,
                                             bool allow_other_run_dir = false);

  /// Rank 0 of a data-parallel run, or a run alone: the one that writes.
  bool writes_outputs() const { return communicator_->rank() == 0; }

  /// Trains until config.ppo.total_timesteps, calling `on_progress` after each update, and
  /// saves the final model. Returns the path of the final model checkpoint.
  std::filesystem::path train(const std::function<void(const TrainingProgress&)>& on_progress = {});

  /// Calls `observer` after every vector step of train() with environment `index`'s full
  /// observation (after an auto-reset, the new episode's first), the action it took, its raw
  /// reward and whether its episode ended at that step; for viewers. The environment must
  /// have full observations (simulated or spine ones).
  /// @throws std::invalid_argument when `index` is not an environment of the run.
  using EnvObserver =
      std::function<void(const Observation& observation, std::span<const float> action,
                         double reward, bool episode_ended)>;
  void observe_env(std::size_t index, EnvObserver observer);

  const TrainingConfig& config() const { return config_; }
  const std::filesystem::path& run_dir() const { return run_dir_; }
  const Ppo& ppo() const { return *ppo_; }
  /// Path of the last checkpoint written by this run, if any.
  const std::optional<std::filesystem::path>& last_checkpoint() const { return last_checkpoint_; }
  /// The TorchScript export of the final model (after train()).
  const std::filesystem::path& torchscript_path() const { return torchscript_path_; }

  /// Tags of progress.csv, in order.
  static std::vector<std::string> logged_tags();
  /// `episode/reward_<term>`: the tag of a reward term's mean episode sum (logged after
  /// logged_tags() when the environment breaks its reward down).
  static std::string reward_term_tag(std::string_view term);

 private:
  struct ResumeTag {};
  TrainingRun(ResumeTag, TrainingConfig config, std::filesystem::path run_dir,
              std::shared_ptr<Communicator> communicator);
  void make_learner();
  void save_checkpoint_now();
  std::uint64_t segment_seed() const;
  /// New episodes (and, on ranks other than 0, a new random stream) at the start of
  /// training and after each checkpoint: what a resumed run starts from too.
  void start_segment();
  std::filesystem::path save_final_model();

  TrainingConfig config_;
  std::filesystem::path run_dir_;
  std::unique_ptr<RunDirectoryLock> lock_;  // rank 0's, from construction to destruction
  VecNormalize* normalize_ = nullptr;       // owned by env_
  std::unique_ptr<VectorEnv> env_;
  std::unique_ptr<Ppo> ppo_;
  std::shared_ptr<Communicator> communicator_;
  std::int64_t checkpoints_saved_ = 0;
  std::optional<std::int64_t> resumed_at_;
  std::optional<std::filesystem::path> last_checkpoint_;
  std::filesystem::path torchscript_path_;
};

}  // namespace upkie_rl
