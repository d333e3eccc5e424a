#include "rl/logging/tensorboard_writer.hpp"

#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include "base/input_file.hpp"
#include "policy/crc32c.hpp"
#include "rl/runs/run_file_error.hpp"

namespace upkie_rl {

namespace {

static_assert(std::endian::native == std::endian::little, "event files are little-endian");

// Protobuf wire types.
constexpr std::uint8_t kVarint = 0;
constexpr std::uint8_t kFixed64 = 1;
constexpr std::uint8_t kLengthDelimited = 2;
constexpr std::uint8_t kFixed32 = 5;

void put_varint(std::string& out, std::uint64_t value) {
  while (value >= 0x80) {
    out.push_back(static_cast<char>((value & 0x7F) | 0x80));
    value >>= 7;
  }
  out.push_back(static_cast<char>(value));
}

void put_tag(std::string& out, int field, std::uint8_t wire_type) {
  put_varint(out, (static_cast<std::uint64_t>(field) << 3) | wire_type);
}

template <typename T>
void put_fixed(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

void put_bytes(std::string& out, int field, const std::string& bytes) {
  put_tag(out, field, kLengthDelimited);
  put_varint(out, bytes.size());
  out += bytes;
}

std::string encode_summary(const std::vector<ScalarValue>& scalars) {
  std::string summary;
  std::string value;
  for (const ScalarValue& scalar : scalars) {
    value.clear();
    put_bytes(value, 1, scalar.tag);
    put_tag(value, 2, kFixed32);
    put_fixed(value, scalar.value);
    put_bytes(summary, 1, value);
  }
  return summary;
}

// A cursor over protobuf bytes that throws on anything truncated or malformed.
class Reader {
 public:
  explicit Reader(std::string_view data) : data_(data) {}
  bool done() const { return position_ >= data_.size(); }
  std::uint64_t varint() {
    std::uint64_t value = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      if (done()) throw RunFileError("truncated varint");
      const auto byte = static_cast<std::uint8_t>(data_[position_++]);
      value |= static_cast<std::uint64_t>(byte & 0x7F) << shift;
      if ((byte & 0x80) == 0) return value;
    }
    throw RunFileError("varint too long");
  }
  std::string_view bytes(std::size_t size) {
    if (size > data_.size() - position_) throw RunFileError("truncated field");
    std::string_view out = data_.substr(position_, size);
    position_ += size;
    return out;
  }
  template <typename T>
  T fixed() {
    T value;
    std::memcpy(&value, bytes(sizeof(T)).data(), sizeof(T));
    return value;
  }
  void skip(std::uint8_t wire_type) {
    switch (wire_type) {
      case kVarint:
        varint();
        break;
      case kFixed64:
        bytes(8);
        break;
      case kLengthDelimited:
        bytes(varint());
        break;
      case kFixed32:
        bytes(4);
        break;
      default:
        throw RunFileError("unsupported wire type " + std::to_string(wire_type));
    }
  }

 private:
  std::string_view data_;
  std::size_t position_ = 0;
};

ScalarValue decode_value(std::string_view data) {
  ScalarValue scalar;
  Reader reader(data);
  while (!reader.done()) {
    const std::uint64_t key = reader.varint();
    const auto wire_type = static_cast<std::uint8_t>(key & 7);
    const std::uint64_t field = key >> 3;
    if (field == 1 && wire_type == kLengthDelimited) {
      scalar.tag = std::string(reader.bytes(reader.varint()));
    } else if (field == 2 && wire_type == kFixed32) {
      scalar.value = reader.fixed<float>();
    } else {
      reader.skip(wire_type);
    }
  }
  return scalar;
}

TensorBoardEvent decode_event(std::string_view data) {
  TensorBoardEvent event;
  Reader reader(data);
  while (!reader.done()) {
    const std::uint64_t key = reader.varint();
    const auto wire_type = static_cast<std::uint8_t>(key & 7);
    const std::uint64_t field = key >> 3;
    if (field == 1 && wire_type == kFixed64) {
      event.wall_time = reader.fixed<double>();
    } else if (field == 2 && wire_type == kVarint) {
      event.step = static_cast<std::int64_t>(reader.varint());
    } else if (field == 3 && wire_type == kLengthDelimited) {
      event.file_version = std::string(reader.bytes(reader.varint()));
    } else if (field == 5 && wire_type == kLengthDelimited) {
      Reader summary(reader.bytes(reader.varint()));
      while (!summary.done()) {
        const std::uint64_t summary_key = summary.varint();
        const auto summary_wire = static_cast<std::uint8_t>(summary_key & 7);
        if ((summary_key >> 3) == 1 && summary_wire == kLengthDelimited) {
          event.scalars.push_back(decode_value(summary.bytes(summary.varint())));
        } else {
          summary.skip(summary_wire);
        }
      }
    } else {
      reader.skip(wire_type);
    }
  }
  return event;
}

std::string host_name() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "localhost";
  return name;
}

}  // namespace

