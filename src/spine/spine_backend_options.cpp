// The environment options of a spine backend (SpineBackendConfig), declared beside it.

#include "spine/spine_backend.hpp"

namespace upkie_rl {

void SpineBackendConfig::declare_options(OptionTable& table) {
  table.add_text("shm_name", &shm_name, "shared-memory name of the spine");
  table.add_choice("regulate_frequency", &regulate_frequency, {{"true", true}, {"false", false}},
                   "sleep so that actions leave at the agent rate (real-time spines)");
  table.add_choice("fresh_observation", &fresh_observation, {{"true", true}, {"false", false}},
                   "with regulate_frequency, return the observation of the next tick (the "
                   "action sent again) rather than the action's own reply");
  table.add_real("request_timeout", &request_timeout, 1e-3, 3600.0,
                 "longest wait for the spine to answer [s]");
  table.add_integer("open_tries", &open_tries, 1, 1000,
                    "attempts at opening the spine's shared memory, 1 s apart");
}

}  // namespace upkie_rl
