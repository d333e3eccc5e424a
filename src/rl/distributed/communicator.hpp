#pragma once
/// @file
/// The collective operations of data-parallel training (DD-PPO), over the processes of a
/// run: sums, means, broadcasts and gathers of flat values. A world of one process needs no
/// network: its communicator's collectives are the identity, so that the learner calls them
/// unconditionally. The ranks' watch over each other is rl/distributed/rank_watchdog.hpp's.

#include <torch/torch.h>

#include <chrono>
#include <functional>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

#include "base/error.hpp"
#include "rl/distributed/distributed_launch.hpp"

namespace upkie_rl {

/// Raised when the processes of a run cannot meet or one of them stops answering. The
/// message names the operation, the rank and, when known, the rank at fault.
class DistributedError : public Error {
 public:
  using Error::Error;
};

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int world_size() const = 0;
  /// Replaces `values` (contiguous, CPU, float32 or float64) by its sum over the ranks.
  /// @throws DistributedError after the timeout when a rank does not join.
  virtual void sum(torch::Tensor values) = 0;
  /// Replaces `values` on every rank by rank `root`'s.
  virtual void broadcast(torch::Tensor values, int root) = 0;
  /// Replaces `values` by its mean over the ranks: sum() divided by world_size().
  virtual void average(torch::Tensor values);
  /// average() of a few doubles.
  virtual void average(std::span<double> values);
  /// Calls `visit` with every rank's `local` values (their sizes may differ), in rank
  /// order, on every rank.
  virtual void gather(std::span<const double> local,
                      const std::function<void(std::span<const double>)>& visit);
};

/// A world of one process: every collective leaves the values as they are, without a copy
/// or an allocation (a single-process run is as fast as before there were ranks).
class SoloCommunicator final : public Communicator {
 public:
  int rank() const override { return 0; }
  int world_size() const override { return 1; }
  void sum(torch::Tensor /*values*/) override {}
  void broadcast(torch::Tensor /*values*/, int /*root*/) override {}
  void average(torch::Tensor /*values*/) override {}
  void average(std::span<double> /*values*/) override {}
  void gather(std::span<const double> local,
              const std::function<void(std::span<const double>)>& visit) override {
    visit(local);
  }
};

/// How the ranks of a data-parallel run wait for and watch over each other.
struct CommunicatorOptions {
  /// How long the rendezvous and each collective operation may wait for the other ranks.
  std::chrono::milliseconds timeout{300'000};
  /// Each rank writes a heartbeat (a count, and how many operations it has entered) to the
  /// rendezvous store this often. When an operation fails, the heartbeats name the rank at
  /// fault: one whose heartbeat stopped (dead, stopped, unreachable), or one alive that did
  /// not reach the operation (hung or far slower).
  std::chrono::milliseconds heartbeat_period{1000};
  /// A rank that sees another abort the run, or loses the store (rank 0 or the launcher is
  /// gone), and is still alive this much later (its main thread is stuck outside the
  /// collectives, which would otherwise fail by themselves) is told through `on_abandoned`.
  std::chrono::milliseconds abort_grace{10'000};
  /// Called from the watchdog's thread with the reason. Required for a world of more than
  /// one: the application decides (upkie-rl train prints it and ends the process, so that
  /// no rank is left running; a test records it).
  std::function<void(const std::string& reason)> on_abandoned;
};

/// Joins the world `launch` describes: rank 0 serves a c10d TCPStore at
/// master_addr:master_port (unless the launcher serves it) and the others connect to it
/// (the rendezvous), then a Gloo process group runs the collectives over TCP, and a
/// RankWatchdog of each rank beats its heartbeat. A world of one gives a SoloCommunicator.
/// @throws DistributedError naming the address when the rendezvous fails;
/// std::invalid_argument without options.on_abandoned.
std::unique_ptr<Communicator> connect_communicator(const DistributedLaunch& launch,
                                                   const CommunicatorOptions& options);

}  // namespace upkie_rl
