#pragma once
/// @file
/// Where a process stands in a distributed training run, read from the variables every
/// PyTorch launcher sets: torchrun (and torch.distributed.launch), Slurm's srun, Kubernetes
/// operators. With none of them set, the process trains alone.

#include <functional>
#include <optional>
#include <string>

namespace upkie_rl {

/// One process's place in a world of processes.
struct DistributedLaunch {
  int world_size = 1;
  int rank = 0;        ///< 0 .. world_size - 1; rank 0 writes logs and checkpoints.
  int local_rank = 0;  ///< Rank among the processes of this machine.
  std::string master_addr = "127.0.0.1";  ///< Host of rank 0's rendezvous store.
  int master_port = 29500;                ///< Port of rank 0's rendezvous store.
  std::string source;                     ///< What set it: "torchrun", "slurm" or "alone".
  /// True when the launcher already serves the rendezvous store at master_addr:master_port
  /// (torchrun's agent: TORCHELASTIC_USE_AGENT_STORE=True); rank 0 then connects to it
  /// instead of serving one.
  bool launcher_store = false;

  bool distributed() const { return world_size > 1; }
};

/// Reads WORLD_SIZE, RANK, LOCAL_RANK, MASTER_ADDR and MASTER_PORT (torchrun), or failing
/// WORLD_SIZE, SLURM_NTASKS, SLURM_PROCID and SLURM_LOCALID with MASTER_ADDR and MASTER_PORT
/// (srun), and TORCHELASTIC_USE_AGENT_STORE. `lookup` returns a variable's value, or nothing when
/// it is unset (default: the process environment).
/// @throws std::invalid_argument naming the variable that is missing, not a number or out
///         of range (a RANK not below WORLD_SIZE, a port outside 1..65535).
DistributedLaunch distributed_launch_from_environment(
    const std::function<std::optional<std::string>(const std::string&)>& lookup = {});

}  // namespace upkie_rl
