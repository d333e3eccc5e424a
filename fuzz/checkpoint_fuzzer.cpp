/// @file
/// libFuzzer target: the checkpoint gate past the CRC. Each input is a checkpoint file
/// without its last four bytes; the target appends the CRC32C of the input, so that every
/// mutation reaches the header parser, the tensor table and the content checks instead of
/// stopping at the checksum. Whatever the gate accepts must load as a deployed policy and
/// act, on an observation inside the range the gate checks, with a finite action (a
/// PolicyOutputError there is a bug: the gate let through weights that overflow).
/// Refusing with CheckpointError is the expected outcome.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "policy/checkpoint_gate.hpp"
#include "policy/crc32c.hpp"
#include "policy/deployed_policy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::uint32_t crc = upkie_rl::crc32c(bytes);
  bytes.append(reinterpret_cast<const char*>(&crc), sizeof(crc));
  try {
    const upkie_rl::CheckpointFile file = upkie_rl::parse_checkpoint_bytes(bytes, "input");
    upkie_rl::DeployedPolicy policy = upkie_rl::DeployedPolicy::from_checkpoint(file, "input");
    // Inside the observation bounds where they are finite, zero elsewhere.
    const upkie_rl::BoxSpace& space = policy.observation_space();
    std::vector<float> observation(space.size(), 0.0f);
    for (std::size_t i = 0; i < space.size(); ++i) {
      if (std::isfinite(space.low[i]) && std::isfinite(space.high[i])) {
        observation[i] = 0.5f * space.low[i] + 0.5f * space.high[i];
      }
    }
    std::vector<float> action(policy.action_space().size());
    policy.act(observation, action);
    for (float value : action) {
      if (!std::isfinite(value)) std::abort();
    }
  } catch (const upkie_rl::CheckpointError&) {
  }
  return 0;
}
