#include "view/driver_arbiter.hpp"

namespace upkie_rl {

bool DriverArbiter::claim(ClientId client) {
  if (!driver_) driver_ = client;
  return *driver_ == client;
}

bool DriverArbiter::release(ClientId client) {
  if (driver_ != client) return false;
  driver_.reset();
  return true;
}

}  // namespace upkie_rl
