#include "envs/records/episode_recorder.hpp"

#include <limits>
#include <stdexcept>

#include "envs/kinds/velocity_env.hpp"
#include "envs/records/record_file_error.hpp"

namespace upkie_rl {

EpisodeRecorder::EpisodeRecorder(const std::filesystem::path& path)
    : path_(path), out_(path, std::ios::out | std::ios::trunc) {
  if (!out_) throw RecordFileError("cannot write the record file " + path.string());
  out_.precision(9);
}

void EpisodeRecorder::write_header(const Env& env, std::span<const std::string> extra_columns) {
  out_ << kEpisodeColumn << ',' << kStepColumn << ',' << kTimeColumn;
  for (const std::string& name : env.observation_space().names) out_ << ',' << name;
  for (const std::string& name : env.action_space().names) {
    out_ << ',' << kActionColumnPrefix << name;
  }
  out_ << ',' << kRewardColumn << ',' << kTerminatedColumn << ',' << kTruncatedColumn;
  const auto column_name = [&](auto column, auto&) { out_ << ',' << column; };
  visit_pose_columns(pose_, column_name);
  visit_measurement_columns(measurement_, column_name);
  velocity_task_ = find_velocity_env(env) != nullptr;
  if (velocity_task_) visit_measured_velocity_columns(measured_velocity_, column_name);
  for (const std::string& column : extra_columns) out_ << ',' << column;
  out_ << '\n';
  num_extra_columns_ = extra_columns.size();
  if (!out_) throw RecordFileError("cannot write the record file " + path_.string());
  observation_.resize(env.observation_space().size());
}

void EpisodeRecorder::before_step(const Env& env, std::span<const float> observation) {
  std::copy(observation.begin(), observation.end(), observation_.begin());
  const Observation* full = env.full_observation();
  time_ = full ? full->time : std::numeric_limits<double>::quiet_NaN();
  const auto set_nan = [](auto, double& value) {
    value = std::numeric_limits<double>::quiet_NaN();
  };
  if (full && full->has_sim) {
    pose_.base_position = full->sim_base.position;
    pose_.base_orientation = full->sim_base.orientation;
    for (std::size_t i = 0; i < kNumServos; ++i) pose_.joint_angles[i] = full->servo[i].position;
  } else {
    visit_pose_columns(pose_, set_nan);
  }
  if (full) {
    measurement_.pitch = full->base_orientation.pitch;
    measurement_.ground_position = full->wheel_odometry.position;
  } else {
    visit_measurement_columns(measurement_, set_nan);
  }
  const VelocityEnv* velocity = velocity_task_ ? find_velocity_env(env) : nullptr;
  if (velocity != nullptr) measured_velocity_ = velocity->measured_velocity();
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
  const auto column_value = [&](auto, double value) { out_ << ',' << value; };
  visit_pose_columns(pose_, column_value);
  visit_measurement_columns(measurement_, column_value);
  if (velocity_task_) visit_measured_velocity_columns(measured_velocity_, column_value);
  for (double value : extra) out_ << ',' << value;
  out_ << '\n';
}

void EpisodeRecorder::close() {
  out_.flush();
  if (!out_) throw RecordFileError("error writing the record file " + path_.string());
  out_.close();
}

}  // namespace upkie_rl
