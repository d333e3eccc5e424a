/// @file
/// libFuzzer target: the training configuration's parser and its `--set` overrides. Each
/// input is read as a YAML file, validated and printed back; its lines are also applied as
/// `--set key=value` overrides to the default configuration. Refusing an input with
/// std::invalid_argument is the expected outcome; a crash, a hang, a sanitizer report or
/// another exception is a bug. Whatever passes validate() must print to YAML that reads
/// back to the same text.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rl/runs/training_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    upkie_rl::TrainingConfig config = upkie_rl::parse_training_config(text);
    config.validate();
    const std::string yaml = upkie_rl::to_yaml(config);
    if (upkie_rl::to_yaml(upkie_rl::parse_training_config(yaml)) != yaml) std::abort();
  } catch (const std::invalid_argument&) {
  }
  std::vector<std::string> overrides;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) overrides.push_back(line);
  try {
    upkie_rl::TrainingConfig config;
    upkie_rl::apply_overrides(config, overrides);
    config.validate();
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
