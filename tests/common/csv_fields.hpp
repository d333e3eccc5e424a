#pragma once
/// @file
/// The fields of one line of a CSV file (the record files of `rollout --record` and
/// `drive --record`), for the tests that read them back.

#include <sstream>
#include <string>
#include <vector>

namespace upkie_rl::testing {

/// The comma-separated fields of `line` (no quoting: record files have none).
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
  return fields;
}

}  // namespace upkie_rl::testing
