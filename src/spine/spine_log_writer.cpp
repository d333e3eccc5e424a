#include "spine/spine_log_writer.hpp"

#include <cstring>
#include <string>

#include "sim/msgpack_float64.hpp"
#include "sim/observation_dict.hpp"
#include "spine/servo_action_message.hpp"

namespace upkie_rl {

namespace {

void pack_key(msgpack::packer<msgpack::sbuffer>& packer, const char* key) {
  const auto size = static_cast<uint32_t>(std::strlen(key));
  packer.pack_str(size);
  packer.pack_str_body(key, size);
}

}  // namespace

SpineLogWriter::SpineLogWriter(const std::filesystem::path& path)
    : path_(path), file_(std::fopen(path.c_str(), "wb")) {
  if (file_ == nullptr) throw RobotLogError("cannot write the spine log " + path.string());
}

SpineLogWriter::~SpineLogWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void SpineLogWriter::write(const Observation& observation, const ServoAction& action) {
  if (file_ == nullptr) throw RobotLogError("spine log " + path_.string() + " is closed");
  buffer_.clear();
  msgpack::packer<msgpack::sbuffer> packer(buffer_);
  packer.pack_map(3);  // keys in byte-wise order, as the spine's maps
  pack_key(packer, kSpineLogActionKey);
  write_servo_action_msgpack(action, action_buffer_);
  buffer_.write(action_buffer_.data(), action_buffer_.size());
  pack_key(packer, kSpineLogObservationKey);
  pack_observation(observation, buffer_);
  pack_key(packer, kSpineLogTimeKey);
  pack_float64(buffer_, observation.time);
  if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size()) {
    throw RobotLogError("error writing the spine log " + path_.string());
  }
}

void SpineLogWriter::close() {
  if (file_ == nullptr) return;
  const bool failed = std::fflush(file_) != 0 || std::ferror(file_) != 0;
  const bool close_failed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || close_failed) throw RobotLogError("error writing the spine log " + path_.string());
}

}  // namespace upkie_rl
