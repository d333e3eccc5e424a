#include "envs/spaces/box_space.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace upkie_rl {

std::size_t BoxSpace::index_of(const std::string& name) const {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

std::string BoxSpace::describe() const {
  std::ostringstream out;
  out << "Box(" << size() << ": ";
  for (std::size_t i = 0; i < size(); ++i) {
    out << (i > 0 ? ", " : "") << names[i] << " [" << low[i] << ", " << high[i] << "]";
  }
  out << ")";
  return out.str();
}

void clamp_to_space(const BoxSpace& space, std::span<const float> action, std::span<float> clamped,
                    std::span<const std::size_t> allow_nan) {
  if (action.size() != space.size() || clamped.size() != space.size()) {
    throw std::invalid_argument("action has " + std::to_string(action.size()) +
                                " components, the action space has " +
                                std::to_string(space.size()));
  }
  for (std::size_t i = 0; i < action.size(); ++i) {
    const float value = action[i];
    if (std::isnan(value)) {
      if (std::find(allow_nan.begin(), allow_nan.end(), i) == allow_nan.end()) {
        throw std::invalid_argument("action component " + std::to_string(i) + " (" +
                                    space.names[i] + ") is NaN");
      }
      clamped[i] = value;
    } else if (std::isinf(value)) {
      throw std::invalid_argument("action component " + std::to_string(i) + " (" + space.names[i] +
                                  ") is infinite");
    } else {
      clamped[i] = std::clamp(value, space.low[i], space.high[i]);
    }
  }
}

}  // namespace upkie_rl
