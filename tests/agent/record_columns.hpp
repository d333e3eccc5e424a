#pragma once
// Reading the record files of `rollout --record` and `upkie-rl-agent --record` in tests.

#include <cstddef>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/csv_fields.hpp"
#include "policy/deployed_policy.hpp"

namespace upkie_rl::testing {

/// A record file: its header's column names and its rows.
struct RecordTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  /// Index of `name` in the columns, or columns.size() when absent.
  std::size_t column(const std::string& name) const {
    std::size_t index = 0;
    while (index < columns.size() && columns[index] != name) ++index;
    return index;
  }
};

inline RecordTable read_record(const std::string& path) {
  RecordTable table;
  std::ifstream in(path);
  std::string line;
  if (std::getline(in, line)) table.columns = csv_fields(line);
  while (std::getline(in, line)) table.rows.push_back(csv_fields(line));
  return table;
}

/// Every recorded action is the checkpoint's DeployedPolicy (what `upkie-rl rollout --model`
/// and `upkie-rl-agent` act with) on the recorded observation, bit for bit: the record keeps 9
/// significant digits, so float values round-trip exactly. Returns the rows compared.
inline std::size_t expect_checkpoint_actions(const RecordTable& table, const std::string& model) {
  DeployedPolicy policy = DeployedPolicy::load(model);
  const std::size_t first_observation = table.column("t") + 1;
  const std::size_t first_action = table.column("action." + policy.action_space().names.at(0));
  EXPECT_LT(first_action, table.columns.size());
  std::vector<float> observation(policy.observation_space().size());
  std::vector<float> action(policy.action_space().size());
  std::size_t compared = 0;
  for (const auto& row : table.rows) {
    for (std::size_t i = 0; i < observation.size(); ++i) {
      observation[i] = std::stof(row.at(first_observation + i));
    }
    policy.act(observation, action);
    for (std::size_t i = 0; i < action.size(); ++i) {
      EXPECT_EQ(action[i], std::stof(row.at(first_action + i))) << "step " << row.at(1);
    }
    ++compared;
  }
  return compared;
}

}  // namespace upkie_rl::testing
