#pragma once
/// @file
/// Waiting for MASTER_ADDR to resolve before a rendezvous.

#include <chrono>
#include <string>

namespace upkie_rl {

/// Returns once `host` resolves to an address, trying once a second (a cluster's name
/// may appear a little after the job starts); throws DistributedError naming the host and
/// the resolver's reason when it still does not after `timeout`. libtorch's store retries
/// an unresolvable host silently (its warnings aside) until its timeout, then reports a
/// connect timeout that does not say the name was the problem.
/// @param who "rank r of n", the start of the error message.
void wait_for_master_address(const std::string& host, std::chrono::milliseconds timeout,
                             const std::string& who);

}  // namespace upkie_rl
