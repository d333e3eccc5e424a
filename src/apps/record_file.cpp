#include "apps/record_file.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <optional>
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

/// The columns the reader takes, in the order of a row's values, each with its position in
/// the header; and where each group of them starts among the values.
struct RecordLayout {
  struct Column {
    std::string name;
    std::size_t position = 0;  ///< In the header (and every row).
  };
  std::vector<Column> columns;
  std::size_t ground_truth = 0;         ///< kGroundTruthColumns (base position, then orientation).
  std::size_t servos = 0;               ///< kServoNames.
  std::optional<std::size_t> measured;  ///< kMeasuredColumns, when the file has them.
  std::optional<std::size_t> velocity;  ///< kCommandColumns then kMeasuredVelocityColumns.
  std::size_t actions = 0;              ///< The "action." columns, to the end.
};

/// Appends the columns `names` to `layout`; returns where they start among the values.
/// @throws RecordFileError when the header lacks one of them.
template <typename Names>
std::size_t add_columns(RecordLayout& layout, const Names& names,
                        const std::unordered_map<std::string, std::size_t>& column_of,
                        const std::string& path) {
  const std::size_t first = layout.columns.size();
  for (const auto& name : names) {
    const auto found = column_of.find(std::string(name));
    if (found == column_of.end()) {
      throw RecordFileError(path + ": no column \"" + std::string(name) +
                            "\" in its header; is it a file of `upkie-rl rollout --record`?");
    }
    layout.columns.push_back({std::string(name), found->second});
  }
  return first;
}

/// Whether the header has every one of `names`.
template <typename Names>
bool has_columns(const Names& names,
                 const std::unordered_map<std::string, std::size_t>& column_of) {
  return std::all_of(names.begin(), names.end(),
                     [&column_of](const char* name) { return column_of.count(name) > 0; });
}

/// The layout of a file whose header is `header`; its action names go to `action_names`.
RecordLayout record_layout(const std::vector<std::string>& header, const std::string& path,
                           std::vector<std::string>& action_names) {
  std::unordered_map<std::string, std::size_t> column_of;
  for (std::size_t i = 0; i < header.size(); ++i) column_of[header[i]] = i;
  RecordLayout layout;
  add_columns(layout, std::array{"episode", "step", "t", "reward"}, column_of, path);
  layout.ground_truth = add_columns(layout, kGroundTruthColumns, column_of, path);
  layout.servos = add_columns(layout, kServoNames, column_of, path);
  if (has_columns(kMeasuredColumns, column_of)) {
    layout.measured = add_columns(layout, kMeasuredColumns, column_of, path);
  }
  // Velocity tasks: the command (observation columns) and the measured velocity, both or
  // neither; files of other tasks, or written before the measured columns, have neither.
  if (has_columns(kCommandColumns, column_of) && has_columns(kMeasuredVelocityColumns, column_of)) {
    layout.velocity = add_columns(layout, kCommandColumns, column_of, path);
    add_columns(layout, kMeasuredVelocityColumns, column_of, path);
  }
  const std::string action_prefix = "action.";
  std::vector<std::string> actions;
  for (const std::string& column : header) {
    if (column.rfind(action_prefix, 0) == 0) {
      action_names.push_back(column.substr(action_prefix.size()));
      actions.push_back(column);
    }
  }
  layout.actions = add_columns(layout, actions, column_of, path);
  return layout;
}

/// The step of one row's `values` (in the order of `layout`); `at` names the line.
/// @throws RecordFileError on a row that is not a step of a simulated episode.
RecordedStep recorded_step(const std::vector<double>& values, const RecordLayout& layout,
                           const std::string& at) {
  const double* truth = values.data() + layout.ground_truth;
  if (std::isnan(truth[0])) {
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
  step.pose.base_position = Eigen::Vector3d(truth[0], truth[1], truth[2]);
  step.pose.base_orientation = Eigen::Quaterniond(truth[3], truth[4], truth[5], truth[6]);
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    step.pose.joint_angles[servo] = values[layout.servos + servo];
  }
  if (!std::isfinite(step.time) || !step.pose.base_position.allFinite() ||
      !step.pose.base_orientation.coeffs().allFinite() ||
      step.pose.base_orientation.norm() < 1e-9) {
    throw RecordFileError(at + "the time or the base pose is not finite");
  }
  if (layout.measured) {
    step.pitch = values[*layout.measured];
    step.ground_position = values[*layout.measured + 1];
  } else {
    step.pitch = base_pitch(step.pose.base_orientation.normalized());
    step.ground_position = step.pose.base_position.x();
  }
  if (layout.velocity) {
    const double* velocity = values.data() + *layout.velocity;
    step.command = VelocityCommand{velocity[0], velocity[1]};
    step.measured = BaseVelocity{velocity[2], velocity[3]};
  }
  step.action.assign(values.begin() + static_cast<std::ptrdiff_t>(layout.actions), values.end());
  return step;
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
  RecordFile file;
  const RecordLayout layout = record_layout(header, path, file.action_names);
  file.has_velocity = layout.velocity.has_value();
  long line_number = 1;
  std::vector<double> values(layout.columns.size());
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string at = path + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size()) {
      throw RecordFileError(at + std::to_string(fields.size()) + " fields, the header has " +
                            std::to_string(header.size()) + " (truncated file?)");
    }
    for (std::size_t i = 0; i < layout.columns.size(); ++i) {
      const RecordLayout::Column& column = layout.columns[i];
      values[i] = parse_number(fields[column.position], path, line_number, column.name);
    }
    RecordedStep step = recorded_step(values, layout, at);
    if (!file.steps.empty() && file.steps.back().episode == step.episode &&
        step.time < file.steps.back().time) {
      throw RecordFileError(at + "time goes back within episode " + std::to_string(step.episode));
    }
    file.steps.push_back(std::move(step));
  }
  if (file.steps.empty()) throw RecordFileError(path + " has a header but no rows");
  return file;
}

}  // namespace upkie_rl::apps
