#include "cli/robustness_grid.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "base/number_text.hpp"
#include "base/split_fields.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl::apps {
namespace {

constexpr std::size_t kMaxAxes = 2;
constexpr std::size_t kMaxValues = 1000;

double parse_number(const std::string& text, const std::string& axis) {
  const std::optional<double> value = number_from_text<double>(text);
  if (!value || !std::isfinite(*value)) {
    throw std::invalid_argument("grid axis \"" + axis + "\": \"" + text +
                                "\" is not a finite number");
  }
  return *value;
}

}  // namespace

std::string format_value(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::vector<GridAxis> parse_grid(const std::string& text) {
  std::vector<GridAxis> axes;
  if (text.empty()) return axes;
  for (const std::string& item : split_fields(text, ',')) {
    const std::size_t equal = item.find('=');
    if (equal == std::string::npos || equal == 0) {
      throw std::invalid_argument("grid axis \"" + item +
                                  "\": expected name=start:stop:step or name=value");
    }
    GridAxis axis{item.substr(0, equal), {}};
    for (const GridAxis& previous : axes) {
      if (previous.name == axis.name) {
        throw std::invalid_argument("grid axis \"" + axis.name + "\" is given twice");
      }
    }
    const std::vector<std::string> range = split_fields(item.substr(equal + 1), ':');
    if (range.size() == 1) {
      axis.values.push_back(parse_number(range[0], axis.name));
    } else if (range.size() == 3) {
      const double start = parse_number(range[0], axis.name);
      const double stop = parse_number(range[1], axis.name);
      const double step = parse_number(range[2], axis.name);
      if (!(step > 0.0) || stop < start) {
        throw std::invalid_argument("grid axis \"" + axis.name +
                                    "\": need start <= stop and a positive step");
      }
      // Values start + i*step up to stop, which counts when within rounding of a step.
      const double count = std::floor((stop - start) / step + 1e-9);
      if (count + 1 > static_cast<double>(kMaxValues)) {
        throw std::invalid_argument("grid axis \"" + axis.name + "\" has more than " +
                                    std::to_string(kMaxValues) + " values");
      }
      for (int i = 0; i <= static_cast<int>(count); ++i) axis.values.push_back(start + i * step);
    } else {
      throw std::invalid_argument("grid axis \"" + axis.name +
                                  "\": expected name=start:stop:step or name=value");
    }
    axes.push_back(std::move(axis));
  }
  if (axes.size() > kMaxAxes) {
    throw std::invalid_argument("the grid has " + std::to_string(axes.size()) +
                                " axes; at most two (a heat map per controller)");
  }
  return axes;
}

std::string axis_label(const std::string& name, const std::string& env_id) {
  static const std::map<std::string, std::string> kUnits = {{"push", "push [N]"},
                                                            {"mass", "mass [x nominal]"},
                                                            {"friction", "friction [x nominal]"},
                                                            {"lag", "action lag [s]"},
                                                            {"delay", "action delay [steps]"},
                                                            {"pitch", "initial pitch bound [rad]"}};
  const auto known = kUnits.find(name);
  if (known != kUnits.end()) return known->second;
  for (const OptionInfo& option : env_option_info(env_id)) {
    if (option.name != name) continue;
    const std::size_t open = option.help.rfind('[');
    const std::size_t close = option.help.rfind(']');
    if (open != std::string::npos && close != std::string::npos && open < close) {
      return name + " " + option.help.substr(open, close - open + 1);
    }
  }
  return name + " [dimensionless]";
}

EnvOptions axis_options(const std::string& name, double value) {
  const std::string text = format_value(value);
  if (name == "push") {
    if (value == 0.0) return {{"push_force", "0"}};
    return {{"push_force", text}, {"push_force_min", text}};
  }
  if (name == "mass") return {{"mass_scale", text}};
  if (name == "friction") return {{"floor_friction", text}};
  if (name == "lag") return {{"action_lag_min", text}, {"action_lag_max", text}};
  if (name == "delay") return {{"action_delay", std::to_string(std::lround(value))}};
  if (name == "pitch") return {{"init_rand_pitch", text}};
  return {{name, text}};
}

EnvOptions cell_options(const std::vector<GridAxis>& axes, const std::vector<std::size_t>& cell) {
  EnvOptions options;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    const EnvOptions axis = axis_options(axes[a].name, axes[a].values[cell[a]]);
    options.insert(options.end(), axis.begin(), axis.end());
  }
  return options;
}

std::vector<std::vector<std::size_t>> grid_cells(const std::vector<GridAxis>& axes) {
  std::vector<std::vector<std::size_t>> cells{{}};
  for (const GridAxis& axis : axes) {
    std::vector<std::vector<std::size_t>> next;
    for (const auto& cell : cells) {
      for (std::size_t v = 0; v < axis.values.size(); ++v) {
        next.push_back(cell);
        next.back().push_back(v);
      }
    }
    cells = std::move(next);
  }
  return cells;
}

}  // namespace upkie_rl::apps
