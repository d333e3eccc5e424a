#include "rl/checkpoint.hpp"

namespace upkie_rl {

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
  CheckpointFile file;
  file.header = checkpoint.header;
  for (const auto& [name, tensor] : checkpoint.tensors) {
    const torch::Tensor values = tensor.detach().to(torch::kFloat32).contiguous();
    const float* data = values.data_ptr<float>();
    file.tensors[name] = {values.sizes().vec(), std::vector<float>(data, data + values.numel())};
  }
  write_checkpoint_file(file, path);
}

Checkpoint load_checkpoint(const std::filesystem::path& path) {
  CheckpointFile file = read_checkpoint_file(path);
  Checkpoint checkpoint;
  checkpoint.header = std::move(file.header);
  for (auto& [name, tensor] : file.tensors) {
    checkpoint.tensors[name] =
        torch::from_blob(tensor.values.data(), tensor.shape, torch::kFloat32).clone();
  }
  return checkpoint;
}

}  // namespace upkie_rl
