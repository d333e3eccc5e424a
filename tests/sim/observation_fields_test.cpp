#include "sim/observation_fields.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/distinct_observation.hpp"
#include "sim/observation_dict.hpp"
#include "sim/servo_command.hpp"
#include "sim/servo_command_fields.hpp"

namespace upkie_rl {
namespace {

std::set<std::string> json_leaves(const nlohmann::json& tree, const std::string& prefix = "") {
  std::set<std::string> leaves;
  for (const auto& [key, value] : tree.items()) {
    if (value.is_object()) {
      leaves.merge(json_leaves(value, prefix + key + "."));
    } else {
      leaves.insert(prefix + key);
    }
  }
  return leaves;
}

std::set<std::string> declared_leaves() {
  std::set<std::string> leaves;
  for (const ObservationKey& key : observation_keys()) {
    if (!key.is_map) leaves.insert(key.path);
  }
  return leaves;
}

TEST(ObservationFields, EveryMapDeclaresItsKeysOnceInByteOrder) {
  std::map<std::string, std::vector<std::string>> keys_of_map;
  for (const ObservationKey& key : observation_keys()) {
    const std::size_t dot = key.path.rfind('.');
    const std::string map = dot == std::string::npos ? "" : key.path.substr(0, dot);
    keys_of_map[map].push_back(key.path.substr(dot == std::string::npos ? 0 : dot + 1));
  }
  ASSERT_GT(keys_of_map.size(), 10u);
  for (const auto& [map, keys] : keys_of_map) {
    ASSERT_FALSE(keys.empty());
    // Strictly increasing: sorted (the spine's msgpack order) and no key twice.
    for (std::size_t i = 1; i < keys.size(); ++i) EXPECT_LT(keys[i - 1], keys[i]);
  }
}

TEST(ObservationFields, TheDictionaryHasExactlyTheDeclaredKeys) {
  Observation observation;
  testing::DistinctValueFiller filler;
  visit_observation_fields(observation, filler);
  ASSERT_TRUE(observation.has_sim);
  const std::set<std::string> declared = declared_leaves();
  EXPECT_EQ(json_leaves(observation_to_json(observation)), declared);
  EXPECT_TRUE(declared.count("base_orientation.rotation_base_to_world"));
  EXPECT_TRUE(declared.count("servo.right_wheel.voltage"));

  observation.has_sim = false;
  std::set<std::string> without_sim;
  for (const std::string& path : declared) {
    if (path.rfind("sim.", 0) != 0) without_sim.insert(path);
  }
  EXPECT_EQ(json_leaves(observation_to_json(observation)), without_sim);
}

TEST(ObservationFields, ServoMeasurementsComeFromTheServoTable) {
  const std::set<std::string> declared = declared_leaves();
  for (const ServoObservationField& field : kServoObservationFields) {
    for (const auto& joint : kServoNames) {
      EXPECT_TRUE(declared.count("servo." + std::string(joint) + "." + std::string(field.key)))
          << field.key;
    }
  }
}

TEST(ServoCommandFields, TheSortedTableIsThePermutationInByteOrder) {
  for (std::size_t i = 1; i < kServoCommandFieldsByKey.size(); ++i) {
    EXPECT_LT(kServoCommandFieldsByKey[i - 1].key, kServoCommandFieldsByKey[i].key);
  }
  for (const ServoCommandField& field : kServoCommandFields) {
    EXPECT_EQ(std::count_if(kServoCommandFieldsByKey.begin(), kServoCommandFieldsByKey.end(),
                            [&](const ServoCommandField& sorted) {
                              return sorted.key == field.key && sorted.member == field.member;
                            }),
              1)
        << field.key;
  }
}

}  // namespace
}  // namespace upkie_rl
