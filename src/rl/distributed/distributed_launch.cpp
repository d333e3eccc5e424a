#include "rl/distributed/distributed_launch.hpp"

#include <cstdlib>
#include <stdexcept>

#include "base/integer_text.hpp"

namespace upkie_rl {

namespace {

std::optional<std::string> process_variable(const std::string& name) {
  const char* value = std::getenv(name.c_str());
  if (value == nullptr) return std::nullopt;
  return std::string(value);
}

int read_integer(const std::string& name, const std::string& text, int minimum, int maximum) {
  const std::optional<int> value = integer_from_text<int>(text);
  if (!value || *value < minimum || *value > maximum) {
    throw std::invalid_argument(name + "=\"" + text + "\" is not an integer in [" +
                                std::to_string(minimum) + ", " + std::to_string(maximum) + "]");
  }
  return *value;
}

}  // namespace

DistributedLaunch distributed_launch_from_environment(
    const std::function<std::optional<std::string>(const std::string&)>& lookup_in) {
  const auto lookup = lookup_in ? lookup_in : process_variable;
  constexpr int kMaxWorld = 1 << 20;
  DistributedLaunch launch;
  // torchrun's names first: a Slurm job that runs torchrun inside has both.
  std::string world_name = "WORLD_SIZE", rank_name = "RANK", local_name = "LOCAL_RANK";
  launch.source = "torchrun";
  if (!lookup(world_name)) {
    world_name = "SLURM_NTASKS";
    rank_name = "SLURM_PROCID";
    local_name = "SLURM_LOCALID";
    launch.source = "slurm";
    // A Slurm job step of one task, or no launcher at all: train alone.
    if (!lookup(world_name) || *lookup(world_name) == "1") {
      launch.source = "alone";
      return launch;
    }
  }
  launch.world_size = read_integer(world_name, *lookup(world_name), 1, kMaxWorld);
  if (launch.world_size == 1) {
    launch.source = "alone";
    return launch;
  }
  const auto required = [&](const std::string& name) {
    const std::optional<std::string> value = lookup(name);
    if (!value || value->empty()) {
      throw std::invalid_argument(world_name + "=" + std::to_string(launch.world_size) + " but " +
                                  name + " is not set");
    }
    return *value;
  };
  launch.rank = read_integer(rank_name, required(rank_name), 0, launch.world_size - 1);
  if (const std::optional<std::string> local = lookup(local_name)) {
    launch.local_rank = read_integer(local_name, *local, 0, launch.world_size - 1);
  }
  launch.master_addr = required("MASTER_ADDR");
  launch.master_port = read_integer("MASTER_PORT", required("MASTER_PORT"), 1, 65535);
  launch.launcher_store =
      lookup("TORCHELASTIC_USE_AGENT_STORE") == std::optional<std::string>("True");
  return launch;
}

}  // namespace upkie_rl
