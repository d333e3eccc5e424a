#include "rl/runs/training_run.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include "rl/logging/scalar_csv_writer.hpp"
#include "rl/logging/tensorboard_writer.hpp"
#include "rl/runs/checkpoint.hpp"

namespace upkie_rl {
namespace {

std::filesystem::path fresh_directory(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("upkie_rl_run_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(path);
  return path;
}

// The pendulum configuration, shrunk: 5 updates of 64 steps, checkpoints every 128 steps.
TrainingConfig tiny_pendulum(std::int64_t threads) {
  TrainingConfig config =
      load_training_config(std::string(UPKIE_RL_SOURCE_DIR) + "/configs/pendulum.yaml");
  apply_overrides(config, {"env.num_envs=2", "env.threads=" + std::to_string(threads),
                           "ppo.n_steps=64", "ppo.batch_size=32", "ppo.n_epochs=2",
                           "ppo.total_timesteps=320", "checkpoint_every=128",
                           "policy.actor_hidden_sizes=[16]", "policy.critic_hidden_sizes=[16]"});
  return config;
}

TEST(TrainingRun, WritesTheRunDirectoryAndResumesToTheSameResult) {
  for (const std::int64_t threads : {0, 2}) {
    const auto run_a = fresh_directory("a" + std::to_string(threads));
    const auto run_b = fresh_directory("b" + std::to_string(threads));
    TrainingRun run(tiny_pendulum(threads), run_a);
    int callbacks = 0;
    const std::filesystem::path model = run.train([&](const TrainingProgress& progress) {
      ++callbacks;
      EXPECT_EQ(progress.timesteps, 64 * callbacks);
    });
    EXPECT_EQ(callbacks, 5);
    EXPECT_TRUE(std::filesystem::exists(model));
    EXPECT_TRUE(std::filesystem::exists(run.torchscript_path()));
    EXPECT_TRUE(std::filesystem::exists(run_a / "config.yaml"));
    const auto first = run_a / "checkpoints" / "checkpoint_000000128_steps.ckpt";
    EXPECT_TRUE(std::filesystem::exists(first));
    EXPECT_TRUE(std::filesystem::exists(run_a / "checkpoints" / "checkpoint_000000256_steps.ckpt"));
    const ScalarTable table = read_scalar_csv(run_a / "progress.csv");
    ASSERT_EQ(table.rows.size(), 5u);
    EXPECT_EQ(table.rows[4][table.index("time/total_timesteps")], 320.0);

    // The event file holds the same scalars, with valid CRCs (read_event_file checks them).
    std::vector<TensorBoardEvent> events;
    for (const auto& entry : std::filesystem::directory_iterator(run_a)) {
      if (entry.path().filename().string().find("tfevents") != std::string::npos) {
        events = read_event_file(entry.path());
      }
    }
    ASSERT_EQ(events.size(), 6u);  // file version + 5 updates
    EXPECT_EQ(events[0].file_version, "brain.Event:2");
    bool found_loss = false;
    for (const ScalarValue& scalar : events[5].scalars) {
      if (scalar.tag == "train/loss") {
        found_loss = true;
        EXPECT_FLOAT_EQ(scalar.value, static_cast<float>(table.rows[4][table.index("train/loss")]));
      }
    }
    EXPECT_TRUE(found_loss);
    EXPECT_EQ(events[5].step, 320);

    // Resume a copy of the run from its first checkpoint: same final weights, same log.
    std::filesystem::copy(run_a, run_b, std::filesystem::copy_options::recursive);
    auto resumed = TrainingRun::resume(run_b / "checkpoints" / first.filename());
    EXPECT_EQ(resumed->run_dir(), run_b);
    EXPECT_EQ(resumed->ppo().num_timesteps(), 128);
    resumed->train();
    EXPECT_TRUE(torch::equal(resumed->ppo().policy().flat_parameters(),
                             run.ppo().policy().flat_parameters()))
        << "threads " << threads;
    const ScalarTable resumed_table = read_scalar_csv(run_b / "progress.csv");
    ASSERT_EQ(resumed_table.rows.size(), 5u);
    for (std::size_t row = 0; row < 5; ++row) {
      EXPECT_EQ(resumed_table.rows[row][table.index("train/loss")],
                table.rows[row][table.index("train/loss")]);
      const double expected = table.rows[row][table.index("rollout/ep_len_mean")];
      const double actual = resumed_table.rows[row][table.index("rollout/ep_len_mean")];
      EXPECT_TRUE(actual == expected || (std::isnan(actual) && std::isnan(expected)))
          << actual << " vs " << expected;
    }
    std::filesystem::remove_all(run_a);
    std::filesystem::remove_all(run_b);
  }
}

TEST(TrainingRun, RefusesAnExistingRunAndBadInput) {
  const auto directory = fresh_directory("existing");
  {
    // A run with checkpoints is refused (one killed before its first one starts over:
    // RunSafety tests that).
    TrainingRun run(tiny_pendulum(0), directory);
    run.train();
  }
  EXPECT_THROW(TrainingRun(tiny_pendulum(0), directory), std::runtime_error);
  TrainingConfig unknown = tiny_pendulum(0);
  unknown.env_id = "Upkie-Bullet-Unicycle";
  EXPECT_THROW(TrainingRun(unknown, fresh_directory("unknown")), std::invalid_argument);
  // A corrupted checkpoint cannot be resumed.
  const auto bad = directory / "bad.ckpt";
  std::ofstream(bad) << "UPKIERL1 and then nothing sensible";
  EXPECT_THROW(TrainingRun::resume(bad), CheckpointError);
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace upkie_rl
