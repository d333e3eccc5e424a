#include "sim/floor_bumps.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "model/number_text.hpp"
#include "model/setting_bounds.hpp"

namespace upkie_rl {

std::vector<double> FloorBumps::centres() const {
  std::vector<double> centres;
  if (!enabled()) return centres;
  // Bumps per side: the field's half length, with a bump on its edge kept (20 m / 0.2 m).
  const int per_side = static_cast<int>(std::floor(kBumpFieldHalfLength / spacing + 1e-9));
  centres.reserve(2 * static_cast<std::size_t>(per_side));
  for (int k = -per_side; k <= per_side; ++k) {
    if (k != 0) centres.push_back(k * spacing);
  }
  return centres;
}

void FloorBumps::declare_options(OptionTable& table) {
  table.add_real(kBumpHeightOption, &height);
  table.add_real(kBumpSpacingOption, &spacing);
  table.add_real(kBumpWidthOption, &width);
  table.add_rule([this] { return problem(); });
}

std::string FloorBumps::problem() const {
  if (enabled() && width > spacing / 2.0) {
    return std::string(kBumpWidthOption.name) + " (" + shortest_text(width) +
           " m) is more than half " + kBumpSpacingOption.name + " (" + shortest_text(spacing) +
           " m)";
  }
  return "";
}

void FloorBumps::validate(const std::string& prefix) const {
  for (const auto& [spec, value] :
       {std::pair{kBumpHeightOption, height}, std::pair{kBumpSpacingOption, spacing},
        std::pair{kBumpWidthOption, width}}) {
    check_setting(prefix + spec.name, value, spec.min, spec.max);
  }
  const std::string broken = problem();
  if (!broken.empty()) throw std::invalid_argument(prefix + broken);
}

}  // namespace upkie_rl
