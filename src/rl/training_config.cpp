#include "rl/training_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "model/integer_text.hpp"
#include "model/setting_bounds.hpp"
#include "policy/network_limits.hpp"
#include "rl/ppo_gradient.hpp"
#include "vec/make_vector_env.hpp"
#include "vec/vec_normalize.hpp"

namespace upkie_rl {

namespace {

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

[[noreturn]] void bad_value(const std::string& key, const std::string& value,
                            const std::string& expected) {
  throw std::invalid_argument("config key '" + key + "': expected " + expected + ", got '" + value +
                              "'");
}

template <typename T>
T parse_integer(const std::string& key, const std::string& raw) {
  const std::optional<T> value = integer_from_text<T>(raw);
  if (!value) bad_value(key, raw, "an integer");
  return *value;
}

double parse_double(const std::string& key, const std::string& raw) {
  const std::string text = trim(raw);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    bad_value(key, raw, "a number");
  }
  return value;
}

bool parse_bool(const std::string& key, const std::string& raw) {
  std::string text = trim(raw);
  std::transform(text.begin(), text.end(), text.begin(), ::tolower);
  if (text == "true" || text == "yes" || text == "on" || text == "1") return true;
  if (text == "false" || text == "no" || text == "off" || text == "0") return false;
  bad_value(key, raw, "true or false");
}

// The values of ppo.gradient, spelled once for parsing, writing and messages.
constexpr std::pair<GradientMethod, const char*> kGradientMethods[] = {
    {GradientMethod::kAuto, "auto"},
    {GradientMethod::kHand, "hand"},
    {GradientMethod::kAutograd, "autograd"},
};

GradientMethod parse_gradient_method(const std::string& key, const std::string& text) {
  std::string known;
  for (const auto& [method, name] : kGradientMethods) {
    if (text == name) return method;
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  bad_value(key, text, "one of " + known);
}

std::vector<std::int64_t> parse_sizes(const std::string& key, const std::string& raw) {
  std::string text = trim(raw);
  if (text.size() >= 2 && text.front() == '[' && text.back() == ']') {
    text = text.substr(1, text.size() - 2);
  }
  std::vector<std::int64_t> sizes;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (trim(item).empty()) continue;
    const auto size = parse_integer<std::int64_t>(key, item);
    if (size <= 0) bad_value(key, raw, "positive layer sizes");
    sizes.push_back(size);
  }
  return sizes;
}

std::string format_double(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text(buffer, result.ptr);
  // Keep it a YAML float (e.g. "1" would read back fine, but "1.0" says what it is).
  if (text.find_first_of(".einn") == std::string::npos) text += ".0";
  return text;
}

std::string format_sizes(const std::vector<std::int64_t>& sizes) {
  std::string text = "[";
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    text += (i ? ", " : "") + std::to_string(sizes[i]);
  }
  return text + "]";
}

// One scalar setting: its dotted key, how to set it from text and how to print it.
struct Field {
  std::string key;
  std::function<void(const std::string&)> set;
  std::function<std::string()> get;
};

std::vector<Field> fields(TrainingConfig& c) {
  std::vector<Field> out;
  auto integer = [&out](const std::string& key, std::int64_t& value) {
    out.push_back(
        {key,
         [&value, key](const std::string& text) { value = parse_integer<std::int64_t>(key, text); },
         [&value] { return std::to_string(value); }});
  };
  auto real = [&out](const std::string& key, double& value) {
    out.push_back({key, [&value, key](const std::string& text) { value = parse_double(key, text); },
                   [&value] { return format_double(value); }});
  };
  auto boolean = [&out](const std::string& key, bool& value) {
    out.push_back({key, [&value, key](const std::string& text) { value = parse_bool(key, text); },
                   [&value] { return std::string(value ? "true" : "false"); }});
  };
  auto sizes = [&out](const std::string& key, std::vector<std::int64_t>& value) {
    out.push_back({key, [&value, key](const std::string& text) { value = parse_sizes(key, text); },
                   [&value] { return format_sizes(value); }});
  };
  out.push_back({"env.id", [&c](const std::string& text) { c.env_id = trim(text); },
                 [&c] { return c.env_id; }});
  integer("env.num_envs", c.num_envs);
  integer("env.threads", c.env_threads);
  integer("env.curriculum_steps", c.curriculum_steps);
  boolean("normalize.observations", c.normalize.observations);
  boolean("normalize.rewards", c.normalize.rewards);
  real("normalize.clip_observations", c.normalize.clip_observations);
  real("normalize.clip_rewards", c.normalize.clip_rewards);
  real("normalize.gamma", c.normalize.gamma);
  real("normalize.epsilon", c.normalize.epsilon);
  sizes("policy.actor_hidden_sizes", c.policy.actor_hidden_sizes);
  sizes("policy.critic_hidden_sizes", c.policy.critic_hidden_sizes);
  out.push_back({"policy.activation",
                 [&c](const std::string& text) {
                   try {
                     c.policy.activation = parse_activation(trim(text));
                   } catch (const std::invalid_argument&) {
                     bad_value("policy.activation", text, activation_names());
                   }
                 },
                 [&c] { return std::string(activation_name(c.policy.activation)); }});
  real("policy.log_std_init", c.policy.log_std_init);
  integer("ppo.total_timesteps", c.ppo.total_timesteps);
  integer("ppo.n_steps", c.ppo.n_steps);
  integer("ppo.batch_size", c.ppo.batch_size);
  integer("ppo.n_epochs", c.ppo.n_epochs);
  real("ppo.gamma", c.ppo.gamma);
  real("ppo.gae_lambda", c.ppo.gae_lambda);
  real("ppo.clip_range", c.ppo.clip_range);
  real("ppo.clip_range_vf", c.ppo.clip_range_vf);
  real("ppo.ent_coef", c.ppo.ent_coef);
  real("ppo.vf_coef", c.ppo.vf_coef);
  real("ppo.max_grad_norm", c.ppo.max_grad_norm);
  real("ppo.learning_rate_initial", c.ppo.learning_rate_initial);
  real("ppo.learning_rate_final", c.ppo.learning_rate_final);
  real("ppo.adam_eps", c.ppo.adam_eps);
  boolean("ppo.normalize_advantage", c.ppo.normalize_advantage);
  out.push_back({"ppo.gradient",
                 [&c](const std::string& text) {
                   c.ppo.gradient = parse_gradient_method("ppo.gradient", trim(text));
                 },
                 [&c] { return std::string(gradient_method_name(c.ppo.gradient)); }});
  out.push_back(
      {"seed",
       [&c](const std::string& text) { c.seed = parse_integer<std::uint64_t>("seed", text); },
       [&c] { return std::to_string(c.seed); }});
  integer("checkpoint_every", c.checkpoint_every);
  integer("torch_threads", c.torch_threads);
  return out;
}

