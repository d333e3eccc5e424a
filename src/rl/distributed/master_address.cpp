#include "rl/distributed/master_address.hpp"

#include <netdb.h>
#include <sys/socket.h>

#include <algorithm>
#include <thread>

#include "rl/distributed/communicator.hpp"

namespace upkie_rl {

namespace {

/// 0 when `host` resolves, else getaddrinfo's error code.
int resolve(const std::string& host) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* addresses = nullptr;
  const int status = getaddrinfo(host.c_str(), nullptr, &hints, &addresses);
  if (addresses != nullptr) freeaddrinfo(addresses);
  return status;
}

}  // namespace

void wait_for_master_address(const std::string& host, std::chrono::milliseconds timeout,
                             const std::string& who) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    const int status = resolve(host);
    if (status == 0) return;
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      throw DistributedError(who + ": MASTER_ADDR \"" + host + "\" does not resolve to an " +
                             "address (" + gai_strerror(status) + ")");
    }
    std::this_thread::sleep_for(
        std::min<std::chrono::steady_clock::duration>(std::chrono::seconds(1), deadline - now));
  }
}

}  // namespace upkie_rl
