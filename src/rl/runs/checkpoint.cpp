#include "rl/runs/checkpoint.hpp"

#include "policy/checkpoint_gate.hpp"

namespace upkie_rl {

const torch::Tensor& Checkpoint::tensor(const std::string& name, std::int64_t numel) const {
  return find_tensor(tensors, name, numel,
                     [](const torch::Tensor& tensor) { return tensor.numel(); });
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
  CheckpointFile file = read_checked_checkpoint(path);
  Checkpoint checkpoint;
  checkpoint.header = std::move(file.header);
  for (auto& [name, tensor] : file.tensors) {
    checkpoint.tensors[name] =
        torch::from_blob(tensor.values.data(), tensor.shape, torch::kFloat32).clone();
  }
  return checkpoint;
}

}  // namespace upkie_rl
