#include "envs/episode_recorder.hpp"

#include <limits>
#include <stdexcept>

#include "envs/velocity_env.hpp"

namespace upkie_rl {

EpisodeRecorder::EpisodeRecorder(const std::filesystem::path& path)
    : path_(path), out_(path, std::ios::out | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write the record file " + path.string());
  out_.precision(9);
}

void EpisodeRecorder::write_header(const Env& env, std::span<const std::string> extra_columns) {
  out_ << "episode,step,t";
  for (const std::string& name : env.observation_space().names) out_ << ',' << name;
  for (const std::string& name : env.action_space().names) out_ << ",action." << name;
  out_ << ",reward,terminated,truncated";
  for (const char* column : kGroundTruthColumns) out_ << ',' << column;
  for (const auto& joint : kServoNames) out_ << ',' << joint;
  for (const char* column : kMeasuredColumns) out_ << ',' << column;
  velocity_task_ = find_velocity_env(env) != nullptr;
  if (velocity_task_) {
    for (const char* column : kMeasuredVelocityColumns) out_ << ',' << column;
  }
  for (const std::string& column : extra_columns) out_ << ',' << column;
  out_ << '\n';
  num_extra_columns_ = extra_columns.size();
  if (!out_) throw std::runtime_error("cannot write the record file " + path_.string());
  observation_.resize(env.observation_space().size());
}

void EpisodeRecorder::before_step(const Env& env, std::span<const float> observation) {
  std::copy(observation.begin(), observation.end(), observation_.begin());
  const Observation* full = env.full_observation();
  time_ = full ? full->time : std::numeric_limits<double>::quiet_NaN();
  if (full && full->has_sim) {
    const SimBaseObservation& base = full->sim_base;
    ground_truth_ = {base.position.x(),    base.position.y(),    base.position.z(),
                     base.orientation.w(), base.orientation.x(), base.orientation.y(),
                     base.orientation.z()};
    for (std::size_t i = 0; i < kNumServos; ++i) ground_truth_[7 + i] = full->servo[i].position;
  } else {
    ground_truth_.fill(std::numeric_limits<double>::quiet_NaN());
  }
  if (full) {
    ground_truth_[7 + kNumServos] = full->base_orientation.pitch;
    ground_truth_[8 + kNumServos] = full->wheel_odometry.position;
  }
  const VelocityEnv* velocity = velocity_task_ ? find_velocity_env(env) : nullptr;
  if (velocity != nullptr) {
    const BaseVelocity measured = velocity->measured_velocity();
    measured_velocity_ = {measured.forward_velocity, measured.yaw_rate};
  }
}

void EpisodeRecorder::after_step(int episode, int step, std::span<const float> action,
                                 const StepResult& result, std::span<const double> extra) {
  if (extra.size() != num_extra_columns_) {
    throw std::invalid_argument("EpisodeRecorder: " + std::to_string(extra.size()) +
                                " extra values for " + std::to_string(num_extra_columns_) +
                                " extra columns");
  }
  out_ << episode << ',' << step << ',' << time_;
  for (float value : observation_) out_ << ',' << value;
  for (float value : action) out_ << ',' << value;
  out_ << ',' << result.reward << ',' << int(result.terminated) << ',' << int(result.truncated);
  for (double value : ground_truth_) out_ << ',' << value;
  if (velocity_task_) {
    for (double value : measured_velocity_) out_ << ',' << value;
  }
  for (double value : extra) out_ << ',' << value;
  out_ << '\n';
}

void EpisodeRecorder::close() {
  out_.flush();
  if (!out_) throw std::runtime_error("error writing the record file " + path_.string());
  out_.close();
}

}  // namespace upkie_rl
