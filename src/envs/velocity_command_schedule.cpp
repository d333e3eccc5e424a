#include "envs/velocity_command_schedule.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "envs/number_row.hpp"

namespace upkie_rl {

VelocityCommandSchedule::VelocityCommandSchedule(std::vector<Row> rows) : rows_(std::move(rows)) {
  if (rows_.empty()) throw std::invalid_argument("velocity command schedule: no rows");
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    const Row& row = rows_[i];
    if (!std::isfinite(row.time) || !std::isfinite(row.command.forward_velocity) ||
        !std::isfinite(row.command.yaw_rate)) {
      throw std::invalid_argument("velocity command schedule: row " + std::to_string(i + 1) +
                                  " has a value that is not finite");
    }
    if (row.time < 0.0 || (i > 0 && row.time <= rows_[i - 1].time)) {
      throw std::invalid_argument("velocity command schedule: row " + std::to_string(i + 1) +
                                  ": times must be non-negative and increasing");
    }
  }
}

VelocityCommandSchedule VelocityCommandSchedule::load(const std::filesystem::path& path) {
  std::ifstream file(path);
  if (!file) throw std::invalid_argument("cannot read velocity commands " + path.string());
  std::vector<Row> rows;
  std::string line;
  int number = 0;
  bool first_content = true;  // a header may come after blank and comment lines
  while (std::getline(file, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    std::array<double, 3> values{};
    const bool header_allowed = first_content;
    first_content = false;
    if (!parse_number_row(line, values)) {
      if (header_allowed) continue;  // a header
      throw std::invalid_argument(path.string() + ":" + std::to_string(number) +
                                  ": expected time,vx,wz (three numbers)");
    }
    rows.push_back({values[0], {values[1], values[2]}});
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
