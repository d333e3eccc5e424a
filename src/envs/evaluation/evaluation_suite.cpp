#include "envs/evaluation/evaluation_suite.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include "base/input_file.hpp"

namespace upkie_rl {
namespace {

// The keys of a suite file and of one of its worlds, declared once: the readers below
// take them from here, and an unknown key is an error listing these.
namespace key {
constexpr const char* kName = "name";
constexpr const char* kDescription = "description";
constexpr const char* kEnvs = "envs";
constexpr const char* kEpisodes = "episodes";
constexpr const char* kSeed = "seed";
constexpr const char* kMaxSteps = "max_steps";
constexpr const char* kDuration = "duration";
constexpr const char* kEarlyFallTime = "early_fall_time";
constexpr const char* kOptions = "options";
constexpr const char* kWorlds = "worlds";
}  // namespace key

const std::set<std::string> kSuiteKeys = {
    key::kName,     key::kDescription, key::kEnvs,          key::kEpisodes, key::kSeed,
    key::kMaxSteps, key::kDuration,    key::kEarlyFallTime, key::kOptions,  key::kWorlds};
const std::set<std::string> kWorldKeys = {key::kName, key::kOptions};

std::string listed(const std::set<std::string>& keys) {
  std::string text;
  for (const std::string& name : keys) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// Throws unless every key of the map `node` is one of `allowed`.
void check_keys(const YAML::Node& node, const std::set<std::string>& allowed,
                const std::string& where) {
  if (!node.IsMap()) throw std::invalid_argument(where + ": expected a map of keys");
  for (const auto& entry : node) {
    const std::string name = entry.first.as<std::string>();
    if (allowed.count(name) == 0) {
      throw std::invalid_argument(where + ": unknown key \"" + name +
                                  "\" (keys: " + listed(allowed) + ")");
    }
  }
}

/// A scalar as `T` within [min, max], or the default when the key is absent.
template <class T>
T read_number(const YAML::Node& parent, const char* name, T fallback, T min, T max,
              const std::string& where) {
  const YAML::Node node = parent[name];
  if (!node) return fallback;
  T value{};
  try {
    value = node.as<T>();
  } catch (const YAML::Exception&) {
    throw std::invalid_argument(where + ": " + name + " is not a number: " +
                                (node.IsScalar() ? node.Scalar() : std::string("a collection")));
  }
  if (!(value >= min && value <= max)) {  // NaN fails too
    throw std::invalid_argument(where + ": " + name + " must be in [" + std::to_string(min) + ", " +
                                std::to_string(max) + "], got " + node.Scalar());
  }
  return value;
}

/// The key=value options of a map of scalars, in file order.
EnvOptions read_options(const YAML::Node& parent, const std::string& where) {
  EnvOptions options;
  const YAML::Node node = parent[key::kOptions];
  if (!node || node.IsNull()) return options;
  if (!node.IsMap()) throw std::invalid_argument(where + ": options must be a map of key: value");
  for (const auto& entry : node) {
    const std::string name = entry.first.as<std::string>();
    if (!entry.second.IsScalar()) {
      throw std::invalid_argument(where + ": option " + name + " must be a single value");
    }
    options.emplace_back(name, entry.second.Scalar());
  }
  return options;
}

std::vector<std::string> read_env_ids(const YAML::Node& root, const std::string& where) {
  const YAML::Node node = root[key::kEnvs];
  std::vector<std::string> ids;
  if (node && node.IsSequence()) {
    for (const auto& id : node) {
      if (id.IsScalar() && !id.Scalar().empty()) ids.push_back(id.Scalar());
    }
  }
  if (ids.empty() || ids.size() != (node ? node.size() : 0)) {
    throw std::invalid_argument(where + ": envs must be a list of environment ids");
  }
  return ids;
}

/// The worlds of the file, each on each env, the suite's options first.
void read_worlds(const YAML::Node& root, const std::string& where, EvaluationSuite& suite) {
  const YAML::Node worlds = root[key::kWorlds];
  if (!worlds || !worlds.IsSequence() || worlds.size() == 0) {
    throw std::invalid_argument(where + ": worlds must be a non-empty list");
  }
  const EnvOptions common = read_options(root, where);
  std::set<std::string> names;
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    const std::string world_where = where + ", world " + std::to_string(i + 1);
    check_keys(worlds[i], kWorldKeys, world_where);
    const YAML::Node name = worlds[i][key::kName];
    if (!name || !name.IsScalar() || name.Scalar().empty()) {
      throw std::invalid_argument(world_where + ": a world needs a name");
    }
    const std::string named_where = where + ", world \"" + name.Scalar() + "\"";
    if (!names.insert(name.Scalar()).second) {
      throw std::invalid_argument(named_where + ": another world has this name");
    }
    EnvOptions options = common;
    const EnvOptions own = read_options(worlds[i], named_where);
    options.insert(options.end(), own.begin(), own.end());
    for (const std::string& env_id : suite.env_ids) {
      suite.worlds.push_back({name.Scalar(), env_id, options, common.size()});
    }
  }
  if (suite.worlds.size() > kMaxSuiteWorlds) {
    throw std::invalid_argument(where + ": " + std::to_string(suite.worlds.size()) +
                                " worlds x envs, more than the limit of " +
                                std::to_string(kMaxSuiteWorlds));
  }
}

EvaluationSuite read_suite_node(const YAML::Node& root, const std::string& where) {
  check_keys(root, kSuiteKeys, where);
  EvaluationSuite suite;
  const YAML::Node name = root[key::kName];
  suite.name = name && name.IsScalar() ? name.Scalar() : "";
  if (suite.name.empty()) throw std::invalid_argument(where + ": the suite needs a name");
  const YAML::Node description = root[key::kDescription];
  if (description && description.IsScalar()) suite.description = description.Scalar();
  suite.env_ids = read_env_ids(root, where);
  suite.episodes = read_number(root, key::kEpisodes, suite.episodes, 1, 100'000, where);
  suite.seed = read_number<std::uint64_t>(root, key::kSeed, suite.seed, 0,
                                          std::numeric_limits<std::uint64_t>::max(), where);
  suite.max_steps = read_number(root, key::kMaxSteps, suite.max_steps, 1, 10'000'000, where);
  suite.duration = read_number(root, key::kDuration, suite.duration, 1e-3, 3600.0, where);
  if (root[key::kDuration] && root[key::kMaxSteps]) {
    throw std::invalid_argument(where + ": give " + key::kDuration + " [s] or " + key::kMaxSteps +
                                " [agent steps], not both");
  }
  suite.early_fall_time =
      read_number(root, key::kEarlyFallTime, suite.early_fall_time, 0.0, 1e6, where);
  read_worlds(root, where, suite);
  return suite;
}

}  // namespace

std::filesystem::path find_suite_file(const std::string& name_or_path,
                                      const std::filesystem::path& source_dir) {
  if (name_or_path.empty()) throw std::invalid_argument("--suite: empty name");
  std::vector<std::filesystem::path> candidates = {name_or_path};
  if (name_or_path.find('/') == std::string::npos) {
    const std::filesystem::path relative =
        std::filesystem::path("configs") / "suites" / (name_or_path + ".yaml");
    candidates.push_back(relative);
    candidates.push_back(source_dir / relative);
  }
  std::string tried;
  for (const std::filesystem::path& candidate : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error)) return candidate;
    tried += (tried.empty() ? "" : ", ") + candidate.string();
  }
  throw std::invalid_argument("suite " + name_or_path + " not found (looked for " + tried + ")");
}

EvaluationSuite parse_evaluation_suite(const std::string& text, const std::string& where,
                                       const SuiteWorldCheck& check) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw std::invalid_argument(where + ": not YAML: " + error.what());
  }
  EvaluationSuite suite;
  try {
    suite = read_suite_node(root, where);
  } catch (const YAML::Exception& error) {  // a key that is not text, say
    throw std::invalid_argument(where + ": " + error.what());
  }
  for (const SuiteWorld& world : suite.worlds) {
    try {
      check(world);
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(where + ", world \"" + world.name + "\" on " + world.env_id +
                                  ": " + error.what());
    }
  }
  return suite;
}

EvaluationSuite read_evaluation_suite(const std::filesystem::path& path,
                                      const SuiteWorldCheck& check) {
  const std::string text =
      read_input_file<std::invalid_argument>(path, "suite file", kMaxSuiteFileBytes);
  return parse_evaluation_suite(text, "suite " + path.string(), check);
}

}  // namespace upkie_rl
