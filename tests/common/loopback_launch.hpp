#pragma once
/// @file
/// The launch of one rank of a world on 127.0.0.1, for tests and benchmarks that run every
/// rank in one process.

#include "rl/distributed/distributed_launch.hpp"

namespace upkie_rl::testing {

inline DistributedLaunch loopback_launch(int rank, int world_size, int port) {
  DistributedLaunch launch;
  launch.world_size = world_size;
  launch.rank = rank;
  launch.master_addr = "127.0.0.1";
  launch.master_port = port;
  return launch;
}

}  // namespace upkie_rl::testing
