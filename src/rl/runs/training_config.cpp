#include "rl/runs/training_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "base/closest_name.hpp"
#include "base/input_file.hpp"
#include "base/setting_bounds.hpp"
#include "base/trim.hpp"
#include "policy/network_limits.hpp"
#include "rl/ppo/hand_gradient_activations.hpp"
#include "rl/runs/config_file_limit.hpp"
#include "vec/make_vector_env.hpp"

namespace upkie_rl {

namespace {

[[noreturn]] void bad_value(const std::string& key, const std::string& value,
                            const std::string& expected) {
  throw std::invalid_argument("config key '" + key + "': expected " + expected + ", got '" + value +
                              "'");
}

std::string config_key(const std::string& key) { return "config key '" + key + "'"; }

// The values of ppo.gradient, spelled once for parsing, writing and messages.
constexpr std::pair<GradientMethod, const char*> kGradientMethods[] = {
    {GradientMethod::kAuto, "auto"},
    {GradientMethod::kHand, "hand"},
    {GradientMethod::kAutograd, "autograd"},
};

std::vector<std::pair<std::string, GradientMethod>> gradient_choices() {
  std::vector<std::pair<std::string, GradientMethod>> choices;
  for (const auto& [method, name] : kGradientMethods) choices.emplace_back(name, method);
  return choices;
}

constexpr const char* kEnvOptionsPrefix = "env.options.";

/// Where a scalar goes in the YAML to_yaml writes.
enum class ScalarPlace { kKey, kValue };

/// Whether `yaml`, written as a key or a value of a block mapping and followed by another
/// line as in to_yaml's output (a carriage return before the newline reads as CRLF),
/// reads back as `text`.
bool reads_back(const std::string& yaml, const std::string& text, ScalarPlace place) {
  try {
    const std::string line = place == ScalarPlace::kKey ? yaml + ": 0" : "k: " + yaml;
    const YAML::Node map = YAML::Load(line + "\n# the next line\n");
    if (!map.IsMap() || map.size() != 1) return false;
    const YAML::Node node = place == ScalarPlace::kKey ? map.begin()->first : map.begin()->second;
    return node.IsScalar() && node.Scalar() == text;
  } catch (const YAML::Exception&) {
    return false;
  }
}

/// `text` as a one-line YAML scalar that parse_training_config reads back exactly: plain
/// when that reads back, else double-quoted with escapes. YAML::Dump alone writes some
/// control characters raw (a carriage return in a value came back one shorter; found by
/// the fuzz target). Throws std::invalid_argument naming `key` when neither form reads back.
std::string yaml_scalar(const std::string& text, const std::string& key,
                        ScalarPlace place = ScalarPlace::kValue) {
  std::string plain = YAML::Dump(YAML::Node(text));
  if (plain.find('\n') == std::string::npos && reads_back(plain, text, place)) return plain;
  YAML::Emitter quoted;
  quoted << YAML::DoubleQuoted << text;
  if (quoted.good() && reads_back(quoted.c_str(), text, place)) return quoted.c_str();
  throw std::invalid_argument(config_key(key) + ": the value cannot be written back as YAML");
}

// The env.options mapping, in the env section of to_yaml.
std::string env_options_yaml(const std::vector<std::pair<std::string, std::string>>& options) {
  std::string out = "  options:" + std::string(options.empty() ? " {}" : "") + "\n";
  for (const auto& [name, value] : options) {
    const std::string key = kEnvOptionsPrefix + name;
    out +=
        "    " + yaml_scalar(name, key, ScalarPlace::kKey) + ": " + yaml_scalar(value, key) + "\n";
  }
  return out;
}

void set_env_option(TrainingConfig& config, const std::string& name, const std::string& value) {
  if (name.empty()) throw std::invalid_argument("config key 'env.options': empty option name");
  for (auto& [key, existing] : config.env_options) {
    if (key == name) {
      existing = value;
      return;
    }
  }
  config.env_options.emplace_back(name, value);
}

void set_key(TrainingConfig& config, const OptionTable& table, const std::string& key,
             const std::string& value) {
  if (key.rfind(kEnvOptionsPrefix, 0) == 0) {
    set_env_option(config, key.substr(std::string(kEnvOptionsPrefix).size()),
                   std::string(trim(value)));
    return;
  }
  if (!table.contains(key)) {
    throw std::invalid_argument("unknown config key '" + key + "'" +
                                did_you_mean(key, table.names()));
  }
  table.read(key, value, config_key(key));
}

std::string node_text(const YAML::Node& node, const std::string& key) {
  if (node.IsScalar()) return node.Scalar();
  if (node.IsNull()) bad_value(key, "", "a value");
  if (node.IsSequence()) {
    std::string text;
    for (std::size_t i = 0; i < node.size(); ++i) {
      if (!node[i].IsScalar()) bad_value(key, "nested list", "a flat list");
      text += (i ? "," : "") + node[i].Scalar();
    }
    return text;
  }
  bad_value(key, "a mapping", "a value");
}

/// A mapping key as text. YAML allows any node as a key (`? {a: 1}`, `? [x]`, `~`), which
/// as<std::string>() would throw YAML::TypedBadConversion for (found by the fuzzer).
std::string key_name(const YAML::Node& key, const std::string& prefix) {
  if (key.IsScalar()) return key.Scalar();
  throw std::invalid_argument("config: line " + std::to_string(key.Mark().line + 1) + ": a key " +
                              (prefix.empty() ? "at the top level" : "under '" + prefix + "'") +
                              " is not a plain name");
}

void walk(const YAML::Node& node, const std::string& prefix, TrainingConfig& config,
          const OptionTable& table) {
  for (const auto& item : node) {
    const std::string name = key_name(item.first, prefix);
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    const YAML::Node& value = item.second;
    if (key == "env.options") {
      if (value.IsNull()) continue;
      if (!value.IsMap()) bad_value(key, "not a mapping", "a mapping of option names to values");
      for (const auto& option : value) {
        const std::string option_name = key_name(option.first, key);
        set_env_option(config, option_name, node_text(option.second, key + "." + option_name));
      }
    } else if (value.IsMap()) {
      static const std::vector<std::string> kSections = {"env", "normalize", "policy", "ppo"};
      if (prefix.empty() &&
          std::find(kSections.begin(), kSections.end(), name) == kSections.end()) {
        throw std::invalid_argument("unknown config section '" + key + "'" +
                                    did_you_mean(key, kSections));
      }
      walk(value, key, config, table);
    } else {
      set_key(config, table, key, node_text(value, key));
    }
  }
}

}  // namespace

bool uses_hand_gradient(const TrainingConfig& config) {
  return config.ppo.gradient == GradientMethod::kHand ||
         (config.ppo.gradient == GradientMethod::kAuto &&
          hand_gradient_covers(config.policy.activation));
}

std::int64_t steps_per_env(std::int64_t n_steps, std::int64_t num_envs) {
  return std::max<std::int64_t>(1, n_steps / std::max<std::int64_t>(1, num_envs));
}

std::int64_t TrainingConfig::steps_per_env() const {
  return upkie_rl::steps_per_env(ppo.n_steps, num_envs);
}

void TrainingConfig::declare_options(OptionTable& table) {
  declare_run_options(table);
  normalize.declare_options(table, "normalize.");
  policy.declare_options(table);
  ppo.declare_options(table, num_envs, policy.activation);
  table.add_integer<std::uint64_t>("seed", &seed, 0, std::numeric_limits<std::uint64_t>::max(),
                                   "random seed of the environments, the policy and the updates");
  table.add_integer<std::int64_t>("checkpoint_every", &checkpoint_every, 0, kMaxTimesteps,
                                  "timesteps between checkpoints, 0 for none");
  table.add_integer<std::int64_t>("torch_threads", &torch_threads, 1, kMaxTorchThreads,
                                  "intra-op threads of libtorch");
}

void TrainingConfig::declare_run_options(OptionTable& table) {
  table.add_text("env.id", &env_id, "environment id (`upkie-rl envs`)",
                 [this] { return env_id.empty() ? std::string("must not be empty") : ""; });
  table.add_integer<std::int64_t>("env.num_envs", &num_envs, 1,
                                  static_cast<std::int64_t>(kMaxVectorEnvs),
                                  "environments stepped together");
  table.add_text("env.mix_id", &mix_env_id,
                 "the same task on another engine, stepped by env.mix_envs of the environments "
                 "(none: no other)");
  table.add_integer<std::int64_t>(
      "env.mix_envs", &mix_envs, 0, static_cast<std::int64_t>(kMaxVectorEnvs) - 1,
      "environments of env.mix_id, spread among the others", [this] {
        if (mix_envs == 0) return std::string();
        if (mix_env_id == "none") return std::string("needs env.mix_id to name an environment");
        if (mix_envs < num_envs) return std::string();
        return "must be below env.num_envs (" + std::to_string(num_envs) + ")";
      });
  table.add_integer<std::int64_t>("env.threads", &env_threads, 0,
                                  static_cast<std::int64_t>(kMaxEnvThreads),
                                  "worker threads of the vector environment, 0 for none");
  table.add_integer<std::int64_t>("env.curriculum_steps", &curriculum_steps, 0, kMaxTimesteps,
                                  "timesteps over which randomisation ramps up, 0 for none");
}

void PolicyConfig::declare_options(OptionTable& table) {
  table.add_integer_list("policy.actor_hidden_sizes", &actor_hidden_sizes,
                         "hidden layer widths of the actor", check_hidden_sizes);
  table.add_integer_list("policy.critic_hidden_sizes", &critic_hidden_sizes,
                         "hidden layer widths of the critic", check_hidden_sizes);
  // Every spelling parse_activation reads (checkpoint headers and SB3's class names too).
  table.add_choice("policy.activation", &activation, activation_spellings(),
                   "activation of the hidden layers");
  table.add_real("policy.log_std_init", &log_std_init, -20, 5,
                 "initial log standard deviation of the actions");
}

void PpoConfig::declare_options(OptionTable& table, const std::int64_t& num_envs,
                                const Activation& activation) {
  using I = std::int64_t;
  table.add_integer<I>("ppo.total_timesteps", &total_timesteps, 1, kMaxTimesteps,
                       "timesteps of the run");
  // The lower bound is env.num_envs (every environment steps at least once per update).
  table.add_integer<I>("ppo.n_steps", &n_steps, 1, kMaxRolloutSteps,
                       "steps per update, all environments together", [this, &num_envs] {
                         if (n_steps < num_envs)
                           return std::string("must be at least env.num_envs");
                         if (n_steps <= kMaxRolloutSteps) return std::string();
                         return std::to_string(n_steps) + " is outside [" +
                                std::to_string(num_envs) + ", " + std::to_string(kMaxRolloutSteps) +
                                "]";
                       });
  table.add_integer<I>("ppo.batch_size", &batch_size, std::numeric_limits<I>::min(),
                       std::numeric_limits<I>::max(), "minibatch size", [this, &num_envs] {
                         if (batch_size < 1) return std::string("must be at least 1");
                         if (batch_size <= steps_per_env(n_steps, num_envs) * num_envs) {
                           return std::string();
                         }
                         return std::string("must not exceed the steps per update");
                       });
  table.add_integer<I>("ppo.n_epochs", &n_epochs, 1, 10'000, "passes over each rollout");
  table.add_real("ppo.gamma", &gamma, 0, 1, "discount", true);
  table.add_real("ppo.gae_lambda", &gae_lambda, 0, 1, "GAE lambda");
  table.add_real("ppo.clip_range", &clip_range, 0, 100, "policy ratio clipping", true);
  table.add_real("ppo.clip_range_vf", &clip_range_vf, -kMaxClip, kMaxClip,
                 "value clipping range, <= 0 for none");
  table.add_real("ppo.ent_coef", &ent_coef, -1000, 1000, "entropy coefficient");
  table.add_real("ppo.vf_coef", &vf_coef, 0, 1000, "value loss coefficient");
  table.add_real("ppo.max_grad_norm", &max_grad_norm, 0, kMaxClip, "gradient norm clipping", true);
  table.add_real("ppo.learning_rate_initial", &learning_rate_initial, 0, 1,
                 "learning rate at the start (linear schedule)", true);
  table.add_real("ppo.learning_rate_final", &learning_rate_final, 0, 1, "learning rate at the end");
  table.add_real("ppo.adam_eps", &adam_eps, 0, 1, "Adam's epsilon", true);
  table.add_boolean("ppo.normalize_advantage", &normalize_advantage,
                    "normalise advantages per minibatch");
  table.add_choice("ppo.gradient", &gradient, gradient_choices(),
                   "how the gradient is computed (auto: hand when it covers the activation)",
                   [this, &activation] {
                     if (gradient != GradientMethod::kHand || hand_gradient_covers(activation)) {
                       return std::string();
                     }
                     return std::string("hand covers the relu and tanh activations, not ") +
                            activation_name(activation) + "; use autograd or auto";
                   });
  table.add_integer<I>("ppo.update_threads", &update_threads, 1, kMaxUpdateThreads,
                       "threads of the hand-written gradient (2: the critic's part beside the "
                       "actor's, the same results)");
  table.add_boolean("ppo.mirror_augmentation", &mirror_augmentation,
                    "train on each sample and its left-right mirror image");
}

void TrainingConfig::validate() const {
  // The table binds mutable fields: a copy, read only (validate runs once per run).
  TrainingConfig copy = *this;
  OptionTable table;
  copy.declare_options(table);
  table.check(config_key, "config");
  // What is accepted must be saved faithfully (the run directory's config.yaml reproduces
  // the run): to_yaml throws naming a value it cannot write.
  to_yaml(copy);
}

void TrainingConfig::check_allocations(std::int64_t observation_size,
                                       std::int64_t action_size) const {
  const std::int64_t parameters = check_network_size(
      observation_size, action_size, policy.actor_hidden_sizes, policy.critic_hidden_sizes,
      "config key 'policy.actor_hidden_sizes'", "config key 'policy.critic_hidden_sizes'");
  // Weights, gradients, two Adam moments and a spare copy.
  check_allocation("config key 'policy.actor_hidden_sizes'",
                   std::to_string(parameters) + " parameters",
                   5.0 * 4.0 * static_cast<double>(parameters), "the actor-critic");
  // Observations, actions, rewards, dones, values, log-probabilities, advantages, returns
  // and the minibatch permutation, per transition.
  const double transition_bytes =
      4.0 * static_cast<double>(observation_size + action_size + 6) + 8.0;
  check_allocation("config key 'ppo.n_steps'", std::to_string(ppo.n_steps),
                   transition_bytes * static_cast<double>(steps_per_env() * num_envs),
                   "the rollout buffer");
}

namespace {

/// The top-level key naming the configuration file a file extends.
constexpr const char* kBaseKey = "base";

/// Files in one chain of bases, the first included. Why a bound: a cycle is refused by name
/// (below), and a chain longer than any hand-written one is a mistake, not a layout.
constexpr std::size_t kMaxBaseChain = 8;

YAML::Node load_yaml(const std::string& yaml_text) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    throw std::invalid_argument(std::string("malformed YAML: ") + error.what());
  }
  if (!root.IsNull() && !root.IsMap()) {
    throw std::invalid_argument("config: expected a mapping at the top level");
  }
  return root;
}

void apply_yaml(const YAML::Node& root, TrainingConfig& config) {
  OptionTable table;
  config.declare_options(table);
  walk(root, "", config, table);
}

/// Reads the file at `path` (as written, for messages; `chain.back()` is its canonical form)
/// into `config`: its base first (a path relative to the file's directory), then its own keys
/// over the base's. `chain` holds the files being read, to refuse a cycle by name.
void read_config_file(const std::filesystem::path& path, std::vector<std::filesystem::path>& chain,
                      TrainingConfig& config) {
  const std::string text =
      read_input_file<std::invalid_argument>(path.string(), "config file", kMaxConfigFileBytes);
  try {
    YAML::Node root = load_yaml(text);
    if (root.IsNull()) return;
    if (const YAML::Node base = root[kBaseKey]; base) {
      if (!base.IsScalar() || base.Scalar().empty()) {
        bad_value(kBaseKey, base.IsScalar() ? "" : "not a file name", "a config file's path");
      }
      const std::filesystem::path base_path = path.parent_path() / base.Scalar();
      const std::filesystem::path canonical = std::filesystem::weakly_canonical(base_path);
      if (std::find(chain.begin(), chain.end(), canonical) != chain.end()) {
        throw std::invalid_argument(config_key(kBaseKey) + ": '" + base.Scalar() +
                                    "' extends this file again (a cycle of bases)");
      }
      if (chain.size() >= kMaxBaseChain) {
        throw std::invalid_argument(config_key(kBaseKey) + ": more than " +
                                    std::to_string(kMaxBaseChain) + " files in the chain of bases");
      }
      chain.push_back(canonical);
      read_config_file(base_path, chain, config);
      chain.pop_back();
      root.remove(kBaseKey);
    }
    apply_yaml(root, config);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(path.string() + ": " + error.what());
  }
}

}  // namespace

