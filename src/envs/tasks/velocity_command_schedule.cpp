#include "envs/tasks/velocity_command_schedule.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "base/input_file.hpp"
#include "base/setting_bounds.hpp"
#include "envs/core/shared_options.hpp"
#include "envs/records/number_row.hpp"

namespace upkie_rl {

VelocityCommandSchedule::VelocityCommandSchedule(std::vector<Row> rows) : rows_(std::move(rows)) {
  if (rows_.empty()) throw std::invalid_argument("velocity command schedule: no rows");
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const Row& row = rows_[i];
    if (!std::isfinite(row.time) || !std::isfinite(row.command.forward_velocity) ||
        !std::isfinite(row.command.yaw_rate) || !std::isfinite(row.command.height)) {
      throw std::invalid_argument("velocity command schedule: row " + std::to_string(i + 1) +
                                  " has a value that is not finite");
    }
    if (row.time < 0.0 || (i > 0 && row.time <= rows_[i - 1].time)) {
      throw std::invalid_argument("velocity command schedule: row " + std::to_string(i + 1) +
                                  ": times must be non-negative and increasing");
    }
  }
}

namespace {

/// Refuses a row whose time or command is outside its range, naming line, column and value;
/// `columns` is 3 (time,vx,wz) or 4 (and height).
void check_row(const std::string& where, const std::array<double, 4>& values, std::size_t columns,
               const VelocityCommandRanges& ranges) {
  check_setting(where + ": column time", values[0], 0.0, kOptionHuge);
  check_setting(where + ": column vx (env option max_forward_velocity)", values[1],
                -ranges.max_forward_velocity, ranges.max_forward_velocity);
  check_setting(where + ": column wz (env option max_yaw_rate)", values[2], -ranges.max_yaw_rate,
                ranges.max_yaw_rate);
  if (columns < 4) return;
  if (!ranges.height_command) {
    throw std::invalid_argument(where +
                                ": column height, but the task has no height command (env "
                                "option height_command=false)");
  }
  check_setting(where + ": column height (env options min_height_command, max_height_command)",
                values[3], ranges.min_height, ranges.max_height);
}

/// Parses `line` as time,vx,wz or time,vx,wz,height into `values`; the number of columns,
/// 0 if it is neither.
std::size_t parse_command_row(const std::string& line, std::array<double, 4>& values) {
  if (parse_number_row(line, values)) return 4;
  if (parse_number_row(line, std::span<double>(values).first(3))) return 3;
  return 0;
}

}  // namespace

VelocityCommandSchedule VelocityCommandSchedule::load(const std::filesystem::path& path,
                                                      const VelocityCommandRanges& ranges) {
  std::istringstream file(
      read_input_file<std::invalid_argument>(path, "velocity commands", kMaxCommandFileBytes));
  std::vector<Row> rows;
  std::string line;
  int number = 0;
  bool first_content = true;  // a header may come after blank and comment lines
  while (std::getline(file, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    std::array<double, 4> values{};
    const bool header_allowed = first_content;
    first_content = false;
    const std::size_t columns = parse_command_row(line, values);
    if (columns == 0) {
      if (header_allowed) continue;  // a header
      throw std::invalid_argument(path.string() + ":" + std::to_string(number) +
                                  ": expected time,vx,wz or time,vx,wz,height (three or four "
                                  "numbers)");
    }
    check_row(path.string() + ":" + std::to_string(number), values, columns, ranges);
    // Without a height column, the top of the range: standing by default.
    const double height = columns == 4 ? values[3] : ranges.rest_command().height;
    rows.push_back({values[0], {values[1], values[2], height}});
  }
  try {
    return VelocityCommandSchedule(std::move(rows));
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(path.string() + ": " + error.what());
  }
}

const VelocityCommand& VelocityCommandSchedule::at(double time) const {
  const auto after = std::upper_bound(rows_.begin(), rows_.end(), time,
                                      [](double t, const Row& row) { return t < row.time; });
  return after == rows_.begin() ? rows_.front().command : std::prev(after)->command;
}

}  // namespace upkie_rl