std::string encode_event(const TensorBoardEvent& event) {
  std::string out;
  put_tag(out, 1, kFixed64);
  put_fixed(out, event.wall_time);
  if (event.step != 0) {
    put_tag(out, 2, kVarint);
    put_varint(out, static_cast<std::uint64_t>(event.step));
  }
  if (!event.file_version.empty()) put_bytes(out, 3, event.file_version);
  if (!event.scalars.empty()) put_bytes(out, 5, encode_summary(event.scalars));
  return out;
}

TensorBoardWriter::TensorBoardWriter(const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const std::string stem = "events.out.tfevents." + std::to_string(static_cast<std::int64_t>(now)) +
                           "." + host_name() + "." + std::to_string(getpid()) + ".";
  for (int n = 0;; ++n) {
    path_ = directory / (stem + std::to_string(n));
    if (!std::filesystem::exists(path_)) break;
  }
  file_.open(path_, std::ios::binary);
  if (!file_) throw RunFileError("cannot create event file " + path_.string());
  TensorBoardEvent first;
  first.wall_time = now;
  first.file_version = "brain.Event:2";
  write_record(encode_event(first));
  flush();
}

void TensorBoardWriter::add_scalars(std::int64_t step, std::span<const ScalarValue> scalars,
                                    double wall_time) {
  TensorBoardEvent event;
  event.wall_time = wall_time;
  event.step = step;
  event.scalars.assign(scalars.begin(), scalars.end());
  write_record(encode_event(event));
}

void TensorBoardWriter::flush() {
  file_.flush();
  if (!file_) throw RunFileError("cannot write event file " + path_.string());
}

void TensorBoardWriter::write_record(const std::string& data) {
  buffer_.clear();
  const std::uint64_t length = data.size();
  put_fixed(buffer_, length);
  put_fixed(buffer_, mask_crc32c(crc32c(std::string_view(buffer_.data(), 8))));
  buffer_ += data;
  put_fixed(buffer_, mask_crc32c(crc32c(data)));
  file_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
}

std::vector<TensorBoardEvent> read_event_file(const std::filesystem::path& path) {
  const std::string content =
      read_input_file<std::runtime_error>(path, "event file", kMaxEventFileBytes);
  std::vector<TensorBoardEvent> events;
  std::size_t position = 0;
  while (position < content.size()) {
    const std::string where = path.string() + ": record " + std::to_string(events.size()) +
                              " at byte " + std::to_string(position);
    if (content.size() - position < 12) throw RunFileError(where + ": truncated header");
    std::uint64_t length;
    std::uint32_t length_crc;
    std::memcpy(&length, content.data() + position, 8);
    std::memcpy(&length_crc, content.data() + position + 8, 4);
    if (mask_crc32c(crc32c(std::string_view(content.data() + position, 8))) != length_crc) {
      throw RunFileError(where + ": bad length CRC");
    }
    position += 12;
    if (length > content.size() - position || content.size() - position - length < 4) {
      throw RunFileError(where + ": truncated data");
    }
    const std::string_view data(content.data() + position, length);
    std::uint32_t data_crc;
    std::memcpy(&data_crc, content.data() + position + length, 4);
    if (mask_crc32c(crc32c(data)) != data_crc) throw RunFileError(where + ": bad data CRC");
    position += length + 4;
    try {
      events.push_back(decode_event(data));
    } catch (const std::runtime_error& error) {
      throw RunFileError(where + ": malformed event: " + error.what());
    }
  }
  return events;
}

}  // namespace upkie_rl
