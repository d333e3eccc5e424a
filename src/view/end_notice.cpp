#include "view/end_notice.hpp"

#include <nlohmann/json.hpp>

namespace upkie_rl {

void EndNotice::post(const std::string& reason, Audience audience) {
  posted_ = true;
  message_ = nlohmann::json{{"type", "end"}, {"reason", reason}}.dump();
  audience_ = std::move(audience);
}

}  // namespace upkie_rl