TrainingConfig parse_training_config(const std::string& yaml_text) {
  const YAML::Node root = load_yaml(yaml_text);
  TrainingConfig config;
  if (root.IsNull()) return config;
  if (root[kBaseKey]) {
    throw std::invalid_argument(config_key(kBaseKey) +
                                ": a base is a path relative to a config file, so only a config "
                                "file may name one (upkie-rl train --config FILE)");
  }
  apply_yaml(root, config);
  return config;
}

TrainingConfig load_training_config(const std::string& path) {
  TrainingConfig config;
  try {
    std::vector<std::filesystem::path> chain = {std::filesystem::weakly_canonical(path)};
    read_config_file(path, chain, config);
  } catch (const std::filesystem::filesystem_error& error) {
    throw std::invalid_argument(path + ": " + error.what());
  }
  return config;
}

void apply_overrides(TrainingConfig& config, const std::vector<std::string>& overrides) {
  OptionTable table;
  config.declare_options(table);
  for (const std::string& item : overrides) {
    const auto equal = item.find('=');
    if (equal == std::string::npos || equal == 0) {
      throw std::invalid_argument("override '" + item + "': expected key=value");
    }
    set_key(config, table, std::string(trim(item.substr(0, equal))), item.substr(equal + 1));
  }
}

double TrainingConfig::randomization_scale(std::int64_t timesteps) const {
  if (curriculum_steps <= 0) return 1.0;
  return std::clamp(static_cast<double>(timesteps) / static_cast<double>(curriculum_steps), 0.0,
                    1.0);
}

std::string to_yaml(const TrainingConfig& const_config) {
  TrainingConfig config = const_config;  // the option table binds mutable fields
  OptionTable table;
  config.declare_options(table);
  std::string out;
  std::string section;
  for (const OptionInfo& option : table.info()) {
    const auto dot = option.name.find('.');
    const std::string option_section = dot == std::string::npos ? "" : option.name.substr(0, dot);
    const std::string name = dot == std::string::npos ? option.name : option.name.substr(dot + 1);
    if (option_section != section) {
      if (section == "env") out += env_options_yaml(config.env_options);
      section = option_section;
      if (!section.empty()) out += section + ":\n";
    }
    std::string value = table.value_text(option.name);
    if (option.type == OptionInfo::Type::kText) value = yaml_scalar(value, option.name);
    // Keep a real a YAML float ("1" would read back fine, but "1.0" says what it is).
    if (option.type == OptionInfo::Type::kReal &&
        value.find_first_of(".einn") == std::string::npos) {
      value += ".0";
    }
    out += (section.empty() ? "" : "  ") + name + ": " + value + "\n";
  }
  return out;
}

}  // namespace upkie_rl
