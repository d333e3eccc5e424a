/// @file
/// libFuzzer target: the spine server's cycle under arbitrary agents. An input is a
/// sequence of records [request code: 1 byte][payload size: 2 bytes, little-endian]
/// [payload]; for each record the "agent" writes the payload and the request word into
/// the shared memory, then the server runs a few cycles. Whatever the records, the server
/// must neither crash nor let an exception out of cycle(), and must stay in a valid state.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "spine/spine_server.hpp"

namespace {

/// No physics: echoes commands, which is all the server needs from a simulation.
class EchoSimulation final : public upkie_rl::Simulation {
 public:
  const upkie_rl::Observation& reset(const upkie_rl::ResetState& state) override {
    observation_ = {};
    for (std::size_t i = 0; i < upkie_rl::kNumServos; ++i) {
      observation_.servo[i].position = state.joint_configuration[i];
    }
    return observation_;
  }
  const upkie_rl::Observation& step(const upkie_rl::ServoAction& action) override {
    observation_.time += 0.005;
    for (std::size_t i = 0; i < upkie_rl::kNumServos; ++i) {
      observation_.servo[i].velocity = action[i].velocity;
    }
    return observation_;
  }
  const upkie_rl::Observation& observation() const override { return observation_; }
  double agent_timestep() const override { return 0.005; }

 private:
  upkie_rl::Observation observation_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string name = "/upkie_rl_fuzz_" + std::to_string(::getpid());
  EchoSimulation simulation;
  upkie_rl::SpineServerConfig config;
  config.shm_name = name;
  config.shm_size = 64 * 1024;
  config.real_time = (size > 0 && (data[0] & 1) != 0);
  // Gains reaching the simulation must have been validated: anything else is a bug.
  const auto set_settings = [](const upkie_rl::SpineStartSettings& settings) {
    const upkie_rl::ServoGains& gains = settings.servo_gains;
    if (!(std::isfinite(gains.kp) && gains.kp >= 0.0 && std::isfinite(gains.kd) &&
          gains.kd >= 0.0)) {
      std::abort();
    }
  };
  upkie_rl::SpineServer server(simulation, config, {}, set_settings);
  upkie_rl::SharedMemory agent = upkie_rl::SharedMemory::open(name);

  std::size_t offset = size > 0 ? 1 : 0;
  while (offset + 3 <= size) {
    const std::uint8_t code = data[offset];
    std::size_t length = data[offset + 1] | (std::size_t{data[offset + 2]} << 8);
    offset += 3;
    if (length > size - offset) length = size - offset;
    if (length > agent.max_payload_size()) length = agent.max_payload_size();
    agent.write_payload({reinterpret_cast<const char*>(data + offset), length});
    offset += length;
    // Codes 0..7 cover the protocol and beyond; larger bytes map to arbitrary words.
    const std::uint32_t request = code < 8 ? code : 0x01000000u * code;
    std::memcpy(const_cast<char*>(agent.payload().data()) - 8, &request, sizeof(request));
    for (int cycle = 0; cycle < 7; ++cycle) server.cycle();
    if (server.state() == upkie_rl::SpineState::kOver) break;
  }
  if (static_cast<std::uint32_t>(server.state()) > 5) std::abort();
  return 0;
}
