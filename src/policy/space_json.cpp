#include "policy/space_json.hpp"

#include <cmath>

#include "policy/checkpoint_file.hpp"

namespace upkie_rl {

namespace {

nlohmann::json bound_to_json(float value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return value;
}

float bound_from_json(const nlohmann::json& json) {
  if (json.is_string()) {
    if (json == "inf") return INFINITY;
    if (json == "-inf") return -INFINITY;
    throw CheckpointError("malformed space bound " + json.dump());
  }
  return json.get<float>();
}

}  // namespace

nlohmann::json space_to_json(const BoxSpace& space) {
  nlohmann::json low = nlohmann::json::array();
  nlohmann::json high = nlohmann::json::array();
  for (std::size_t i = 0; i < space.size(); ++i) {
    low.push_back(bound_to_json(space.low[i]));
    high.push_back(bound_to_json(space.high[i]));
  }
  return {{"low", low}, {"high", high}, {"names", space.names}};
}

BoxSpace space_from_json(const nlohmann::json& json) {
  try {
    BoxSpace space;
    for (const auto& value : json.at("low")) space.low.push_back(bound_from_json(value));
    for (const auto& value : json.at("high")) space.high.push_back(bound_from_json(value));
    space.names = json.at("names").get<std::vector<std::string>>();
    if (space.high.size() != space.low.size() ||
        (!space.names.empty() && space.names.size() != space.low.size())) {
      throw CheckpointError("space bounds and names differ in size");
    }
    return space;
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(std::string("malformed space: ") + error.what());
  }
}

void check_same_space(const BoxSpace& expected, const BoxSpace& actual, const std::string& what) {
  if (expected.size() != actual.size()) {
    throw CheckpointError("the model's " + what + " has " + std::to_string(expected.size()) +
                          " components, the environment's has " + std::to_string(actual.size()));
  }
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const std::string name = i < expected.names.size() ? expected.names[i] : std::to_string(i);
    if (i < expected.names.size() && i < actual.names.size() &&
        expected.names[i] != actual.names[i]) {
      throw CheckpointError("the model's " + what + " component " + std::to_string(i) + " is '" +
                            expected.names[i] + "', the environment's is '" + actual.names[i] +
                            "'");
    }
    if (expected.low[i] != actual.low[i] || expected.high[i] != actual.high[i]) {
      throw CheckpointError("the model's " + what + " component '" + name + "' has bounds [" +
                            std::to_string(expected.low[i]) + ", " +
                            std::to_string(expected.high[i]) + "], the environment's [" +
                            std::to_string(actual.low[i]) + ", " + std::to_string(actual.high[i]) +
                            "]");
    }
  }
}

}  // namespace upkie_rl
