#include "envs/builtin_controllers.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace upkie_rl {

namespace {

constexpr const char* kValidSpecs = "valid controllers: zero, linear:k1,k2,k3,k4";

std::array<float, 4> parse_gains(const std::string& spec, const std::string& list) {
  std::array<float, 4> gains{};
  std::size_t count = 0;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, comma - start);
    float value = 0.0f;
    const char* end = item.data() + item.size();
    const auto [stop, error] = std::from_chars(item.data(), end, value);
    if (item.empty() || error != std::errc() || stop != end || !std::isfinite(value) ||
        count == gains.size()) {
      throw std::invalid_argument("controller \"" + spec +
                                  "\": expected four finite gains, linear:k1,k2,k3,k4");
    }
    gains[count++] = value;
    start = comma + 1;
  }
  if (count != gains.size()) {
    throw std::invalid_argument("controller \"" + spec +
                                "\": expected four finite gains, linear:k1,k2,k3,k4");
  }
  return gains;
}

}  // namespace

ZeroController::ZeroController(const Env& env) : neutral_(env.action_space().size()) {
  env.neutral_action(neutral_);
}

void ZeroController::act(std::span<const float>, std::span<float> action) {
  std::copy(neutral_.begin(), neutral_.end(), action.begin());
}

LinearController::LinearController(const Env& env, const std::array<float, 4>& gains)
    : gains_(gains) {
  const BoxSpace& observation = env.observation_space();
  const std::array<const char*, 4> names = {"theta", "p", "theta_dot", "p_dot"};
  for (std::size_t k = 0; k < names.size(); ++k) {
    indices_[k] = observation.index_of(names[k]);
    if (indices_[k] == observation.size()) {
      throw std::invalid_argument(
          std::string("linear controller: the observation has no \"") + names[k] +
          "\" component (it needs theta, p, theta_dot, p_dot: the pendulum or gyropod)");
    }
  }
  const BoxSpace& action = env.action_space();
  action_index_ = action.index_of("ground_velocity");
  if (action_index_ == action.size()) {
    throw std::invalid_argument(
        "linear controller: the action has no \"ground_velocity\" component");
  }
  low_ = action.low[action_index_];
  high_ = action.high[action_index_];
}

void LinearController::act(std::span<const float> observation, std::span<float> action) {
  std::fill(action.begin(), action.end(), 0.0f);
  float velocity = 0.0f;
  for (std::size_t k = 0; k < gains_.size(); ++k) velocity += gains_[k] * observation[indices_[k]];
  action[action_index_] = std::clamp(velocity, low_, high_);
}

std::unique_ptr<Controller> make_builtin_controller(const std::string& spec, const Env& env) {
  if (spec == "zero") return std::make_unique<ZeroController>(env);
  constexpr std::string_view kLinearPrefix = "linear:";
  if (spec.rfind(kLinearPrefix, 0) == 0) {
    return std::make_unique<LinearController>(env,
                                              parse_gains(spec, spec.substr(kLinearPrefix.size())));
  }
  throw std::invalid_argument("unknown controller \"" + spec + "\"; " + kValidSpecs);
}

}  // namespace upkie_rl
