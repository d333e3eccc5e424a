#include "envs/records/robot_log.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "base/input_file.hpp"
#include "base/number_text.hpp"
#include "base/split_fields.hpp"
#include "envs/records/record_columns.hpp"
#include "sim/servo_command_fields.hpp"
#include "spine/spine_log_reader.hpp"

namespace upkie_rl {

namespace {

double parse_field(const std::string& text, const std::string& column, const std::string& where) {
  const std::optional<double> value = number_from_text<double>(text);
  if (!value) {
    throw RobotLogError(where + "column " + column + " is not a number: \"" + text + "\"");
  }
  return *value;
}

/// Where each value of a row goes in a LoggedCycle.
struct ColumnTarget {
  std::size_t position = 0;  ///< In the row.
  std::string name;
  double* (*field)(LoggedCycle&, std::size_t) = nullptr;
  std::size_t index = 0;  ///< Servo, or servo * fields + field for commands.
  bool nan_allowed = false;
};

/// Finds the column positions of a record file header.
class RecordHeader {
 public:
  explicit RecordHeader(const std::vector<std::string>& header) {
    for (std::size_t i = 0; i < header.size(); ++i) position_of_[header[i]] = i;
  }
  std::optional<std::size_t> find(const std::string& column) const {
    const auto found = position_of_.find(column);
    if (found == position_of_.end()) return std::nullopt;
    return found->second;
  }

 private:
  std::unordered_map<std::string, std::size_t> position_of_;
};

std::vector<ColumnTarget> record_targets(const RecordHeader& header, const std::string& name,
                                         LoggedSignals& signals) {
  std::vector<ColumnTarget> targets;
  const auto add = [&](const std::string& column, auto field, std::size_t index, bool nan) {
    const std::optional<std::size_t> position = header.find(column);
    if (!position) return false;
    targets.push_back({*position, column, field, index, nan});
    return true;
  };
  const auto require = [&](const char* column, auto field) {
    if (!add(column, field, 0, false)) {
      throw RobotLogError("record file " + name + ": no column \"" + column +
                          "\" in its header; is it a file of `upkie-rl rollout --record`?");
    }
  };
  require(
      kTimeColumn, +[](LoggedCycle& c, std::size_t) { return &c.time; });
  require(
      "pitch", +[](LoggedCycle& c, std::size_t) { return &c.observation.base_orientation.pitch; });
  require(
      "ground_position",
      +[](LoggedCycle& c, std::size_t) { return &c.observation.wheel_odometry.position; });
  signals.pitch_rate = add(
                           "theta_dot",
                           +[](LoggedCycle& c, std::size_t) {
                             return &c.observation.base_orientation.angular_velocity.y();
                           },
                           0, false) ||
                       add(
                           "gyro.y",
                           +[](LoggedCycle& c, std::size_t) {
                             return &c.observation.base_orientation.angular_velocity.y();
                           },
                           0, false);
  add(
      "p_dot", +[](LoggedCycle& c, std::size_t) { return &c.observation.wheel_odometry.velocity; },
      0, false);
  signals.servo_measurements = true;
  signals.servo_commands = true;
  for (std::size_t servo = 0; servo < kNumServos; ++servo) {
    const std::string joint(kServoNames[servo]);
    signals.servo_measurements &=
        add(
            joint + ".position",
            +[](LoggedCycle& c, std::size_t s) { return &c.observation.servo[s].position; }, servo,
            false) &
        add(
            joint + ".velocity",
            +[](LoggedCycle& c, std::size_t s) { return &c.observation.servo[s].velocity; }, servo,
            false);
    add(
        joint + ".torque",
        +[](LoggedCycle& c, std::size_t s) { return &c.observation.servo[s].torque; }, servo,
        false);
    for (std::size_t field = 0; field < kServoCommandFields.size(); ++field) {
      signals.servo_commands &= add(
          kActionColumnPrefix + joint + "." + std::string(kServoCommandFields[field].key),
          +[](LoggedCycle& c, std::size_t i) {
            const ServoCommandField& f = kServoCommandFields[i % kServoCommandFields.size()];
            return &(c.command[i / kServoCommandFields.size()].*f.member);
          },
          servo * kServoCommandFields.size() + field, kServoCommandFields[field].nan_allowed);
    }
  }
  return targets;
}

}  // namespace

double RobotLog::period() const {
  std::vector<double> steps;
  steps.reserve(cycles.size());
  for (std::size_t i = 1; i < cycles.size(); ++i) {
    steps.push_back(cycles[i].time - cycles[i - 1].time);
  }
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2),
                   steps.end());
  return steps[steps.size() / 2];
}

void RobotLog::check_regular() const {
  const double expected = period();
  for (std::size_t i = 1; i < cycles.size(); ++i) {
    const double step = cycles[i].time - cycles[i - 1].time;
    if (std::abs(step - expected) > 0.25 * expected) {
      throw RobotLogError(
          format + " " + name + ": cycle " + std::to_string(i) +
          " at t = " + std::to_string(cycles[i].time) + " s comes " + std::to_string(1e3 * step) +
          " ms after the previous one, the log's "
          "period is " +
          std::to_string(1e3 * expected) + " ms: cycles dropped or a log at another frequency");
    }
  }
}

RobotLog read_record_log(std::string_view text, const std::string& name) {
  std::istringstream in{std::string(text)};
  std::string line;
  if (!std::getline(in, line)) throw RobotLogError("record file " + name + " is empty");
  const std::vector<std::string> header = split_fields(line);
  RobotLog log{name, "record file", {}, {}};
  const std::vector<ColumnTarget> targets = record_targets(RecordHeader(header), name, log.signals);
  const std::optional<std::size_t> episode_column = RecordHeader(header).find(kEpisodeColumn);
  LoggedCycle cycle;
  long line_number = 1;
  std::optional<std::string> first_episode;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string where = "record file " + name + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size()) {
      throw RobotLogError(where + std::to_string(fields.size()) + " fields, the header has " +
                          std::to_string(header.size()) + " (truncated file?)");
    }
    if (episode_column) {
      if (!first_episode) first_episode = fields[*episode_column];
      if (fields[*episode_column] != *first_episode) break;  // the first episode only
    }
    for (const ColumnTarget& target : targets) {
      double& value = *target.field(cycle, target.index);
      value = parse_field(fields[target.position], target.name, where);
      if (!(target.nan_allowed && std::isnan(value))) check_logged_value(value, target.name, where);
    }
    if (!log.cycles.empty() && !(cycle.time > log.cycles.back().time)) {
      throw RobotLogError(where + "time does not increase");
    }
    log.cycles.push_back(cycle);
  }
  if (log.cycles.size() < 2) {
    throw RobotLogError("record file " + name + " has " + std::to_string(log.cycles.size()) +
                        " rows, need at least 2");
  }
  return log;
}

RobotLog read_robot_log(const std::filesystem::path& path) {
  const std::string bytes = read_input_file<RobotLogError>(path, "log", kMaxSpineLogBytes);
  if (!looks_like_spine_log(bytes)) return read_record_log(bytes, path.string());
  RobotLog log{
      path.string(), "spine log", {true, true, true}, read_spine_log(bytes, path.string())};
  return log;
}

}  // namespace upkie_rl
