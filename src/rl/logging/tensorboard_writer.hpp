#pragma once
/// @file
/// TensorBoard event files written by hand: records of length, masked CRC32C and a
/// serialised `Event` protobuf holding a `Summary` of scalar values.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace upkie_rl {

/// One scalar of a summary, e.g. {"train/loss", 0.12}.
struct ScalarValue {
  std::string tag;
  float value = 0.0f;
};

/// One decoded `Event` record.
struct TensorBoardEvent {
  double wall_time = 0.0;  ///< Seconds since the Unix epoch.
  std::int64_t step = 0;
  std::string file_version;  ///< Set in the first record only ("brain.Event:2").
  std::vector<ScalarValue> scalars;
};

/// Appends scalar summaries to a new `events.out.tfevents.<seconds>.<host>.<pid>.<n>` file.
class TensorBoardWriter {
 public:
  /// Creates the directory if needed and a new event file in it, starting with the
  /// file-version record. Throws std::runtime_error if the file cannot be created.
  explicit TensorBoardWriter(const std::filesystem::path& directory);

  /// Writes one event at `step` with every scalar of `scalars`; `wall_time` in seconds
  /// since the Unix epoch.
  void add_scalars(std::int64_t step, std::span<const ScalarValue> scalars, double wall_time);

  /// Flushes buffered records to the file.
  void flush();

  const std::filesystem::path& path() const { return path_; }

 private:
  void write_record(const std::string& data);

  std::filesystem::path path_;
  std::ofstream file_;
  std::string buffer_;  // reused serialisation buffer
};

/// Serialises an Event message (the protobuf bytes, without the record framing).
std::string encode_event(const TensorBoardEvent& event);

/// Largest event file read back: an update's scalars take under 1 KiB.
inline constexpr std::uintmax_t kMaxEventFileBytes = std::uintmax_t{1} << 30;

/// Reads every record of an event file (at most kMaxEventFileBytes, a regular file), checking both
/// CRCs of each. Throws std::runtime_error naming the file and the record on a bad CRC, a truncated
/// record or a malformed message.
std::vector<TensorBoardEvent> read_event_file(const std::filesystem::path& path);

}  // namespace upkie_rl
