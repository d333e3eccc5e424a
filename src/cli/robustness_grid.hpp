#pragma once
/// @file
/// The perturbation grid of `upkie-rl evaluate`: axes such as push=0:40:5 or
/// mass=0.7:1.3:0.1, and the environment options each cell sets.

#include <string>
#include <vector>

#include "envs/core/env_options.hpp"

namespace upkie_rl::apps {

/// One axis of the grid: a name and its values in order.
struct GridAxis {
  std::string name;
  std::vector<double> values;
};

/// Parses "name=start:stop:step[,name=...]" (stop included) or "name=value"; at most two
/// axes. Names: push [N] (one push per episode of exactly this magnitude), mass (factor on
/// every body's mass and inertia), friction (factor on the tire-floor friction), lag [s]
/// (first-order action lag), delay [steps] (action delay), pitch [rad] (initial pitch drawn
/// in ±it), or any numeric environment option.
/// @throws std::invalid_argument naming the malformed axis (empty, reversed or too many
///         values, more than two axes, a repeated name).
std::vector<GridAxis> parse_grid(const std::string& text);

/// An axis's name with its unit, for figures: "push [N]", "mass [x nominal]", ...; another
/// environment option gets the unit its help states ("[...]"), else "[dimensionless]".
/// @throws std::invalid_argument on an unknown `env_id`.
std::string axis_label(const std::string& name, const std::string& env_id);

/// The environment options an axis value sets.
EnvOptions axis_options(const std::string& name, double value);

/// A cell's options: those of each axis at the cell's value index.
EnvOptions cell_options(const std::vector<GridAxis>& axes, const std::vector<std::size_t>& cell);

/// Every cell of the grid as value indices, the last axis varying fastest; one empty cell
/// without axes.
std::vector<std::vector<std::size_t>> grid_cells(const std::vector<GridAxis>& axes);

/// A value as text, shortest round-trip form ("0.7", "5").
std::string format_value(double value);

}  // namespace upkie_rl::apps