constexpr const char* kEnvOptionsPrefix = "env.options.";

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

void set_key(TrainingConfig& config, std::vector<Field>& table, const std::string& key,
             const std::string& value) {
  if (key.rfind(kEnvOptionsPrefix, 0) == 0) {
    set_env_option(config, key.substr(std::string(kEnvOptionsPrefix).size()), trim(value));
    return;
  }
  for (Field& field : table) {
    if (field.key == key) {
      field.set(value);
      return;
    }
  }
  throw std::invalid_argument("unknown config key '" + key + "'");
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

void walk(const YAML::Node& node, const std::string& prefix, TrainingConfig& config,
          std::vector<Field>& table) {
  for (const auto& item : node) {
    const std::string name = item.first.as<std::string>();
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    const YAML::Node& value = item.second;
    if (key == "env.options") {
      if (value.IsNull()) continue;
      if (!value.IsMap()) bad_value(key, "not a mapping", "a mapping of option names to values");
      for (const auto& option : value) {
        const std::string option_name = option.first.as<std::string>();
        set_env_option(config, option_name, node_text(option.second, key + "." + option_name));
      }
    } else if (value.IsMap()) {
      if (prefix.empty() && name != "env" && name != "normalize" && name != "policy" &&
          name != "ppo") {
        throw std::invalid_argument("unknown config section '" + key + "'");
      }
      walk(value, key, config, table);
    } else {
      set_key(config, table, key, node_text(value, key));
    }
  }
}

}  // namespace

const char* gradient_method_name(GradientMethod method) {
  for (const auto& [known, name] : kGradientMethods) {
    if (known == method) return name;
  }
  return "unknown";
}

bool uses_hand_gradient(const TrainingConfig& config) {
  return config.ppo.gradient == GradientMethod::kHand ||
         (config.ppo.gradient == GradientMethod::kAuto &&
          PpoGradient::covers(config.policy.activation));
}

std::int64_t TrainingConfig::steps_per_env() const {
  return std::max<std::int64_t>(1, ppo.n_steps / std::max<std::int64_t>(1, num_envs));
}

