#include "envs/records/record_file.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "base/input_file.hpp"
#include "base/number_text.hpp"
#include "base/split_fields.hpp"
#include "sim/base_observer.hpp"

namespace upkie_rl {

namespace {

double parse_number(const std::string& text, const std::string& path, long line,
                    const std::string& column) {
  const std::optional<double> value = number_from_text<double>(text);
  if (!value) {
    throw RecordFileError(path + ":" + std::to_string(line) + ": column " + column +
                          " is not a number: \"" + text + "\"");
  }
  return *value;
}

/// The columns the reader takes, in the order of a row's values, each with its position in
/// the header; and which optional groups of envs/records/record_columns.hpp the file has.
struct RecordLayout {
  struct Column {
    std::string name;
    std::size_t position = 0;  ///< In the header (and every row).
  };
  std::vector<Column> columns;
  bool measured = false;    ///< visit_measurement_columns' columns, when the file has them.
  bool velocity = false;    ///< visit_command_columns' then visit_measured_velocity_columns'.
  std::size_t actions = 0;  ///< The kActionColumnPrefix columns, to the end.
};

using ColumnIndex = std::unordered_map<std::string, std::size_t>;

/// Appends the column `name` to `layout`.
/// @throws RecordFileError when the header lacks it.
void add_column(RecordLayout& layout, const std::string& name, const ColumnIndex& column_of,
                const std::string& path) {
  const auto found = column_of.find(name);
  if (found == column_of.end()) {
    throw RecordFileError(path + ": no column \"" + name +
                          "\" in its header; is it a file of `upkie-rl rollout --record`?");
  }
  layout.columns.push_back({name, found->second});
}

/// The layout of a file whose header is `header`; its action names go to `action_names`.
/// The columns and their order are those the visitors of envs/records/record_columns.hpp name, the
/// ones EpisodeRecorder writes with.
RecordLayout record_layout(const std::vector<std::string>& header, const std::string& path,
                           std::vector<std::string>& action_names) {
  ColumnIndex column_of;
  for (std::size_t i = 0; i < header.size(); ++i) column_of[header[i]] = i;
  RecordLayout layout;
  const auto add = [&](const auto& column, auto&) {
    add_column(layout, std::string(column), column_of, path);
  };
  bool found = true;
  const auto check = [&](const auto& column, auto&) {
    found = found && column_of.count(std::string(column)) > 0;
  };
  for (const char* column : {kEpisodeColumn, kStepColumn, kTimeColumn, kRewardColumn}) {
    add_column(layout, column, column_of, path);
  }
  RecordedStep fields;  // Only the names of its members' columns are visited here.
  visit_pose_columns(fields.pose, add);
  visit_measurement_columns(fields, check);
  layout.measured = std::exchange(found, true);
  if (layout.measured) visit_measurement_columns(fields, add);
  // Velocity tasks: the command (observation columns) and the measured velocity, both or
  // neither; files of other tasks, or written before the measured columns, have neither.
  VelocityCommand command;
  BaseVelocity measured;
  visit_command_columns(command, check);
  visit_measured_velocity_columns(measured, check);
  layout.velocity = found;
  if (layout.velocity) {
    visit_command_columns(command, add);
    visit_measured_velocity_columns(measured, add);
  }
  layout.actions = layout.columns.size();
  const std::string action_prefix = kActionColumnPrefix;
  for (const std::string& column : header) {
    if (column.rfind(action_prefix, 0) == 0) {
      action_names.push_back(column.substr(action_prefix.size()));
      add_column(layout, column, column_of, path);
    }
  }
  return layout;
}

/// The step of one row's `values` (in the order of `layout`); `at` names the line.
/// @throws RecordFileError on a row that is not a step of a simulated episode.
RecordedStep recorded_step(const std::vector<double>& values, const RecordLayout& layout,
                           const std::string& at) {
  std::size_t next = 0;
  const auto take = [&](const auto&, double& value) { value = values[next++]; };
  RecordedStep step;
  double episode = 0.0;
  double step_index = 0.0;
  take(kEpisodeColumn, episode);
  take(kStepColumn, step_index);
  take(kTimeColumn, step.time);
  take(kRewardColumn, step.reward);
  visit_pose_columns(step.pose, take);
  if (std::isnan(step.pose.base_position.x())) {
    throw RecordFileError(at + "no ground truth (a spine run has no simulator pose to draw)");
  }
  if (!(episode >= 0.0 && episode < 1e9 && step_index >= 0.0 && step_index < 1e9) ||
      episode != std::floor(episode) || step_index != std::floor(step_index)) {
    throw RecordFileError(at + "episode and step must be whole numbers >= 0");
  }
  step.episode = static_cast<int>(episode);
  step.step = static_cast<int>(step_index);
  if (!std::isfinite(step.time) || !step.pose.base_position.allFinite() ||
      !step.pose.base_orientation.coeffs().allFinite() ||
      step.pose.base_orientation.norm() < 1e-9) {
    throw RecordFileError(at + "the time or the base pose is not finite");
  }
  if (layout.measured) {
    visit_measurement_columns(step, take);
  } else {
    step.pitch = base_pitch(step.pose.base_orientation.normalized());
    step.ground_position = step.pose.base_position.x();
  }
  if (layout.velocity) {
    visit_command_columns(step.command.emplace(), take);
    visit_measured_velocity_columns(step.measured.emplace(), take);
  }
  step.action.assign(values.begin() + static_cast<std::ptrdiff_t>(layout.actions), values.end());
  return step;
}

}  // namespace

RecordFile read_record_file(const std::filesystem::path& path) {
  std::istringstream in(read_input_file<RecordFileError>(path, "record file", kMaxRecordFileBytes));
  return read_record_file(in, path.string());
}

RecordFile read_record_file(std::istream& in, const std::string& path) {
  std::string line;
  if (!std::getline(in, line)) throw RecordFileError(path + " is empty");
  const std::vector<std::string> header = split_fields(line);
  RecordFile file;
  const RecordLayout layout = record_layout(header, path, file.action_names);
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

}  // namespace upkie_rl
