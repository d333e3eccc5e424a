#include "envs/controllers/builtin_controllers.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "envs/controllers/lqr_design.hpp"
#include "envs/controllers/velocity_balancer.hpp"
#include "envs/controllers/velocity_balancer_design.hpp"
#include "envs/kinds/velocity_env.hpp"

namespace upkie_rl {

namespace {

constexpr const char* kValidSpecs =
    "valid controllers: zero, linear:k1,k2,k3,k4, lqr, lqr:theta,p,theta_dot,p_dot,command, "
    "balancer:k_theta,k_theta_dot,k_v,k_e,theta0,theta_per_v,u0,u_per_v[,theta_per_a,u_per_a] "
    "(velocity tasks)";

/// `N` finite numbers separated by commas in `list`.
template <std::size_t N>
std::array<float, N> parse_numbers(const std::string& spec, const std::string& list,
                                   const char* expected) {
  std::array<float, N> gains{};
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
      throw std::invalid_argument("controller \"" + spec + "\": expected " + expected);
    }
    gains[count++] = value;
    start = comma + 1;
  }
  if (count != gains.size()) {
    throw std::invalid_argument("controller \"" + spec + "\": expected " + expected);
  }
  return gains;
}

constexpr const char* kLinearExpected = "four finite gains, linear:k1,k2,k3,k4";
constexpr const char* kBalancerExpected =
    "eight or ten finite numbers, "
    "balancer:k_theta,k_theta_dot,k_v,k_e,theta0,theta_per_v,u0,u_per_v[,theta_per_a,u_per_a]";
constexpr std::string_view kBalancerPrefix = "balancer:";

/// The pendulum's law k·[θ, p, θ̇, ṗ] as a velocity balancer without feedforward (the
/// position p becomes the integral of the velocity error).
VelocityBalancerGains balancer_of_linear(const std::array<float, 4>& gains) {
  VelocityBalancerGains balancer;
  balancer.feedback = {gains[0], gains[2], gains[3], gains[1]};
  return balancer;
}

std::string balancer_spec(const VelocityBalancerGains& gains) {
  std::ostringstream spec;
  spec.precision(9);
  spec << kBalancerPrefix;
  for (const double k : gains.feedback) spec << k << ',';
  spec << gains.pitch_offset << ',' << gains.pitch_per_velocity << ',' << gains.command_offset
       << ',' << gains.command_per_velocity << ',' << gains.pitch_per_acceleration << ','
       << gains.command_per_acceleration;
  return spec.str();
}

/// The gains of a `balancer:` spec's list: all of VelocityBalancerGains' members, or the
/// first eight (no acceleration feedforward, the specs before it existed).
VelocityBalancerGains parse_balancer(const std::string& spec, const std::string& list) {
  std::array<float, VelocityBalancerGains::kNumValues> numbers{};
  if (static_cast<std::size_t>(std::count(list.begin(), list.end(), ',')) + 1 ==
      VelocityBalancerGains::kNumLegacyValues) {
    const auto legacy =
        parse_numbers<VelocityBalancerGains::kNumLegacyValues>(spec, list, kBalancerExpected);
    std::copy(legacy.begin(), legacy.end(), numbers.begin());
  } else {
    numbers = parse_numbers<VelocityBalancerGains::kNumValues>(spec, list, kBalancerExpected);
  }
  VelocityBalancerGains gains;
  for (std::size_t k = 0; k < 4; ++k) gains.feedback[k] = numbers[k];
  gains.pitch_offset = numbers[4];
  gains.pitch_per_velocity = numbers[5];
  gains.command_offset = numbers[6];
  gains.command_per_velocity = numbers[7];
  gains.pitch_per_acceleration = numbers[8];
  gains.command_per_acceleration = numbers[9];
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
    const std::array<float, 4> gains =
        parse_numbers<4>(spec, spec.substr(kLinearPrefix.size()), kLinearExpected);
    // The velocity task has no pendulum state: the same law in error coordinates drives it.
    if (find_velocity_env(env) != nullptr) {
      return std::make_unique<VelocityBalancer>(env, balancer_of_linear(gains));
    }
    return std::make_unique<LinearController>(env, gains);
  }
  if (spec.rfind(kBalancerPrefix, 0) == 0) {
    return std::make_unique<VelocityBalancer>(
        env, parse_balancer(spec, spec.substr(kBalancerPrefix.size())));
  }
  throw std::invalid_argument("unknown controller \"" + spec + "\"; " + kValidSpecs);
}

std::string resolve_controller_spec(const std::string& spec, const DesignEnvFactory& design_env) {
  if (spec != "lqr" && spec.rfind("lqr:", 0) != 0) return spec;
  std::optional<std::array<float, 5>> deviations;
  if (spec != "lqr") {
    deviations = parse_numbers<5>(spec, spec.substr(4),
                                  "five positive deviations, lqr:theta,p,theta_dot,p_dot,command");
    for (const float number : *deviations) {
      if (!(number > 0.0f)) {
        throw std::invalid_argument("controller \"" + spec + "\": deviations must be positive");
      }
    }
  }
  if (!design_env) throw std::invalid_argument("controller lqr: no environment to design it on");
  const std::unique_ptr<Env> env = design_env();
  if (find_velocity_env(*env) != nullptr) {
    // Velocity tasks: the balancer designed on the task itself; p is the integral of the
    // velocity error and ṗ the velocity error.
    VelocityBalancerWeights weights;
    if (deviations) {
      const std::array<float, 5>& d = *deviations;
      weights = {d[0], d[2], d[3], d[1], d[4]};
    }
    return balancer_spec(design_velocity_balancer(*env, weights));
  }
  LqrWeights weights;
  if (deviations) {
    for (std::size_t k = 0; k < 4; ++k) weights.max_state[k] = (*deviations)[k];
    weights.max_command = (*deviations)[4];
  }
  const std::array<float, 4> gains = design_lqr_gains(*env, weights);
  std::ostringstream linear;
  linear.precision(9);
  linear << "linear:" << gains[0] << ',' << gains[1] << ',' << gains[2] << ',' << gains[3];
  return linear.str();
}

}  // namespace upkie_rl
