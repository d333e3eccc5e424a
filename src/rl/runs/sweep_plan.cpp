#include "rl/runs/sweep_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <set>
#include <sstream>
#include <stdexcept>

#include "base/atomic_file.hpp"
#include "base/input_file.hpp"
#include "base/integer_text.hpp"
#include "rl/runs/config_file_limit.hpp"
#include "rl/runs/run_file_error.hpp"

namespace upkie_rl {

namespace {

constexpr const char* kPlanFile = "sweep.yaml";
constexpr const char* kConfigFile = "config.yaml";

std::uint64_t parse_seed(const std::string& text, const std::string& whole) {
  const std::optional<std::uint64_t> value = integer_from_text<std::uint64_t>(text);
  if (!value) {
    throw std::invalid_argument("seeds '" + whole +
                                "': expected A:B (seeds A to B-1), A,B,C or A, with "
                                "non-negative integers");
  }
  return *value;
}

/// Splits at the commas that are outside brackets.
std::vector<std::string> split_values(const std::string& text) {
  std::vector<std::string> values;
  std::string current;
  int depth = 0;
  for (char c : text) {
    if (c == '[') ++depth;
    if (c == ']') --depth;
    if (c == ',' && depth == 0) {
      values.push_back(current);
      current.clear();
    } else {
      current += c;
    }
  }
  values.push_back(current);
  return values;
}

/// The last component of a dotted key: names are short where they stay unambiguous.
std::string short_key(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

/// Characters a directory name keeps; others become '_'.
std::string file_safe(const std::string& text) {
  std::string out = text;
  for (char& c : out) {
    const bool kept = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' ||
                      c == '=' || c == '+';
    if (!kept) c = '_';
  }
  return out;
}

std::string read_text(const std::filesystem::path& path) {
  std::error_code missing;
  if (!std::filesystem::exists(path, missing)) {
    throw std::invalid_argument(path.string() + ": cannot read (is it a sweep directory?)");
  }
  return read_input_file<std::invalid_argument>(path, "sweep file", kMaxConfigFileBytes);
}

/// Writes `text` to `path` through a temporary file, so that a reader never sees half.
void write_text(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically<std::runtime_error>(path, text);
}

// sweep.yaml: the writer and the reader of its keys, side by side.

std::string plan_yaml(const SweepPlan& plan) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "evaluation_episodes" << YAML::Value << plan.evaluation_episodes;
  out << YAML::Key << "evaluation_seed" << YAML::Value << plan.evaluation_seed;
  out << YAML::Key << "evaluation_max_steps" << YAML::Value << plan.evaluation_max_steps;
  out << YAML::Key << "axes" << YAML::Value << YAML::BeginSeq;
  for (const SweepAxis& axis : plan.axes) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "key" << YAML::Value << axis.key
        << YAML::Key << "values" << YAML::Value << YAML::Flow << axis.values << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "seeds" << YAML::Value << YAML::Flow << plan.seeds;
  out << YAML::Key << "runs" << YAML::Value << YAML::BeginSeq;
  for (const SweepRun& run : plan.runs) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << run.name
        << YAML::Key << "seed" << YAML::Value << run.seed << YAML::Key << "set" << YAML::Value
        << YAML::Flow << run.overrides << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(
             "# A sweep of upkie-rl: run entry I (from 0) with `upkie-rl sweep DIR --run I`,\n"
             "# all of them with `upkie-rl sweep DIR`; config.yaml is the base configuration.\n") +
         out.c_str() + "\n";
}

template <typename T>
T plan_value(const YAML::Node& node, const std::string& key) {
  if (!node[key]) throw std::invalid_argument("missing key '" + key + "'");
  try {
    return node[key].as<T>();
  } catch (const YAML::Exception&) {
    throw std::invalid_argument("key '" + key + "' has a malformed value");
  }
}

SweepPlan parse_plan(const std::string& text) {
  const YAML::Node root = YAML::Load(text);
  if (!root.IsMap()) throw std::invalid_argument("expected a map of keys");
  SweepPlan plan;
  plan.evaluation_episodes = plan_value<int>(root, "evaluation_episodes");
  plan.evaluation_seed = plan_value<std::uint64_t>(root, "evaluation_seed");
  plan.evaluation_max_steps = plan_value<int>(root, "evaluation_max_steps");
  plan.seeds = plan_value<std::vector<std::uint64_t>>(root, "seeds");
  for (const YAML::Node& axis : plan_value<std::vector<YAML::Node>>(root, "axes")) {
    plan.axes.push_back({plan_value<std::string>(axis, "key"),
                         plan_value<std::vector<std::string>>(axis, "values")});
  }
  for (const YAML::Node& run : plan_value<std::vector<YAML::Node>>(root, "runs")) {
    plan.runs.push_back({plan_value<std::string>(run, "name"),
                         plan_value<std::uint64_t>(run, "seed"),
                         plan_value<std::vector<std::string>>(run, "set")});
  }
  if (plan.evaluation_episodes < 1) {
    throw std::invalid_argument("key 'evaluation_episodes' must be at least 1");
  }
  if (plan.evaluation_max_steps < 1) {
    throw std::invalid_argument("key 'evaluation_max_steps' must be at least 1");
  }
  return plan;
}

}  // namespace

std::vector<std::uint64_t> parse_seed_list(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  const auto colon = text.find(':');
  if (colon != std::string::npos) {
    const std::uint64_t first = parse_seed(text.substr(0, colon), text);
    const std::uint64_t end = parse_seed(text.substr(colon + 1), text);
    if (end <= first) {
      throw std::invalid_argument("seeds '" + text + "': A:B needs B > A (seeds A to B-1)");
    }
    if (end - first > 100'000) throw std::invalid_argument("seeds '" + text + "': too many seeds");
    for (std::uint64_t seed = first; seed < end; ++seed) seeds.push_back(seed);
    return seeds;
  }
  std::stringstream items(text);
  for (std::string item; std::getline(items, item, ',');) seeds.push_back(parse_seed(item, text));
  if (seeds.empty()) parse_seed("", text);  // throws
  const std::set<std::uint64_t> unique(seeds.begin(), seeds.end());
  if (unique.size() != seeds.size()) {
    throw std::invalid_argument("seeds '" + text + "': a seed is listed twice");
  }
  return seeds;
}

SweepAxis parse_sweep_axis(const std::string& text) {
  const auto equal = text.find('=');
  if (equal == std::string::npos || equal == 0) {
    throw std::invalid_argument("--set '" + text + "': expected key=value1,value2,...");
  }
  SweepAxis axis{text.substr(0, equal), split_values(text.substr(equal + 1))};
  for (const std::string& value : axis.values) {
    if (value.empty()) throw std::invalid_argument("--set '" + text + "': an empty value");
  }
  const std::set<std::string> unique(axis.values.begin(), axis.values.end());
  if (unique.size() != axis.values.size()) {
    throw std::invalid_argument("--set '" + text + "': a value is listed twice");
  }
  return axis;
}

TrainingConfig sweep_run_config(const TrainingConfig& base, const SweepRun& run) {
  TrainingConfig config = base;
  apply_overrides(config, run.overrides);
  config.seed = run.seed;
  return config;
}

std::string sweep_group_label(const SweepRun& run) {
  if (run.overrides.empty()) return "base";
  std::string label;
  for (const std::string& item : run.overrides) label += (label.empty() ? "" : " ") + item;
  return label;
}

namespace {

// Refuses a seed axis and a key given twice; returns the short keys that several axes
// share (their runs are named with the full key).
std::set<std::string> checked_axes(const std::vector<SweepAxis>& axes) {
  std::set<std::string> keys, short_keys_seen, short_keys_repeated;
  for (const SweepAxis& axis : axes) {
    if (axis.key == "seed") throw std::invalid_argument("sweep seeds with --seeds, not --set seed");
    if (!keys.insert(axis.key).second) {
      throw std::invalid_argument("--set " + axis.key + " is given twice: list its values once");
    }
    if (!short_keys_seen.insert(short_key(axis.key)).second)
      short_keys_repeated.insert(short_key(axis.key));
  }
  return short_keys_repeated;
}

}  // namespace

SweepPlan make_sweep_plan(const TrainingConfig& base, std::vector<std::uint64_t> seeds,
                          std::vector<SweepAxis> axes, int evaluation_episodes) {
  if (seeds.empty()) throw std::invalid_argument("a sweep needs at least one seed");
  if (evaluation_episodes < 1) {
    throw std::invalid_argument("a sweep evaluates each run on at least one episode");
  }
  const std::set<std::string> short_keys_repeated = checked_axes(axes);
  SweepPlan plan;
  plan.evaluation_episodes = evaluation_episodes;
  plan.seeds = std::move(seeds);
  plan.axes = std::move(axes);
  std::size_t combinations = 1;
  for (const SweepAxis& axis : plan.axes) combinations *= axis.values.size();
  if (combinations * plan.seeds.size() > kMaxSweepRuns) {
    throw std::invalid_argument("a sweep of " + std::to_string(combinations * plan.seeds.size()) +
                                " runs: at most " + std::to_string(kMaxSweepRuns));
  }
  for (std::size_t combination = 0; combination < combinations; ++combination) {
    std::vector<std::string> overrides;
    std::string name;
    std::size_t rest = combination;
    // Mixed radix with the last axis fastest: index digits from the last axis.
    std::vector<std::size_t> digits(plan.axes.size());
    for (std::size_t a = plan.axes.size(); a-- > 0;) {
      digits[a] = rest % plan.axes[a].values.size();
      rest /= plan.axes[a].values.size();
    }
    for (std::size_t a = 0; a < plan.axes.size(); ++a) {
      const SweepAxis& axis = plan.axes[a];
      const std::string& value = axis.values[digits[a]];
      overrides.push_back(axis.key + "=" + value);
      const std::string key_name =
          short_keys_repeated.count(short_key(axis.key)) > 0 ? axis.key : short_key(axis.key);
      name += file_safe(key_name + "=" + value) + "_";
    }
    for (std::uint64_t seed : plan.seeds) {
      SweepRun run{name + "seed" + std::to_string(seed), seed, overrides};
      try {
        sweep_run_config(base, run).validate();
      } catch (const std::invalid_argument& error) {
        throw std::invalid_argument("sweep run " + run.name + ": " + error.what());
      }
      plan.runs.push_back(std::move(run));
    }
  }
  std::set<std::string> names;
  for (const SweepRun& run : plan.runs) {
    if (!names.insert(run.name).second) {
      throw std::invalid_argument("two runs of the sweep would share the directory " + run.name +
                                  " (values that differ only in characters a file name cannot "
                                  "hold)");
    }
  }
  return plan;
}

void write_sweep(const std::filesystem::path& directory, const TrainingConfig& base,
                 const SweepPlan& plan) {
  const std::string plan_text = plan_yaml(plan);
  const std::string config_text = to_yaml(base);
  const std::filesystem::path plan_path = directory / kPlanFile;
  if (std::filesystem::exists(plan_path)) {
    if (read_text(plan_path) != plan_text || read_text(directory / kConfigFile) != config_text) {
      throw RunFileError(directory.string() +
                         " already holds another sweep: choose another --output, or run "
                         "`upkie-rl sweep " +
                         directory.string() + "` to continue that one");
    }
    return;
  }
  std::filesystem::create_directories(directory);
  write_text(directory / kConfigFile, config_text);
  write_text(plan_path, plan_text);  // last: a directory with a plan is a whole sweep
}

Sweep load_sweep(const std::filesystem::path& directory) {
  Sweep sweep;
  sweep.directory = directory;
  const std::filesystem::path plan_path = directory / kPlanFile;
  const std::string plan_text = read_text(plan_path);  // its message names the file already
  try {
    sweep.plan = parse_plan(plan_text);
  } catch (const YAML::Exception& error) {
    throw std::invalid_argument(plan_path.string() + ": " + error.what());
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    if (message.rfind(plan_path.string(), 0) == 0) throw;
    throw std::invalid_argument(plan_path.string() + ": " + message);
  }
  sweep.base = load_training_config((directory / kConfigFile).string());
  for (const SweepRun& run : sweep.plan.runs) {
    try {
      sweep_run_config(sweep.base, run).validate();
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(plan_path.string() + ": run " + run.name + ": " + error.what());
    }
  }
  return sweep;
}

}  // namespace upkie_rl
