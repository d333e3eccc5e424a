// Fault injection (issue 26, item 3): a run directory cannot be damaged by a resume, a
// second trainer, a resume into another run, a kill before the first checkpoint or the
// temporary files of an interrupted write.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>

#include "common/temp_files.hpp"
#include "rl/logging/scalar_csv_writer.hpp"
#include "rl/runs/run_directory_lock.hpp"
#include "rl/runs/training_run.hpp"

namespace upkie_rl {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto path = testing::temp_path(name, "upkie_rl_run_safety");
  std::filesystem::remove_all(path);
  std::filesystem::create_directories(path);
  return path;
}

ino_t inode(const std::filesystem::path& path) {
  struct stat status {};
  EXPECT_EQ(::stat(path.c_str(), &status), 0) << path;
  return status.st_ino;
}

TEST(RunSafety, ResumedProgressLogIsReplacedByRenameNotCutInPlace) {
  const auto csv = fresh_directory("csv") / "progress.csv";
  testing::write_bytes(csv, "step,value\n64,1\n128,2\n192,3\n");
  // A reader holding the old file keeps all of it: the writer never truncates it in place.
  std::ifstream old_reader(csv);
  const ino_t before = inode(csv);
  {
    ScalarCsvWriter writer(csv, {"step", "value"}, 128);
    const ScalarValue row[] = {{"step", 192.0f}, {"value", 4.0f}};
    writer.write_row(row);
  }
  EXPECT_NE(inode(csv), before);
  EXPECT_EQ(testing::read_bytes(csv), "step,value\n64,1\n128,2\n192,4\n");
  const std::string old_text{std::istreambuf_iterator<char>(old_reader),
                             std::istreambuf_iterator<char>()};
  EXPECT_EQ(old_text, "step,value\n64,1\n128,2\n192,3\n");
  EXPECT_FALSE(std::filesystem::exists(csv.string() + ".tmp." + std::to_string(::getpid())));
}

TEST(RunSafety, EmptyProgressLogOfAnOlderKilledResumeDoesNotBlockResuming) {
  const auto csv = fresh_directory("empty_csv") / "progress.csv";
  testing::write_bytes(csv, "");
  EXPECT_NO_THROW(ScalarCsvWriter(csv, {"step", "value"}, 128));
  EXPECT_EQ(testing::read_bytes(csv), "step,value\n");
}

TEST(RunSafety, SecondTrainerInTheSameDirectoryIsRefused) {
  const auto run = fresh_directory("locked");
  RunDirectoryLock first(run);
  try {
    RunDirectoryLock second(run);
    FAIL() << "a second lock was granted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what())
                  .find("in use by another trainer (process " + std::to_string(::getpid()) + ")"),
              std::string::npos)
        << error.what();
  }
}

TEST(RunSafety, LockIsReleasedWithItsOwner) {
  const auto run = fresh_directory("released");
  { RunDirectoryLock first(run); }
  EXPECT_NO_THROW(RunDirectoryLock again(run));
}

TEST(RunSafety, StaleTemporariesAreRemovedAndNothingElse) {
  const auto run = fresh_directory("stale");
  std::filesystem::create_directories(run / "checkpoints");
  testing::write_bytes(run / "checkpoints" / "checkpoint_000000128_steps.ckpt.tmp.4242", "x");
  testing::write_bytes(run / "progress.csv.tmp.77", "x");
  testing::write_bytes(run / "checkpoints" / "checkpoint_000000064_steps.ckpt", "kept");
  testing::write_bytes(run / "progress.csv", "kept");
  EXPECT_EQ(remove_stale_temporaries(run), 2);
  EXPECT_TRUE(std::filesystem::exists(run / "checkpoints" / "checkpoint_000000064_steps.ckpt"));
  EXPECT_TRUE(std::filesystem::exists(run / "progress.csv"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(run / "checkpoints"),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(RunSafety, ResumeIntoAnotherNonEmptyRunIsRefusedAndTouchesNothing) {
  const auto run_a = fresh_directory("run_a");
  const auto run_b = fresh_directory("run_b");
  std::filesystem::create_directories(run_a / "checkpoints");
  const auto checkpoint = run_a / "checkpoints" / "checkpoint_000000128_steps.ckpt";
  std::filesystem::copy_file(
      std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "tests/data/policies/pendulum_bullet_seed0.ckpt",
      checkpoint);
  testing::write_bytes(run_b / "progress.csv", "step\n1\n");
  testing::write_bytes(run_b / "config.yaml", "seed: 3\n");
  try {
    TrainingRun::resume(checkpoint, run_b);
    FAIL() << "resumed into another run";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("--force-run-dir"), std::string::npos) << error.what();
  }
  EXPECT_EQ(testing::read_bytes(run_b / "progress.csv"), "step\n1\n");
  EXPECT_EQ(testing::read_bytes(run_b / "config.yaml"), "seed: 3\n");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(run_b),
                          std::filesystem::directory_iterator()),
            2);
}

TEST(RunSafety, RunKilledBeforeItsFirstCheckpointStartsOver) {
  const auto run = fresh_directory("killed_early");
  TrainingConfig config =
      load_training_config(std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml");
  apply_overrides(config, {"env.num_envs=1", "env.threads=0", "ppo.n_steps=16", "ppo.batch_size=16",
                           "ppo.total_timesteps=16", "policy.actor_hidden_sizes=[8]",
                           "policy.critic_hidden_sizes=[8]"});
  // What a trainer killed during its first rollout leaves.
  testing::write_bytes(run / ".lock", "12345");
  testing::write_bytes(run / "config.yaml", to_yaml(config));
  testing::write_bytes(run / "progress.csv", "time/total_timesteps\n");
  testing::write_bytes(run / "events.out.tfevents.1.host", "x");
  EXPECT_NO_THROW(TrainingRun(config, run));
  EXPECT_FALSE(std::filesystem::exists(run / "events.out.tfevents.1.host"));
  EXPECT_FALSE(std::filesystem::exists(run / "progress.csv"));
  // With a checkpoint, the run is kept and refused.
  std::filesystem::create_directories(run / "checkpoints");
  testing::write_bytes(run / "checkpoints" / "checkpoint_000000016_steps.ckpt", "x");
  EXPECT_THROW(TrainingRun(config, run), std::runtime_error);
}

}  // namespace
}  // namespace upkie_rl
