#include "envs/randomization/action_lag.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "envs/core/shared_options.hpp"
#include "sim/random_draws.hpp"

namespace upkie_rl {
namespace {

constexpr std::uint64_t kActionLagStream = 3;
constexpr int kMaxDelaySteps = 10000;

}  // namespace

std::string ActionLagSettings::problem() const {
  const double low = time_constant_min;
  const double high = time_constant_max;
  if (!(std::isfinite(low) && std::isfinite(high) && low >= 0.0 && high >= low)) {
    return "ActionLag: need 0 <= action_lag_min <= action_lag_max, got " + std::to_string(low) +
           " and " + std::to_string(high);
  }
  if (delay_steps < 0 || delay_steps > kMaxDelaySteps) {
    return "ActionLag: action_delay must be in [0, " + std::to_string(kMaxDelaySteps) + "], got " +
           std::to_string(delay_steps);
  }
  if (delay_steps_max < 0 || delay_steps_max > kMaxDelaySteps) {
    return "ActionLag: action_delay_max must be in [0, " + std::to_string(kMaxDelaySteps) +
           "], got " + std::to_string(delay_steps_max);
  }
  return "";
}

void ActionLagSettings::validate() const { throw_problem(problem()); }

void ActionLagSettings::declare_options(OptionTable& table) {
  table.add_real("action_lag_min", &time_constant_min, 0.0, kOptionHuge,
                 "first-order action lag: time constant drawn in U(min, max) at reset [s]");
  table.add_real("action_lag_max", &time_constant_max, 0.0, kOptionHuge,
                 "largest action lag time constant [s], 0 for no lag");
  table.add_integer("action_delay", &delay_steps, 0, kMaxDelaySteps,
                    "steps between an action and its application");
  table.add_integer("action_delay_max", &delay_steps_max, 0, kMaxDelaySteps,
                    "largest delay drawn per episode in U{action_delay..max} [steps], 0 for "
                    "a fixed delay");
  table.add_rule([this] { return problem(); });
}

ActionLag::ActionLag(std::unique_ptr<Env> env, const ActionLagSettings& settings)
    : EnvWrapper(std::move(env), "ActionLag"), settings_(settings) {
  settings_.validate();
  const std::size_t size = env_->action_space().size();
  neutral_.resize(size);
  env_->neutral_action(neutral_);
  filtered_ = neutral_;
  delayed_ = neutral_;
  queue_.reserve(size * static_cast<std::size_t>(settings.largest_delay()));
}

void ActionLag::reset(std::optional<std::uint64_t> seed, std::span<float> observation) {
  if (seed) generator_.seed(derive_seed(*seed, kActionLagStream));
  time_constant_ = scale_ * uniform_between(generator_, settings_.time_constant_min,
                                            settings_.time_constant_max);
  const int drawn_delay =
      settings_.largest_delay() > settings_.delay_steps
          ? uniform_integer(generator_, settings_.delay_steps, settings_.largest_delay())
          : settings_.delay_steps;
  delay_ = static_cast<int>(std::lround(scale_ * drawn_delay));
  queue_.clear();
  for (int i = 0; i < delay_; ++i) queue_.insert(queue_.end(), neutral_.begin(), neutral_.end());
  head_ = 0;
  filtered_ = neutral_;
  env_->reset(seed, observation);
}

StepResult ActionLag::step(std::span<const float> action, std::span<float> observation) {
  const std::size_t size = neutral_.size();
  if (action.size() != size) {
    throw std::invalid_argument("ActionLag: action has " + std::to_string(action.size()) +
                                " components, expected " + std::to_string(size));
  }
  // Checked now, not when the action leaves the delay line. NaN is legal where the neutral
  // action has it (servo positions).
  for (std::size_t i = 0; i < size; ++i) {
    if (!std::isfinite(action[i]) && !(std::isnan(action[i]) && std::isnan(neutral_[i]))) {
      throw std::invalid_argument("action component " + action_space().names[i] + " is " +
                                  (std::isnan(action[i]) ? "NaN" : "infinite"));
    }
  }
  const float* input = action.data();
  if (delay_ > 0) {
    float* slot = queue_.data() + head_ * size;
    std::copy(slot, slot + size, delayed_.begin());
    std::copy(action.begin(), action.end(), slot);
    head_ = (head_ + 1) % static_cast<std::size_t>(delay_);
    input = delayed_.data();
  }
  if (time_constant_ > 0.0) {
    const float alpha = static_cast<float>(std::min(1.0, timestep() / time_constant_));
    for (std::size_t i = 0; i < size; ++i) {
      const float target = input[i];
      float& filtered = filtered_[i];
      filtered = std::isnan(target) || std::isnan(filtered)
                     ? target
                     : filtered + alpha * (target - filtered);
    }
    input = filtered_.data();
  }
  return env_->step(std::span<const float>(input, size), observation);
}

void ActionLag::set_randomization_scale(double scale) {
  check_randomization_scale(scale);
  env_->set_randomization_scale(scale);
  scale_ = scale;
}

}  // namespace upkie_rl
