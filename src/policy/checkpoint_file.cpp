#include "policy/checkpoint_file.hpp"

#include <bit>
#include <cstring>
#include <iterator>
#include <limits>

#include "base/atomic_file.hpp"
#include "base/bounded_json.hpp"
#include "base/input_file.hpp"
#include "policy/crc32c.hpp"
#include "policy/model_format.hpp"

namespace upkie_rl {

namespace {

static_assert(std::endian::native == std::endian::little, "checkpoints are little-endian");

constexpr char kMagic[8] = {'U', 'P', 'K', 'I', 'E', 'R', 'L', '1'};

template <typename T>
void append(std::string& out, const T& value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

/// Number of values of `shape`; throws naming the tensor on a negative size.
std::int64_t count_values(const std::vector<std::int64_t>& shape, const std::string& name,
                          const std::string& where) {
  std::int64_t numel = 1;
  for (std::int64_t size : shape) {
    if (size < 0) throw CheckpointError(where + ": negative size in tensor '" + name + "'");
    if (size > 0 && numel > std::numeric_limits<std::int64_t>::max() / size) {
      throw CheckpointError(where + ": tensor '" + name + "' is too large");
    }
    numel *= size;
  }
  return numel;
}

}  // namespace

const FloatTensor& CheckpointFile::tensor(const std::string& name, std::int64_t numel) const {
  return find_tensor(tensors, name, numel, [](const FloatTensor& tensor) {
    return static_cast<std::int64_t>(tensor.values.size());
  });
}

void write_checkpoint_file(const CheckpointFile& file, const std::filesystem::path& path) {
  nlohmann::json header = file.header;
  nlohmann::json table = nlohmann::json::array();
  std::string data;
  for (const auto& [name, tensor] : file.tensors) {
    if (count_values(tensor.shape, name, "checkpoint " + path.string()) !=
        static_cast<std::int64_t>(tensor.values.size())) {
      throw CheckpointError("checkpoint " + path.string() + ": tensor '" + name +
                            "' has values that do not match its shape");
    }
    table.push_back({{"name", name}, {"shape", tensor.shape}});
    data.append(reinterpret_cast<const char*>(tensor.values.data()),
                tensor.values.size() * sizeof(float));
  }
  header["tensors"] = table;
  const std::string header_text = header.dump();
  std::string bytes(kMagic, sizeof(kMagic));
  append(bytes, static_cast<std::uint64_t>(header_text.size()));
  bytes += header_text;
  bytes += data;
  append(bytes, crc32c(bytes));

  write_file_atomically<CheckpointError>(path, bytes);
}

CheckpointFile read_checkpoint_file(const std::filesystem::path& path) {
  const std::string bytes =
      read_input_file<CheckpointError>(path, "checkpoint", kMaxCheckpointBytes);
  // An export or an SB3 zip gets what to run instead rather than "bad magic" (a checkpoint
  // under any name still loads).
  const bool has_magic =
      bytes.size() >= sizeof(kMagic) && std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) == 0;
  const std::string refusal = has_magic ? std::string() : model_format_refusal(path);
  if (!refusal.empty()) throw CheckpointError(refusal);
  return parse_checkpoint_bytes(bytes, "checkpoint " + path.string());
}

CheckpointFile parse_checkpoint_bytes(std::string_view bytes, const std::string& where) {
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    throw CheckpointError(where + ": not an upkie-rl checkpoint (bad magic)");
  }
  if (bytes.size() < sizeof(kMagic) + 8 + 4) throw CheckpointError(where + ": truncated");
  std::uint32_t stored_crc;
  std::memcpy(&stored_crc, bytes.data() + bytes.size() - 4, 4);
  if (crc32c(std::string_view(bytes.data(), bytes.size() - 4)) != stored_crc) {
    throw CheckpointError(where + ": truncated or corrupted (CRC mismatch)");
  }
  std::uint64_t header_size;
  std::memcpy(&header_size, bytes.data() + sizeof(kMagic), 8);
  const std::size_t header_begin = sizeof(kMagic) + 8;
  if (header_size > bytes.size() - header_begin - 4) {
    throw CheckpointError(where + ": header size exceeds the file");
  }
  if (header_size > kMaxCheckpointHeaderBytes) {
    throw CheckpointError(where + ": header of " + std::to_string(header_size) +
                          " bytes exceeds the limit of " +
                          std::to_string(kMaxCheckpointHeaderBytes));
  }
  CheckpointFile file;
  try {
    file.header = parse_bounded_json(bytes.substr(header_begin, header_size), "header");
  } catch (const std::invalid_argument& error) {
    throw CheckpointError(where + ": " + error.what());
  }
  if (!file.header.is_object()) throw CheckpointError(where + ": header is not a JSON object");
  try {
    std::size_t position = header_begin + header_size;
    const std::size_t end = bytes.size() - 4;
    for (const auto& entry : file.header.at("tensors")) {
      const auto name = entry.at("name").get<std::string>();
      FloatTensor tensor;
      tensor.shape = entry.at("shape").get<std::vector<std::int64_t>>();
      const auto numel = static_cast<std::size_t>(count_values(tensor.shape, name, where));
      if (numel > (end - position) / sizeof(float)) {
        throw CheckpointError(where + ": tensor '" + name + "' exceeds the file");
      }
      tensor.values.resize(numel);
      // An empty tensor's vector has no storage: memcpy takes no null pointer, even for 0 bytes.
      if (numel != 0) {
        std::memcpy(tensor.values.data(), bytes.data() + position, numel * sizeof(float));
      }
      position += numel * sizeof(float);
      file.tensors[name] = std::move(tensor);
    }
    if (position != end) throw CheckpointError(where + ": unexpected bytes after the tensors");
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(where + ": malformed header: " + error.what());
  }
  file.header.erase("tensors");
  return file;
}

}  // namespace upkie_rl
