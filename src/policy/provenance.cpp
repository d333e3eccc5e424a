#include "policy/provenance.hpp"

#include <yaml-cpp/yaml.h>

#include <ctime>
#include <iterator>
#include <sstream>

#include "policy/build_info.hpp"
#include "policy/checkpoint_file.hpp"
#include "policy/checkpoint_header.hpp"
#include "policy/model_header.hpp"

namespace upkie_rl {

namespace {

namespace key = provenance_key;

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

// The entries read from the rest of the header, each "unknown" when it cannot be read.
void complete_from_header(const nlohmann::json& header, nlohmann::json& provenance) {
  try {
    const std::string config = checkpoint_config_yaml(header);
    provenance[key::kConfig] = config;
    provenance[key::kEnvId] = checkpoint_env_id(header);
    nlohmann::json options = nlohmann::json::object();
    for (const auto& [name, value] : checkpoint_env_options(header)) options[name] = value;
    provenance[key::kEnvOptions] = options;
    // The training configuration's seed key (rl/runs/training_config.cpp), which policy_core
    // cannot include: the provenance's key has the same name.
    const YAML::Node seed = YAML::Load(config)[key::kSeed];
    if (seed && seed.IsScalar()) provenance[key::kSeed] = seed.as<std::string>();
  } catch (const CheckpointError&) {
    // A header without (readable) configuration: those fields stay unknown.
  } catch (const YAML::Exception&) {
  }
  const auto counters = header.find(checkpoint_header::kCounters);
  if (counters != header.end() && counters->is_object()) {
    const auto timesteps = counters->find(checkpoint_header::kNumTimesteps);
    if (timesteps != counters->end() && timesteps->is_number_integer()) {
      provenance[key::kTimesteps] = timesteps->get<std::int64_t>();
    }
  }
}

}  // namespace

nlohmann::json new_provenance(const std::string& source) {
  return {{key::kUpkieRlVersion, upkie_rl_version()},
          {key::kGitCommit, upkie_rl_git_commit()},
          {key::kDate, utc_now()},
          {key::kSource, source}};
}

nlohmann::json model_provenance(const nlohmann::json& header) {
  nlohmann::json provenance = nlohmann::json::object();
  const auto stored = header.find(checkpoint_header::kProvenance);
  if (stored != header.end() && stored->is_object()) provenance = *stored;
  // What the stored entry says wins (an import records the original's seed and steps).
  nlohmann::json from_header = nlohmann::json::object();
  complete_from_header(header, from_header);
  for (const auto& [name, value] : from_header.items()) {
    if (!provenance.contains(name)) provenance[name] = value;
  }
  for (std::size_t i = 0; i < std::size(key::kAllKeys); ++i) {
    const char* name = key::kAllKeys[i].text;
    if (key::kAlways[i] && !provenance.contains(name)) provenance[name] = kUnknownProvenance;
  }
  return provenance;
}

std::string format_provenance(const nlohmann::json& provenance) {
  std::ostringstream out;
  std::string config;
  for (const auto& [name, value] : provenance.items()) {
    if (name == key::kConfig) {
      config = value.is_string() ? value.get<std::string>() : value.dump();
      continue;
    }
    out << name << ": " << (value.is_string() ? value.get<std::string>() : value.dump()) << "\n";
  }
  if (!config.empty()) {
    out << key::kConfig << ":";
    if (config == kUnknownProvenance) {
      out << " " << config << "\n";
    } else {
      out << "\n";
      std::istringstream lines(config);
      for (std::string line; std::getline(lines, line);) out << "  " << line << "\n";
    }
  }
  return out.str();
}

}  // namespace upkie_rl
