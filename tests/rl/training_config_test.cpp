#include "rl/runs/training_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/temp_files.hpp"

namespace upkie_rl {
namespace {

std::string config_path(const std::string& name) {
  return std::string(UPKIE_RL_SOURCE_DIR) + "/configs/" + name;
}

void expect_error_mentions(const std::function<void()>& action, const std::string& text) {
  try {
    action();
    FAIL() << "expected an error mentioning '" << text << "'";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
}

TEST(TrainingConfig, PendulumFileHoldsTheSeedConfiguration) {
  const TrainingConfig config = load_training_config(config_path("pendulum.yaml"));
  EXPECT_EQ(config.env_id, "Upkie-Bullet-Pendulum");
  EXPECT_EQ(config.num_envs, 10);
  EXPECT_EQ(config.ppo.total_timesteps, 1'000'000);
  EXPECT_EQ(config.policy.actor_hidden_sizes, (std::vector<std::int64_t>{64, 64}));
  EXPECT_EQ(config.policy.critic_hidden_sizes, (std::vector<std::int64_t>{64, 64}));
  EXPECT_EQ(config.policy.activation, Activation::kReLU);
  EXPECT_DOUBLE_EQ(config.ppo.learning_rate_initial, 2e-4);
  EXPECT_DOUBLE_EQ(config.ppo.learning_rate_final, 1e-5);
  EXPECT_EQ(config.ppo.n_steps, 2048);
  EXPECT_EQ(config.steps_per_env(), 204);
  EXPECT_EQ(config.ppo.batch_size, 128);
  EXPECT_EQ(config.ppo.n_epochs, 5);
  EXPECT_DOUBLE_EQ(config.ppo.gamma, 0.99);
  EXPECT_DOUBLE_EQ(config.ppo.gae_lambda, 0.95);
  EXPECT_DOUBLE_EQ(config.ppo.clip_range, 0.2);
  EXPECT_DOUBLE_EQ(config.ppo.clip_range_vf, 0.2);
  EXPECT_DOUBLE_EQ(config.ppo.ent_coef, 0.0);
  EXPECT_DOUBLE_EQ(config.ppo.vf_coef, 0.5);
  EXPECT_DOUBLE_EQ(config.ppo.max_grad_norm, 0.5);
  EXPECT_TRUE(config.normalize.observations);
  EXPECT_TRUE(config.normalize.rewards);
  EXPECT_DOUBLE_EQ(config.normalize.clip_observations, 10.0);
  EXPECT_EQ(config.checkpoint_every, 50'000);
  ASSERT_EQ(config.env_options.size(), 1u);
  EXPECT_EQ(config.env_options[0].first, "frequency");
  EXPECT_EQ(config.env_options[0].second, "200");
  EXPECT_NO_THROW(config.validate());
}

TEST(TrainingConfig, ServosFileHoldsTheSeedConfiguration) {
  const TrainingConfig config = load_training_config(config_path("servos.yaml"));
  EXPECT_EQ(config.num_envs, 8);
  EXPECT_EQ(config.ppo.total_timesteps, 2'000'000);
  EXPECT_EQ(config.policy.actor_hidden_sizes, (std::vector<std::int64_t>{128, 128}));
  EXPECT_EQ(config.steps_per_env(), 256);
  EXPECT_NO_THROW(config.validate());
}

TEST(TrainingConfig, ResolvedYamlReadsBackIdentically) {
  TrainingConfig config = load_training_config(config_path("pendulum.yaml"));
  apply_overrides(config, {"ppo.learning_rate_initial=0.000123", "policy.activation=tanh",
                           "env.options.fall_pitch=0.8", "seed=42"});
  const std::string yaml = to_yaml(config);
  const TrainingConfig again = parse_training_config(yaml);
  EXPECT_EQ(to_yaml(again), yaml);
  EXPECT_DOUBLE_EQ(again.ppo.learning_rate_initial, 0.000123);
  EXPECT_EQ(again.policy.activation, Activation::kTanh);
  EXPECT_EQ(again.seed, 42u);
  ASSERT_EQ(again.env_options.size(), 2u);
  EXPECT_EQ(again.env_options[1].first, "fall_pitch");
  EXPECT_EQ(again.env_options[1].second, "0.8");
}

TEST(TrainingConfig, GradientMethodFollowsTheActivation) {
  TrainingConfig config;
  EXPECT_EQ(config.ppo.gradient, GradientMethod::kAuto);
  EXPECT_TRUE(uses_hand_gradient(config));  // relu
  apply_overrides(config, {"policy.activation=elu"});
  EXPECT_FALSE(uses_hand_gradient(config));
  apply_overrides(config, {"ppo.gradient=hand"});
  expect_error_mentions([&] { config.validate(); }, "ppo.gradient");
  apply_overrides(config, {"policy.activation=tanh"});
  EXPECT_NO_THROW(config.validate());
  EXPECT_TRUE(uses_hand_gradient(config));
  apply_overrides(config, {"ppo.gradient=autograd"});
  EXPECT_FALSE(uses_hand_gradient(config));
  EXPECT_EQ(parse_training_config(to_yaml(config)).ppo.gradient, GradientMethod::kAutograd);
  expect_error_mentions([&] { apply_overrides(config, {"ppo.gradient=fast"}); }, "ppo.gradient");
}

TEST(TrainingConfig, UpdateThreadsAreOneOrTwo) {
  TrainingConfig config;
  EXPECT_EQ(config.ppo.update_threads, 2);
  apply_overrides(config, {"ppo.update_threads=1"});
  EXPECT_NO_THROW(config.validate());
  EXPECT_EQ(parse_training_config(to_yaml(config)).ppo.update_threads, 1);
  EXPECT_EQ(parse_training_config("ppo:\n  update_threads: 2\n").ppo.update_threads, 2);
  for (const char* bad : {"ppo.update_threads=0", "ppo.update_threads=3"}) {
    TrainingConfig broken;
    apply_overrides(broken, {bad});
    expect_error_mentions([&] { broken.validate(); }, "'ppo.update_threads'");
  }
  expect_error_mentions([&] { apply_overrides(config, {"ppo.update_threads=two"}); },
                        "ppo.update_threads");
}

TEST(TrainingConfig, ActivationAcceptsEverySpellingTheParserKnows) {
  // PyTorch's class names (as Stable-Baselines3 and checkpoint converters write them) load
  // as well as the lower-case names, in YAML and in overrides; to_yaml writes the latter.
  const TrainingConfig relu = parse_training_config("policy:\n  activation: ReLU\n");
  EXPECT_EQ(relu.policy.activation, Activation::kReLU);
  const TrainingConfig tanh = parse_training_config("policy:\n  activation: Tanh\n");
  EXPECT_EQ(tanh.policy.activation, Activation::kTanh);
  EXPECT_NE(to_yaml(tanh).find("activation: tanh"), std::string::npos) << to_yaml(tanh);
  TrainingConfig config;
  apply_overrides(config, {"policy.activation=LeakyReLU"});
  EXPECT_EQ(config.policy.activation, Activation::kLeakyReLU);
  apply_overrides(config, {"policy.activation= Tanh"});
  EXPECT_EQ(config.policy.activation, Activation::kTanh);
  expect_error_mentions([] { parse_training_config("policy:\n  activation: RELU\n"); },
                        "policy.activation");
}

TEST(TrainingConfig, UnknownKeysAreRefusedByName) {
  expect_error_mentions([] { parse_training_config("ppo:\n  batch_sise: 64\n"); },
                        "ppo.batch_sise");
  expect_error_mentions([] { parse_training_config("learning_rate: 1\n"); }, "learning_rate");
  expect_error_mentions([] { parse_training_config("optimizer:\n  lr: 1\n"); }, "optimizer");
  TrainingConfig config;
  expect_error_mentions([&] { apply_overrides(config, {"ppo.n_epoch=3"}); }, "ppo.n_epoch");
  expect_error_mentions([&] { apply_overrides(config, {"no_equal_sign"}); }, "key=value");
}

// YAML allows any node as a mapping key; the parser threw yaml-cpp's TypedBadConversion
// (not std::invalid_argument) on them, found by the training configuration's fuzz target.
TEST(TrainingConfig, KeysThatAreNotNamesAreRefusedWithTheirLine) {
  expect_error_mentions([] { parse_training_config("seed: 1\n? options:\n    a: 1\n"); },
                        "line 2: a key at the top level is not a plain name");
  expect_error_mentions([] { parse_training_config("ppo:\n  ? [n_steps]\n  : 64\n"); },
                        "a key under 'ppo' is not a plain name");
  expect_error_mentions([] { parse_training_config("env:\n  options:\n    ~: 1\n"); },
                        "a key under 'env.options' is not a plain name");
}

// YAML::Dump wrote a value ending in carriage returns raw, and it read back one shorter
// (found by the training configuration's fuzz target; its input is in the corpus). Every
// value the parser accepts, control characters and YAML's own syntax included, is written
// back to the same value, as keys too.
TEST(TrainingConfig, EveryAcceptedTextIsWrittenBackExactly) {
  const std::vector<std::string> texts = {"true            \r\r\r",
                                          "\rleading",
                                          "a\tb\x01\x1b\x7f",
                                          "a: b # not a comment",
                                          "\"quoted\" and 'single'",
                                          " padded ",
                                          "- dash",
                                          "{[braces]}",
                                          "line\nbreak",
                                          "caf\xc3\xa9",
                                          "~"};
  TrainingConfig config;
  config.env_id = "Upkie\r-Pendulum";
  for (std::size_t i = 0; i < texts.size(); ++i) {
    config.env_options.emplace_back("option_" + std::to_string(i), texts[i]);
    config.env_options.emplace_back(texts[i] + "_name", "1");
  }
  ASSERT_NO_THROW(config.validate());
  const std::string yaml = to_yaml(config);
  const TrainingConfig read = parse_training_config(yaml);
  EXPECT_EQ(read.env_id, config.env_id) << yaml;
  EXPECT_EQ(read.env_options, config.env_options) << yaml;
  EXPECT_EQ(to_yaml(read), yaml);
  // The fuzz target's input: a value with trailing spaces and carriage returns.
  const TrainingConfig crlf =
      parse_training_config("env:\n  options:\n    observe_pitch: true  \r\r\r # IMU\n");
  ASSERT_EQ(crlf.env_options.size(), 1u);
  EXPECT_EQ(to_yaml(parse_training_config(to_yaml(crlf))), to_yaml(crlf));
  EXPECT_EQ(parse_training_config(to_yaml(crlf)).env_options, crlf.env_options);
}

TEST(TrainingConfig, MalformedValuesNameTheirKey) {
  expect_error_mentions([] { parse_training_config("ppo:\n  batch_size: many\n"); },
                        "ppo.batch_size");
  expect_error_mentions([] { parse_training_config("ppo:\n  gamma: [1, 2]\n"); }, "ppo.gamma");
  expect_error_mentions([] { parse_training_config("policy:\n  activation: swish\n"); },
                        "policy.activation");
  expect_error_mentions([] { parse_training_config("policy:\n  actor_hidden_sizes: [64, -1]\n"); },
                        "policy.actor_hidden_sizes");
  expect_error_mentions([] { parse_training_config("normalize:\n  rewards: maybe\n"); },
                        "normalize.rewards");
  expect_error_mentions([] { parse_training_config("ppo: [1, 2\n"); }, "malformed YAML");
  TrainingConfig config;
  expect_error_mentions([&] { apply_overrides(config, {"ppo.n_epochs=3.5"}); }, "ppo.n_epochs");
}

TEST(TrainingConfig, ValidateNamesTheInconsistentKey) {
  TrainingConfig config;
  config.ppo.batch_size = 0;
  expect_error_mentions([&] { config.validate(); }, "ppo.batch_size");
  config = TrainingConfig{};
  config.ppo.batch_size = 4096;  // more than one rollout
  expect_error_mentions([&] { config.validate(); }, "ppo.batch_size");
  config = TrainingConfig{};
  config.num_envs = 0;
  expect_error_mentions([&] { config.validate(); }, "env.num_envs");
  config = TrainingConfig{};
  config.mix_envs = 2;  // and no env.mix_id
  expect_error_mentions([&] { config.validate(); }, "env.mix_id");
  config.mix_env_id = "Upkie-MuJoCo-Pendulum";
  config.mix_envs = config.num_envs;  // none left of env.id
  expect_error_mentions([&] { config.validate(); }, "env.mix_envs");
  config.mix_envs = config.num_envs - 1;
  EXPECT_NO_THROW(config.validate());
}

TEST(TrainingConfig, CurriculumRampsTheRandomisationScale) {
  TrainingConfig config = parse_training_config("env:\n  curriculum_steps: 1000\n");
  EXPECT_EQ(config.curriculum_steps, 1000);
  EXPECT_EQ(config.randomization_scale(0), 0.0);
  EXPECT_EQ(config.randomization_scale(250), 0.25);
  EXPECT_EQ(config.randomization_scale(1000), 1.0);
  EXPECT_EQ(config.randomization_scale(5000), 1.0);
  config.curriculum_steps = 0;
  EXPECT_EQ(config.randomization_scale(0), 1.0);  // no curriculum: full from the start
  EXPECT_NE(
      to_yaml(parse_training_config("env:\n  curriculum_steps: 7\n")).find("curriculum_steps: 7"),
      std::string::npos);
  config.curriculum_steps = -1;
  EXPECT_THROW(config.validate(), std::invalid_argument);
}

TEST(TrainingConfig, RobustAndServosBalanceFilesAreValid) {
  for (const char* name : {"pendulum_robust.yaml", "servos_balance.yaml"}) {
    const TrainingConfig config =
        load_training_config(std::string(UPKIE_RL_SOURCE_DIR) + "/configs/" + name);
    EXPECT_NO_THROW(config.validate()) << name;
    EXPECT_FALSE(config.env_options.empty()) << name;
  }
}

TEST(TrainingConfig, ABaseIsReadFirstAndTheFilesKeysOverIt) {
  const auto folder = testing::temp_path("bases") / "derived";
  std::filesystem::create_directories(folder);
  testing::write_bytes(folder.parent_path() / "base.yaml",
                       "env:\n  id: Upkie-MuJoCo-Velocity\n  num_envs: 4\n"
                       "  options: {push_force: 10, nb_substeps: 10}\nseed: 3\n");
  testing::write_bytes(folder / "robust.yaml",
                       "base: ../base.yaml  # relative to this file\n"
                       "env:\n  options: {push_force: 20, slope_variation: 8}\nseed: 5\n");
  const TrainingConfig config = load_training_config((folder / "robust.yaml").string());
  EXPECT_EQ(config.env_id, "Upkie-MuJoCo-Velocity");  // the base's
  EXPECT_EQ(config.num_envs, 4);
  EXPECT_EQ(config.seed, 5u);  // the file's, over the base's
  const std::vector<std::pair<std::string, std::string>> options = {
      {"push_force", "20"}, {"nb_substeps", "10"}, {"slope_variation", "8"}};
  EXPECT_EQ(config.env_options, options);
  // What a run directory saves is the whole resolved configuration, without the base.
  const std::string yaml = to_yaml(config);
  EXPECT_EQ(yaml.find("base:"), std::string::npos) << yaml;
  EXPECT_EQ(parse_training_config(yaml).env_options, options);
}

TEST(TrainingConfig, ShippedRobustVelocityFileExtendsTheScratchOne) {
  const TrainingConfig scratch = load_training_config(config_path("velocity_scratch.yaml"));
  const TrainingConfig robust = load_training_config(config_path("velocity_robust.yaml"));
  EXPECT_NO_THROW(robust.validate());
  EXPECT_EQ(robust.ppo.total_timesteps, scratch.ppo.total_timesteps);
  EXPECT_GT(robust.env_options.size(), scratch.env_options.size());
}

TEST(TrainingConfig, BadBasesAreRefusedByName) {
  const auto folder = testing::temp_path("bad_bases");
  std::filesystem::create_directories(folder);
  const auto write = [&](const std::string& name, const std::string& text) {
    testing::write_bytes(folder / name, text);
    return (folder / name).string();
  };
  write("a.yaml", "base: b.yaml\n");
  const std::string cycle = write("b.yaml", "base: a.yaml\n");
  expect_error_mentions([&] { load_training_config(cycle); }, "a cycle of bases");
  const std::string self = write("self.yaml", "base: ./self.yaml\n");
  expect_error_mentions([&] { load_training_config(self); }, "a cycle of bases");
  const std::string missing = write("missing.yaml", "base: nowhere.yaml\n");
  expect_error_mentions([&] { load_training_config(missing); }, "nowhere.yaml");
  const std::string empty = write("empty.yaml", "base: ''\n");
  expect_error_mentions([&] { load_training_config(empty); }, "config key 'base'");
  const std::string list = write("list.yaml", "base: [a.yaml]\n");
  expect_error_mentions([&] { load_training_config(list); }, "config key 'base'");
  // A bad key of the base names both files.
  write("typo.yaml", "sed: 1\n");
  const std::string derived = write("derived.yaml", "base: typo.yaml\n");
  expect_error_mentions([&] { load_training_config(derived); }, "derived.yaml: ");
  expect_error_mentions([&] { load_training_config(derived); },
                        "typo.yaml: unknown config key 'sed'");
  // A chain of nine files is refused, eight are read.
  for (int i = 1; i <= 8; ++i) {
    write("chain" + std::to_string(i) + ".yaml", "base: chain" + std::to_string(i + 1) + ".yaml\n");
  }
  write("chain9.yaml", "seed: 9\n");
  expect_error_mentions([&] { load_training_config((folder / "chain1.yaml").string()); },
                        "more than 8 files");
  EXPECT_EQ(load_training_config((folder / "chain2.yaml").string()).seed, 9u);
  // Text has no directory to resolve a base against.
  expect_error_mentions([] { parse_training_config("base: a.yaml\n"); }, "only a config file");
}

}  // namespace
}  // namespace upkie_rl
