#include "apps/record_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "sim/base_observer.hpp"

namespace upkie_rl::apps {

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

double parse_number(const std::string& text, const std::string& path, long line,
                    const std::string& column) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw RecordFileError(path + ":" + std::to_string(line) + ": column " + column +
                          " is not a number: \"" + text + "\"");
  }
  return value;
}

}  // namespace

RecordFile read_record_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw RecordFileError("cannot read the record file " + path.string());
  return read_record_file(in, path.string());
}

RecordFile read_record_file(std::istream& in, const std::string& path) {
  std::string line;
  if (!std::getline(in, line)) throw RecordFileError(path + " is empty");
  const std::vector<std::string> header = split_fields(line);
  std::unordered_map<std::string, std::size_t> column_of;
  for (std::size_t i = 0; i < header.size(); ++i) column_of[header[i]] = i;
  std::vector<std::string> needed = {"episode", "step", "t", "reward"};
  needed.insert(needed.end(), kGroundTruthColumns.begin(), kGroundTruthColumns.end());
  for (const auto& joint : kServoNames) needed.emplace_back(joint);
  const std::size_t num_required = needed.size();
  const bool has_measured =
      column_of.count(kMeasuredColumns[0]) && column_of.count(kMeasuredColumns[1]);
  if (has_measured) needed.insert(needed.end(), kMeasuredColumns.begin(), kMeasuredColumns.end());
  RecordFile file;
  // Velocity tasks: the command (observation columns) and the measured velocity, both or
  // neither; files of other tasks, or written before the measured columns, have neither.
  std::size_t velocity_first = needed.size();
  file.has_velocity = true;
  for (const auto& columns : {kCommandColumns, kMeasuredVelocityColumns}) {
    for (const char* column : columns)
      file.has_velocity = file.has_velocity && column_of.count(column);
  }
  if (file.has_velocity) {
    needed.insert(needed.end(), kCommandColumns.begin(), kCommandColumns.end());
    needed.insert(needed.end(), kMeasuredVelocityColumns.begin(), kMeasuredVelocityColumns.end());
  }
  const std::string action_prefix = "action.";
  for (const std::string& column : header) {
    if (column.rfind(action_prefix, 0) == 0) {
      file.action_names.push_back(column.substr(action_prefix.size()));
      needed.push_back(column);
    }
  }
  std::vector<std::size_t> index;
  for (const std::string& name : needed) {
    const auto found = column_of.find(name);
    if (found == column_of.end()) {
      throw RecordFileError(path + ": no column \"" + name +
                            "\" in its header; is it a file of `upkie-rl rollout --record`?");
    }
    index.push_back(found->second);
  }

  long line_number = 1;
  std::vector<double> values(needed.size());
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string at = path + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size()) {
      throw RecordFileError(at + std::to_string(fields.size()) + " fields, the header has " +
                            std::to_string(header.size()) + " (truncated file?)");
    }
    for (std::size_t i = 0; i < needed.size(); ++i) {
      values[i] = parse_number(fields[index[i]], path, line_number, needed[i]);
    }
    if (std::isnan(values[4])) {
      throw RecordFileError(at + "no ground truth (a spine run has no simulator pose to draw)");
    }
    RecordedStep step;
    if (!(values[0] >= 0.0 && values[0] < 1e9 && values[1] >= 0.0 && values[1] < 1e9) ||
        values[0] != std::floor(values[0]) || values[1] != std::floor(values[1])) {
      throw RecordFileError(at + "episode and step must be whole numbers >= 0");
    }
    step.episode = static_cast<int>(values[0]);
    step.step = static_cast<int>(values[1]);
    step.time = values[2];
    step.reward = values[3];
    step.pose.base_position = Eigen::Vector3d(values[4], values[5], values[6]);
    step.pose.base_orientation = Eigen::Quaterniond(values[7], values[8], values[9], values[10]);
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      step.pose.joint_angles[servo] = values[11 + servo];
    }
    if (!std::isfinite(step.time) || !step.pose.base_position.allFinite() ||
        !step.pose.base_orientation.coeffs().allFinite() ||
        step.pose.base_orientation.norm() < 1e-9) {
      throw RecordFileError(at + "the time or the base pose is not finite");
    }
    if (!file.steps.empty() && file.steps.back().episode == step.episode &&
        step.time < file.steps.back().time) {
      throw RecordFileError(at + "time goes back within episode " + std::to_string(step.episode));
    }
    std::size_t next = num_required;
    if (has_measured) {
      step.pitch = values[next++];
      step.ground_position = values[next++];
    } else {
      step.pitch = base_pitch(step.pose.base_orientation.normalized());
      step.ground_position = step.pose.base_position.x();
    }
    if (file.has_velocity) {
      step.command = VelocityCommand{values[velocity_first], values[velocity_first + 1]};
      step.measured = BaseVelocity{values[velocity_first + 2], values[velocity_first + 3]};
      next += 4;
    }
    step.action.assign(values.begin() + static_cast<std::ptrdiff_t>(next), values.end());
    file.steps.push_back(std::move(step));
  }
  if (file.steps.empty()) throw RecordFileError(path + " has a header but no rows");
  return file;
}

}  // namespace upkie_rl::apps
