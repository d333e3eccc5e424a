#include "sim/floor_bumps.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "base/number_text.hpp"
#include "base/setting_bounds.hpp"

namespace upkie_rl {

int FloorBumps::bumps_per_side() const {
  if (!enabled()) return 0;
  // The field's half length, with a bump on its edge kept (20 m / 0.2 m).
  return static_cast<int>(std::floor(kBumpFieldHalfLength / spacing + 1e-9));
}

std::vector<double> FloorBumps::centres() const {
  std::vector<double> centres;
  const int per_side = bumps_per_side();
  centres.reserve(2 * static_cast<std::size_t>(per_side));
  for (int k = -per_side; k <= per_side; ++k) {
    if (k != 0) centres.push_back(k * spacing);
  }
  return centres;
}

double FloorBumps::surface_height(double x) const {
  // problem() keeps a footprint within half the spacing: only the nearest bump reaches x.
  const long nearest = std::lround(x / spacing);
  if (nearest == 0 || std::labs(nearest) > bumps_per_side()) return 0.0;
  const double from_top = std::abs(x - nearest * spacing) - width / 2.0;
  if (from_top <= 0.0) return height;
  if (!ramped() || from_top >= ramp_run()) return 0.0;
  return height - from_top / ramp;
}

std::array<std::array<double, 2>, 4> FloorBumps::ramped_section(double inset) const {
  const double top = height - inset;
  const double bottom = -kBumpFooting + inset;
  // The right slope, z = height - (x - width/2) / ramp, moved in by `inset` along its
  // normal (1, ramp) / sqrt(1 + ramp²): x moves in by inset sqrt(1 + ramp²) at every z.
  const auto right_x = [&](double z) {
    return width / 2.0 + ramp * (height - z) - inset * std::sqrt(1.0 + ramp * ramp);
  };
  return {{{right_x(top), top},
           {right_x(bottom), bottom},
           {-right_x(bottom), bottom},
           {-right_x(top), top}}};
}

void FloorBumps::declare_options(OptionTable& table) {
  table.add_real(kBumpHeightOption, &height);
  table.add_real(kBumpSpacingOption, &spacing);
  table.add_real(kBumpWidthOption, &width);
  table.add_real(kBumpRampOption, &ramp);
  table.add_rule([this] { return problem(); });
}

std::string FloorBumps::problem() const {
  if (!enabled() || !(footprint() > spacing / 2.0)) return "";
  const std::string half_spacing = " is more than half " + std::string(kBumpSpacingOption.name) +
                                   " (" + shortest_text(spacing) + " m)";
  if (!ramped()) {
    return std::string(kBumpWidthOption.name) + " (" + shortest_text(width) + " m)" + half_spacing;
  }
  return "the bumps' footprint " + std::string(kBumpWidthOption.name) + " + 2 " +
         kBumpRampOption.name + " x " + kBumpHeightOption.name + " (" + shortest_text(width) +
         " + 2 x " + shortest_text(ramp) + " x " + shortest_text(height) + " = " +
         shortest_text(footprint()) + " m)" + half_spacing;
}

void FloorBumps::validate(const std::string& prefix) const {
  for (const auto& [spec, value] :
       {std::pair{kBumpHeightOption, height}, std::pair{kBumpSpacingOption, spacing},
        std::pair{kBumpWidthOption, width}, std::pair{kBumpRampOption, ramp}}) {
    check_setting(prefix + spec.name, value, spec.min, spec.max);
  }
  const std::string broken = problem();
  if (!broken.empty()) throw std::invalid_argument(prefix + broken);
}

}  // namespace upkie_rl
