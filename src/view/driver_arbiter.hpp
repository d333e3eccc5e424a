#pragma once
/// @file
/// DriverArbiter: which page drives. One at a time; the others watch.

#include <cstdint>
#include <optional>

namespace upkie_rl {

/// Gives control to the first page that asks while nobody drives, and keeps it there until
/// that page releases it (it closes).
class DriverArbiter {
 public:
  using ClientId = std::uint64_t;

  /// Whether `client` drives after the call: it already did, or nobody did and it takes over.
  bool claim(ClientId client);

  /// Forgets `client`; returns true when it was the driver (control is then free).
  bool release(ClientId client);

  std::optional<ClientId> driver() const { return driver_; }
  bool is_driver(ClientId client) const { return driver_ == client; }

 private:
  std::optional<ClientId> driver_;
};

}  // namespace upkie_rl
