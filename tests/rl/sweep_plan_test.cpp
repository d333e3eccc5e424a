/// The plan of a sweep: seed lists, axes, the grid, run names, and the sweep file read back.

#include "rl/runs/sweep_plan.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::temp_path;
using testing::write_bytes;

TEST(SweepPlan, SeedListsAreRangesListsOrOneSeed) {
  EXPECT_EQ(parse_seed_list("0:5"), (std::vector<std::uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(parse_seed_list("7,3,9"), (std::vector<std::uint64_t>{7, 3, 9}));
  EXPECT_EQ(parse_seed_list("42"), (std::vector<std::uint64_t>{42}));
  for (const char* bad : {"", "5:2", "3:3", "a:4", "1,,2", "-1", "1,1", "0:1000000"}) {
    EXPECT_THROW(parse_seed_list(bad), std::invalid_argument) << bad;
  }
}

TEST(SweepPlan, AxisValuesSplitAtCommasOutsideBrackets) {
  const SweepAxis axis = parse_sweep_axis("policy.actor_hidden_sizes=[64,64],[128,128]");
  EXPECT_EQ(axis.key, "policy.actor_hidden_sizes");
  EXPECT_EQ(axis.values, (std::vector<std::string>{"[64,64]", "[128,128]"}));
  for (const char* bad : {"no_equal", "=1,2", "ppo.gamma=0.9,,0.99", "ppo.gamma=0.9,0.9"}) {
    EXPECT_THROW(parse_sweep_axis(bad), std::invalid_argument) << bad;
  }
}

TEST(SweepPlan, TheGridHasEveryCombinationThenEverySeed) {
  const SweepPlan plan = make_sweep_plan(
      TrainingConfig{}, {0, 1},
      {parse_sweep_axis("ppo.gamma=0.9,0.99"), parse_sweep_axis("ppo.n_epochs=3,5,10")}, 4);
  ASSERT_EQ(plan.runs.size(), 12U);
  EXPECT_EQ(plan.runs[0].name, "gamma=0.9_n_epochs=3_seed0");
  EXPECT_EQ(plan.runs[1].name, "gamma=0.9_n_epochs=3_seed1");
  EXPECT_EQ(plan.runs[2].name, "gamma=0.9_n_epochs=5_seed0");
  EXPECT_EQ(plan.runs[11].overrides,
            (std::vector<std::string>{"ppo.gamma=0.99", "ppo.n_epochs=10"}));
  EXPECT_EQ(plan.runs[11].seed, 1U);
  EXPECT_EQ(sweep_group_label(plan.runs[11]), "ppo.gamma=0.99 ppo.n_epochs=10");
  const TrainingConfig config = sweep_run_config(TrainingConfig{}, plan.runs[11]);
  EXPECT_DOUBLE_EQ(config.ppo.gamma, 0.99);
  EXPECT_EQ(config.ppo.n_epochs, 10);
  EXPECT_EQ(config.seed, 1U);
}

TEST(SweepPlan, WithoutAxesTheRunsAreTheSeeds) {
  const SweepPlan plan = make_sweep_plan(TrainingConfig{}, {3, 4}, {}, 1);
  ASSERT_EQ(plan.runs.size(), 2U);
  EXPECT_EQ(plan.runs[0].name, "seed3");
  EXPECT_EQ(sweep_group_label(plan.runs[1]), "base");
}

TEST(SweepPlan, KeysSharingTheirLastPartAreNamedInFull) {
  const SweepPlan plan = make_sweep_plan(
      TrainingConfig{}, {0},
      {parse_sweep_axis("ppo.gamma=0.9,0.99"), parse_sweep_axis("normalize.gamma=0.9,0.99")}, 1);
  EXPECT_EQ(plan.runs[0].name, "ppo.gamma=0.9_normalize.gamma=0.9_seed0");
}

TEST(SweepPlan, BadRunsFailBeforeAnyTrainingNamingTheRunAndTheKey) {
  try {
    make_sweep_plan(TrainingConfig{}, {0}, {parse_sweep_axis("ppo.n_epochs=5,-1")}, 1);
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("n_epochs=-1_seed0"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("ppo.n_epochs"), std::string::npos) << error.what();
  }
  EXPECT_THROW(make_sweep_plan(TrainingConfig{}, {0}, {parse_sweep_axis("ppo.nope=1,2")}, 1),
               std::invalid_argument);
  EXPECT_THROW(make_sweep_plan(TrainingConfig{}, {0}, {parse_sweep_axis("seed=1,2")}, 1),
               std::invalid_argument);
  EXPECT_THROW(
      make_sweep_plan(
          TrainingConfig{}, {0},
          {parse_sweep_axis("ppo.gamma=0.9,0.8"), parse_sweep_axis("ppo.gamma=0.7,0.6")}, 1),
      std::invalid_argument);
  EXPECT_THROW(make_sweep_plan(TrainingConfig{}, {}, {}, 1), std::invalid_argument);
  EXPECT_THROW(make_sweep_plan(TrainingConfig{}, {0}, {}, 0), std::invalid_argument);
}

TEST(SweepPlan, TheSweepFileReadsBackAsWritten) {
  const auto directory = temp_path("sweep_plan_roundtrip");
  std::filesystem::remove_all(directory);
  TrainingConfig base;
  base.ppo.total_timesteps = 12'345;
  const SweepPlan plan = make_sweep_plan(
      base, {0, 2}, {parse_sweep_axis("policy.actor_hidden_sizes=[32,32],[64,64]")}, 7);
  write_sweep(directory, base, plan);
  const Sweep sweep = load_sweep(directory);
  EXPECT_EQ(sweep.base.ppo.total_timesteps, 12'345);
  EXPECT_EQ(sweep.plan.evaluation_episodes, 7);
  EXPECT_EQ(sweep.plan.seeds, plan.seeds);
  ASSERT_EQ(sweep.plan.axes.size(), 1U);
  EXPECT_EQ(sweep.plan.axes[0].values, plan.axes[0].values);
  ASSERT_EQ(sweep.plan.runs.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(sweep.plan.runs[i].name, plan.runs[i].name);
    EXPECT_EQ(sweep.plan.runs[i].seed, plan.runs[i].seed);
    EXPECT_EQ(sweep.plan.runs[i].overrides, plan.runs[i].overrides);
  }
  EXPECT_EQ(sweep.run_dir(plan.runs[3]), directory / "runs" / plan.runs[3].name);

  // The same sweep again continues it; another one is refused, and the first is kept.
  EXPECT_NO_THROW(write_sweep(directory, base, plan));
  const std::string before = read_bytes(directory / "sweep.yaml");
  const SweepPlan other = make_sweep_plan(base, {0}, {}, 7);
  EXPECT_THROW(write_sweep(directory, base, other), std::runtime_error);
  EXPECT_EQ(read_bytes(directory / "sweep.yaml"), before);
}

TEST(SweepPlan, DamagedSweepFilesAreNamedWithTheKey) {
  const auto directory = temp_path("sweep_plan_damaged");
  std::filesystem::remove_all(directory);
  const TrainingConfig base;
  write_sweep(directory, base, make_sweep_plan(base, {0}, {}, 2));
  const std::string good = read_bytes(directory / "sweep.yaml");
  auto error_of = [&](const std::string& text) -> std::string {
    write_bytes(directory / "sweep.yaml", text);
    try {
      load_sweep(directory);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(error_of("evaluation_episodes: 2\n").find("missing key 'evaluation_seed'"),
            std::string::npos);
  std::string bad_seed = good;
  bad_seed.replace(bad_seed.find("seed: 0"), 7, "seed: x");
  EXPECT_NE(error_of(bad_seed).find("key 'seed'"), std::string::npos);
  std::string bad_override = good;
  bad_override.replace(bad_override.find("set: []"), 7, "set: [ppo.n_epochs=-3]");
  EXPECT_NE(error_of(bad_override).find("ppo.n_epochs"), std::string::npos);
  EXPECT_NE(error_of("[unclosed").find("sweep.yaml"), std::string::npos);
  std::filesystem::remove(directory / "sweep.yaml");
  EXPECT_NE(error_of("").find("sweep.yaml"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
