#include "rl/distributed/rank_agreement.hpp"

#include <torch/version.h>

#include <algorithm>
#include <sstream>

#include "policy/checkpoint_gate.hpp"

namespace upkie_rl {

namespace {

/// `text` from `root` to every rank, as one int32 per byte (a type every backend reduces).
std::string broadcast_text(const std::string& text, int root, Communicator& communicator) {
  torch::Tensor length = torch::tensor({static_cast<std::int64_t>(text.size())}, torch::kInt64);
  communicator.broadcast(length, root);
  torch::Tensor bytes = torch::zeros({length.item<std::int64_t>()}, torch::kInt32);
  if (communicator.rank() == root) {
    auto* data = bytes.data_ptr<std::int32_t>();
    for (std::size_t i = 0; i < text.size(); ++i) data[i] = static_cast<unsigned char>(text[i]);
  }
  communicator.broadcast(bytes, root);
  std::string received(static_cast<std::size_t>(bytes.numel()), '\0');
  const auto* data = bytes.data_ptr<std::int32_t>();
  for (std::size_t i = 0; i < received.size(); ++i) received[i] = static_cast<char>(data[i]);
  return received;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  return lines;
}

std::string key_of(const std::string& line) { return line.substr(0, line.find(": ")); }

std::string value_of(const std::string& line) {
  const auto colon = line.find(": ");
  return colon == std::string::npos ? "(absent)" : line.substr(colon + 2);
}

/// The first setting of `theirs` that differs from `ours`, as a message; "" if none.
std::string first_difference(const std::vector<std::string>& ours,
                             const std::vector<std::string>& theirs, int rank) {
  for (std::size_t i = 0; i < std::max(ours.size(), theirs.size()); ++i) {
    const std::string mine = i < ours.size() ? ours[i] : "(absent): (absent)";
    const std::string other = i < theirs.size() ? theirs[i] : "(absent): (absent)";
    if (mine == other) continue;
    const std::string key =
        key_of(mine) == key_of(other) ? key_of(mine) : key_of(mine) + " / " + key_of(other);
    return "the ranks disagree: " + key + " is " + value_of(mine) + " on rank 0 but " +
           value_of(other) + " on rank " + std::to_string(rank) +
           "; start every rank with the same configuration and build";
  }
  return "";
}

}  // namespace

std::vector<std::string> agreement_settings(const TrainingConfig& config) {
  std::vector<std::string> settings;
  std::string section;
  for (const std::string& line : split_lines(to_yaml(config))) {
    // Dotted keys from the YAML's two levels of sections (env, env.options, ppo, ...).
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos) continue;
    const std::string body = line.substr(indent);
    const std::size_t depth = indent / 2;
    std::vector<std::string> parts;
    std::istringstream path(section);
    for (std::string part; std::getline(path, part, '.') && parts.size() < depth;) {
      parts.push_back(part);
    }
    std::string prefix;
    for (const std::string& part : parts) prefix += part + ".";
    if (body.back() == ':' || body.ends_with(": {}")) {
      section = prefix + body.substr(0, body.find(':'));
      continue;
    }
    settings.push_back(prefix + body);
  }
  settings.push_back("checkpoint format version: " + std::to_string(kCheckpointVersion));
  settings.push_back(std::string("libtorch version: ") + TORCH_VERSION);
  return settings;
}

void check_ranks_agree(const std::vector<std::string>& settings, Communicator& communicator) {
  if (communicator.world_size() <= 1) return;
  std::string text;
  for (const std::string& line : settings) text += line + "\n";
  std::vector<std::vector<std::string>> every_rank;
  for (int root = 0; root < communicator.world_size(); ++root) {
    every_rank.push_back(split_lines(broadcast_text(text, root, communicator)));
  }
  for (int rank = 1; rank < communicator.world_size(); ++rank) {
    const std::string difference = first_difference(every_rank[0], every_rank[rank], rank);
    if (!difference.empty()) throw DistributedError(difference);
  }
}

}  // namespace upkie_rl