void TrainingConfig::validate() const {
  auto require = [](bool condition, const std::string& key, const std::string& what) {
    if (!condition) throw std::invalid_argument("config key '" + key + "': " + what);
  };
  auto integer = [](const std::string& key, std::int64_t value, std::int64_t min,
                    std::int64_t max) {
    check_setting("config key '" + key + "'", value, min, max);
  };
  auto real = [](const std::string& key, double value, double min, double max,
                 LowerBound lower = LowerBound::kIncluded) {
    check_setting("config key '" + key + "'", value, min, max, lower);
  };
  constexpr auto kExcluded = LowerBound::kExcluded;
  require(!env_id.empty(), "env.id", "must not be empty");
  integer("env.num_envs", num_envs, 1, static_cast<std::int64_t>(kMaxVectorEnvs));
  integer("env.threads", env_threads, 0, static_cast<std::int64_t>(kMaxEnvThreads));
  integer("env.curriculum_steps", curriculum_steps, 0, kMaxTimesteps);
  real("normalize.clip_observations", normalize.clip_observations, 0, kMaxNormalizationClip,
       kExcluded);
  real("normalize.clip_rewards", normalize.clip_rewards, 0, kMaxNormalizationClip, kExcluded);
  real("normalize.gamma", normalize.gamma, 0, 1, kExcluded);
  real("normalize.epsilon", normalize.epsilon, 0, 1, kExcluded);
  check_hidden_sizes("config key 'policy.actor_hidden_sizes'", policy.actor_hidden_sizes);
  check_hidden_sizes("config key 'policy.critic_hidden_sizes'", policy.critic_hidden_sizes);
  real("policy.log_std_init", policy.log_std_init, -20, 5);
  integer("ppo.total_timesteps", ppo.total_timesteps, 1, kMaxTimesteps);
  require(ppo.n_steps >= num_envs, "ppo.n_steps", "must be at least env.num_envs");
  integer("ppo.n_steps", ppo.n_steps, num_envs, kMaxRolloutSteps);
  require(ppo.batch_size >= 1, "ppo.batch_size", "must be at least 1");
  require(ppo.batch_size <= steps_per_env() * num_envs, "ppo.batch_size",
          "must not exceed the steps per update");
  integer("ppo.n_epochs", ppo.n_epochs, 1, 10'000);
  real("ppo.gamma", ppo.gamma, 0, 1, kExcluded);
  real("ppo.gae_lambda", ppo.gae_lambda, 0, 1);
  real("ppo.clip_range", ppo.clip_range, 0, 100, kExcluded);
  real("ppo.clip_range_vf", ppo.clip_range_vf, -kMaxClip, kMaxClip);
  real("ppo.ent_coef", ppo.ent_coef, -1000, 1000);
  real("ppo.vf_coef", ppo.vf_coef, 0, 1000);
  real("ppo.max_grad_norm", ppo.max_grad_norm, 0, kMaxClip, kExcluded);
  real("ppo.learning_rate_initial", ppo.learning_rate_initial, 0, 1, kExcluded);
  real("ppo.learning_rate_final", ppo.learning_rate_final, 0, 1);
  real("ppo.adam_eps", ppo.adam_eps, 0, 1, kExcluded);
  require(ppo.gradient != GradientMethod::kHand || PpoGradient::covers(policy.activation),
          "ppo.gradient",
          std::string("hand covers the relu and tanh activations, not ") +
              activation_name(policy.activation) + "; use autograd or auto");
  integer("checkpoint_every", checkpoint_every, 0, kMaxTimesteps);
  integer("torch_threads", torch_threads, 1, kMaxTorchThreads);
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

TrainingConfig parse_training_config(const std::string& yaml_text) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& error) {
    throw std::invalid_argument(std::string("malformed YAML: ") + error.what());
  }
  TrainingConfig config;
  if (root.IsNull()) return config;
  if (!root.IsMap()) throw std::invalid_argument("config: expected a mapping at the top level");
  std::vector<Field> table = fields(config);
  walk(root, "", config, table);
  return config;
}

TrainingConfig load_training_config(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("cannot read config file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  try {
    return parse_training_config(text.str());
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(path + ": " + error.what());
  }
}

void apply_overrides(TrainingConfig& config, const std::vector<std::string>& overrides) {
  std::vector<Field> table = fields(config);
  for (const std::string& item : overrides) {
    const auto equal = item.find('=');
    if (equal == std::string::npos || equal == 0) {
      throw std::invalid_argument("override '" + item + "': expected key=value");
    }
    set_key(config, table, trim(item.substr(0, equal)), item.substr(equal + 1));
  }
}

double TrainingConfig::randomization_scale(std::int64_t timesteps) const {
  if (curriculum_steps <= 0) return 1.0;
  return std::clamp(static_cast<double>(timesteps) / static_cast<double>(curriculum_steps), 0.0,
                    1.0);
}

std::string to_yaml(const TrainingConfig& const_config) {
  TrainingConfig config = const_config;  // the field table binds mutable references
  std::vector<Field> table = fields(config);
  std::string out;
  std::string section;
  for (const Field& field : table) {
    const auto dot = field.key.find('.');
    const std::string field_section = dot == std::string::npos ? "" : field.key.substr(0, dot);
    const std::string name = dot == std::string::npos ? field.key : field.key.substr(dot + 1);
    if (field_section != section) {
      if (section == "env") {
        out += "  options:" + std::string(config.env_options.empty() ? " {}" : "") + "\n";
        for (const auto& [key, value] : config.env_options) {
          out += "    " + key + ": " + YAML::Dump(YAML::Node(value)) + "\n";
        }
      }
      section = field_section;
      if (!section.empty()) out += section + ":\n";
    }
    const std::string value = field.get();
    out += (section.empty() ? "" : "  ") + name + ": " +
           (field.key == "env.id" ? YAML::Dump(YAML::Node(value)) : value) + "\n";
  }
  return out;
}

}  // namespace upkie_rl
