#include "rl/checkpoint.hpp"

#include <unistd.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>

#include "rl/crc32c.hpp"

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

}  // namespace

const torch::Tensor& Checkpoint::tensor(const std::string& name, std::int64_t numel) const {
  const auto found = tensors.find(name);
  if (found == tensors.end()) throw CheckpointError("checkpoint has no tensor '" + name + "'");
  if (numel >= 0 && found->second.numel() != numel) {
    throw CheckpointError("checkpoint tensor '" + name + "' has " +
                          std::to_string(found->second.numel()) + " values, expected " +
                          std::to_string(numel));
  }
  return found->second;
}

void save_checkpoint(const Checkpoint& checkpoint, const std::filesystem::path& path) {
  nlohmann::json header = checkpoint.header;
  nlohmann::json table = nlohmann::json::array();
  std::string data;
  for (const auto& [name, tensor] : checkpoint.tensors) {
    const torch::Tensor values = tensor.detach().to(torch::kFloat32).contiguous();
    table.push_back({{"name", name}, {"shape", values.sizes().vec()}});
    data.append(reinterpret_cast<const char*>(values.data_ptr<float>()),
                static_cast<std::size_t>(values.numel()) * sizeof(float));
  }
  header["tensors"] = table;
  const std::string header_text = header.dump();
  std::string bytes(kMagic, sizeof(kMagic));
  append(bytes, static_cast<std::uint64_t>(header_text.size()));
  bytes += header_text;
  bytes += data;
  append(bytes, crc32c(bytes));

  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  const std::filesystem::path temporary = path.string() + ".tmp." + std::to_string(getpid());
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    if (!file) throw CheckpointError("cannot create " + temporary.string());
    file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    file.flush();
    if (!file) throw CheckpointError("cannot write " + temporary.string());
  }
  // Flush to disk before the rename so a crash cannot leave a renamed, empty file.
  if (FILE* handle = std::fopen(temporary.c_str(), "rb")) {
    fsync(fileno(handle));
    std::fclose(handle);
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary);
    throw CheckpointError("cannot rename " + temporary.string() + " to " + path.string() + ": " +
                          error.message());
  }
}

Checkpoint load_checkpoint(const std::filesystem::path& path) {
  const std::string where = "checkpoint " + path.string();
  std::ifstream file(path, std::ios::binary);
  if (!file) throw CheckpointError(where + ": cannot open file");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
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
  Checkpoint checkpoint;
  try {
    checkpoint.header = nlohmann::json::parse(bytes.substr(header_begin, header_size));
    std::size_t position = header_begin + header_size;
    const std::size_t end = bytes.size() - 4;
    for (const auto& entry : checkpoint.header.at("tensors")) {
      const auto name = entry.at("name").get<std::string>();
      const auto shape = entry.at("shape").get<std::vector<std::int64_t>>();
      std::int64_t numel = 1;
      for (std::int64_t size : shape) {
        if (size < 0) throw CheckpointError(where + ": negative size in tensor '" + name + "'");
        numel *= size;
      }
      const std::size_t size = static_cast<std::size_t>(numel) * sizeof(float);
      if (size > end - position) {
        throw CheckpointError(where + ": tensor '" + name + "' exceeds the file");
      }
      torch::Tensor tensor = torch::empty(shape, torch::kFloat32);
      std::memcpy(tensor.data_ptr<float>(), bytes.data() + position, size);
      position += size;
      checkpoint.tensors[name] = tensor;
    }
    if (position != end) throw CheckpointError(where + ": unexpected bytes after the tensors");
  } catch (const nlohmann::json::exception& error) {
    throw CheckpointError(where + ": malformed header: " + error.what());
  }
  checkpoint.header.erase("tensors");
  return checkpoint;
}

}  // namespace upkie_rl
