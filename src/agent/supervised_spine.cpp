#include "agent/supervised_spine.hpp"

#include <spdlog/spdlog.h>

#include "spine/spine_error.hpp"

namespace upkie_rl {

SupervisedSpine::SupervisedSpine(std::unique_ptr<SpineBackend> spine, Supervisor& supervisor,
                                 bool dry_run)
    : spine_(std::move(spine)), supervisor_(supervisor), dry_run_(dry_run) {}

const Observation& SupervisedSpine::reset(const ResetState& state) {
  const Observation& observation = spine_->reset(state);
  supervisor_.check_observation(observation);
  supervisor_.reset_commands(observation);
  stop_ = supervisor_.stop_action(observation);
  intended_ = stop_;
  return observation;
}

const Observation& SupervisedSpine::step(const ServoAction& action) {
  intended_ = action;
  supervisor_.limit_commands(intended_);
  const Observation& observation = spine_->step(dry_run_ ? stop_ : intended_);
  supervisor_.check_observation(observation);
  return observation;
}

int SupervisedSpine::send_stop_commands(int nb_stop_cycles, const std::atomic<bool>& cut_short) {
  const ServoAction stop = supervisor_.stop_action(spine_->observation());
  int answered = 0;
  try {
    for (; answered < nb_stop_cycles && !cut_short.load(); ++answered) spine_->step(stop);
    spine_->stop();
  } catch (const SpineError& error) {
    spdlog::warn("stopping: the spine did not take the stop commands ({}); writing Stop",
                 error.what());
    spine_->force_stop();
  }
  return answered;
}

}  // namespace upkie_rl
