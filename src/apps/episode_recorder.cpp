#include "apps/episode_recorder.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "sim/base_observer.hpp"

namespace upkie_rl::apps {

EpisodeRecorder::EpisodeRecorder(const std::filesystem::path& path)
    : path_(path), out_(path, std::ios::out | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write the record file " + path.string());
  out_.precision(9);
}

void EpisodeRecorder::write_header(const Env& env) {
  out_ << "episode,step,t";
  for (const std::string& name : env.observation_space().names) out_ << ',' << name;
  for (const std::string& name : env.action_space().names) out_ << ",action." << name;
  out_ << ",reward,terminated,truncated";
  for (const char* column : kGroundTruthColumns) out_ << ',' << column;
  for (const auto& joint : kServoNames) out_ << ',' << joint;
  for (const char* column : kMeasuredColumns) out_ << ',' << column;
  out_ << '\n';
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
}

void EpisodeRecorder::after_step(int episode, int step, std::span<const float> action,
                                 const StepResult& result) {
  out_ << episode << ',' << step << ',' << time_;
  for (float value : observation_) out_ << ',' << value;
  for (float value : action) out_ << ',' << value;
  out_ << ',' << result.reward << ',' << int(result.terminated) << ',' << int(result.truncated);
  for (double value : ground_truth_) out_ << ',' << value;
  out_ << '\n';
}

void EpisodeRecorder::close() {
  out_.flush();
  if (!out_) throw std::runtime_error("error writing the record file " + path_.string());
  out_.close();
}

namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream stream(line);
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

double parse_number(const std::string& text, const std::filesystem::path& path, long line,
                    const std::string& column) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": column " + column +
                             " is not a number: \"" + text + "\"");
  }
  return value;
}

}  // namespace

RecordFile read_record_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the record file " + path.string());
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path.string() + " is empty");
  const std::vector<std::string> header = split_fields(line);
  std::unordered_map<std::string, std::size_t> column_of;
  for (std::size_t i = 0; i < header.size(); ++i) column_of[header[i]] = i;
  std::vector<std::string> needed = {"episode", "step", "t", "reward"};
  needed.insert(needed.end(), kGroundTruthColumns.begin(), kGroundTruthColumns.end());
  for (const auto& joint : kServoNames) needed.emplace_back(joint);
  const std::size_t num_required = needed.size();
  const bool has_measured =
      column_of.count(kMeasuredColumns[0]) && column_of.count(kMeasuredColumns[1]);
  if (has_measured) needed.insert(needed.end(), kMeasuredColumns.begin(), kMeasuredColumns.end());
  RecordFile file;
  const std::string action_prefix = "action.";
  for (const std::string& column : header) {
    if (column.rfind(action_prefix, 0) == 0) {
      file.action_names.push_back(column.substr(action_prefix.size()));
      needed.push_back(column);
    }
  }
  std::vector<std::size_t> index;
  for (const std::string& name : needed) {
    const auto found = column_of.find(name);
    if (found == column_of.end()) {
      throw std::runtime_error(path.string() + ": no column \"" + name +
                               "\" in its header; is it a file of `upkie-rl rollout --record`?");
    }
    index.push_back(found->second);
  }

  long line_number = 1;
  std::vector<double> values(needed.size());
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string at = path.string() + ":" + std::to_string(line_number) + ": ";
    const std::vector<std::string> fields = split_fields(line);
    if (fields.size() != header.size()) {
      throw std::runtime_error(at + std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(header.size()) + " (truncated file?)");
    }
    for (std::size_t i = 0; i < needed.size(); ++i) {
      values[i] = parse_number(fields[index[i]], path, line_number, needed[i]);
    }
    if (std::isnan(values[4])) {
      throw std::runtime_error(at + "no ground truth (a spine run has no simulator pose to draw)");
    }
    RecordedStep step;
    if (!(values[0] >= 0.0 && values[0] < 1e9 && values[1] >= 0.0 && values[1] < 1e9) ||
        values[0] != std::floor(values[0]) || values[1] != std::floor(values[1])) {
      throw std::runtime_error(at + "episode and step must be whole numbers >= 0");
    }
    step.episode = static_cast<int>(values[0]);
    step.step = static_cast<int>(values[1]);
    step.time = values[2];
    step.reward = values[3];
    step.pose.base_position = Eigen::Vector3d(values[4], values[5], values[6]);
    step.pose.base_orientation = Eigen::Quaterniond(values[7], values[8], values[9], values[10]);
    for (std::size_t servo = 0; servo < kNumServos; ++servo) {
      step.pose.joint_angles[servo] = values[11 + servo];
    }
    if (!std::isfinite(step.time) || !step.pose.base_position.allFinite() ||
        !step.pose.base_orientation.coeffs().allFinite() ||
        step.pose.base_orientation.norm() < 1e-9) {
      throw std::runtime_error(at + "the time or the base pose is not finite");
    }
    if (!file.steps.empty() && file.steps.back().episode == step.episode &&
        step.time < file.steps.back().time) {
      throw std::runtime_error(at + "time goes back within episode " +
                               std::to_string(step.episode));
    }
    std::size_t next = num_required;
    if (has_measured) {
      step.pitch = values[next++];
      step.ground_position = values[next++];
    } else {
      step.pitch = base_pitch(step.pose.base_orientation.normalized());
      step.ground_position = step.pose.base_position.x();
    }
    step.action.assign(values.begin() + static_cast<std::ptrdiff_t>(next), values.end());
    file.steps.push_back(std::move(step));
  }
  if (file.steps.empty()) throw std::runtime_error(path.string() + " has a header but no rows");
  return file;
}

}  // namespace upkie_rl::apps
