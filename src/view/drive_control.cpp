#include "view/drive_control.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "view/drive_message.hpp"
#include "view/view_error.hpp"

namespace upkie_rl {

namespace k = drive_keys;

namespace {

std::string refusal(const std::string& reason) {
  return nlohmann::json{{k::kType, k::kRefused}, {k::kReason, reason}}.dump();
}

}  // namespace

DriveControl::DriveControl(const DriveLimits& limits, const DriveRateSettings& rate)
    : limits_(limits), rate_(rate) {
  const auto positive = [](double value) { return std::isfinite(value) && value > 0.0; };
  if (!positive(limits.max_forward_velocity) || !positive(limits.max_yaw_rate)) {
    throw ViewError("drive: the command limits must be finite and positive");
  }
  if (limits.height_command &&
      !(limits.min_height > 0.0 && limits.min_height <= limits.max_height &&
        std::isfinite(limits.max_height))) {
    throw ViewError("drive: the height limits must be finite, positive and increasing");
  }
  pending_.height = limits.max_height;                      // standing until a page asks otherwise
  RateLimiter check(rate.messages_per_second, rate.burst);  // throws on a bad rate
  (void)check;
}

DriveControl::Reply DriveControl::receive(ClientId client, std::string_view text,
                                          Clock::time_point now) {
  const std::lock_guard lock(mutex_);
  auto rate = rates_.find(client);
  if (rate == rates_.end()) {
    rate =
        rates_.emplace(client, PageRate{RateLimiter(rate_.messages_per_second, rate_.burst)}).first;
  }
  PageRate& page = rate->second;
  if (!page.limiter.allow(now)) {
    ++statistics_.rate_limited;
    // Said once per spell, so that a flood does not get a flood of answers.
    if (page.warned) return {};
    page.warned = true;
    return {refusal("too many messages: at most " + std::to_string(rate_.messages_per_second) +
                    " per second"),
            false};
  }
  page.warned = false;
  return handle(client, text, now);
}

DriveControl::Reply DriveControl::handle(ClientId client, std::string_view text,
                                         Clock::time_point now) {
  DriveMessage message;
  try {
    message = parse_drive_message(text, limits_);
  } catch (const DriveMessageError& error) {
    ++statistics_.refused;
    return {refusal(error.what()), false};
  }
  const bool was_free = !arbiter_.driver().has_value();
  if (!arbiter_.claim(client)) {
    ++statistics_.refused;
    return {refusal("another page drives; this one watches until it closes"), false};
  }
  Reply reply;
  reply.status_changed = was_free;
  switch (message.kind) {
    case DriveMessage::Kind::kCommand:
      ++statistics_.commands;
      pending_.forward_velocity = message.forward_velocity;
      pending_.yaw_rate = message.yaw_rate;
      pending_.height = message.height;
      pending_.sequence = message.sequence;
      pending_.new_command = true;
      received_at_ = now;
      break;
    case DriveMessage::Kind::kReset:
      pending_.reset = true;
      break;
    case DriveMessage::Kind::kPause:
      pending_.paused = !pending_.paused;
      reply.status_changed = true;
      break;
    case DriveMessage::Kind::kPush:
      if (waiting_push_count_ == kMaxWaitingPushes) {
        ++statistics_.refused;
        return {refusal("pushes come faster than the robot takes them; this one is dropped"),
                reply.status_changed};
      }
      waiting_pushes_[waiting_push_count_++] = message.heading;
      break;
  }
  return reply;
}

bool DriveControl::disconnect(ClientId client) {
  const std::lock_guard lock(mutex_);
  rates_.erase(client);
  if (!arbiter_.release(client)) return false;
  // Nobody holds the controls: the robot stands still (at the height it has), and a paused
  // run goes on.
  pending_.forward_velocity = 0.0;
  pending_.yaw_rate = 0.0;
  pending_.sequence = 0;
  pending_.new_command = true;
  pending_.paused = false;
  received_at_ = Clock::now();
  return true;
}

std::string DriveControl::status_message(ClientId client) const {
  const std::lock_guard lock(mutex_);
  const char* role = k::kFree;
  std::string reason = "nobody drives: press a key (or move a gamepad stick) to take the controls";
  if (arbiter_.is_driver(client)) {
    role = k::kDriver;
    reason = "this page drives";
  } else if (arbiter_.driver()) {
    role = k::kWatcher;
    reason = "another page drives; this one watches";
  }
  return nlohmann::json{
      {k::kType, k::kStatus}, {k::kRole, role}, {k::kPaused, pending_.paused}, {k::kReason, reason}}
      .dump();
}

DriveInputs DriveControl::take() {
  const std::lock_guard lock(mutex_);
  DriveInputs inputs = pending_;
  pending_.new_command = false;
  pending_.reset = false;
  // Pushes wait while the run is paused, each for a step of its own after it.
  if (waiting_push_count_ > 0 && !pending_.paused) {
    inputs.push_heading = waiting_pushes_[0];
    std::copy(waiting_pushes_.begin() + 1, waiting_pushes_.begin() + waiting_push_count_,
              waiting_pushes_.begin());
    --waiting_push_count_;
  }
  return inputs;
}

void DriveControl::applied(const DriveInputs& inputs, Clock::time_point now) {
  if (!inputs.new_command) return;
  std::function<void()> listener;
  {
    const std::lock_guard lock(mutex_);
    const double latency = std::chrono::duration<double>(now - received_at_).count();
    ++statistics_.applied;
    statistics_.latency_sum += latency;
    statistics_.latency_max = std::max(statistics_.latency_max, latency);
    const std::optional<ClientId> driver = arbiter_.driver();
    if (!driver || inputs.sequence == 0) return;
    acknowledgement_ = {*driver, inputs.sequence};
    listener = listener_;
  }
  if (listener) listener();
}

void DriveControl::set_applied_listener(std::function<void()> listener) {
  const std::lock_guard lock(mutex_);
  listener_ = std::move(listener);
}

std::optional<std::pair<DriveControl::ClientId, std::string>> DriveControl::take_acknowledgement() {
  const std::lock_guard lock(mutex_);
  if (!acknowledgement_) return std::nullopt;
  const auto [client, sequence] = *acknowledgement_;
  acknowledgement_.reset();
  return std::make_pair(client,
                        nlohmann::json{{k::kType, k::kApplied}, {k::kSequence, sequence}}.dump());
}

DriveStatistics DriveControl::statistics() const {
  const std::lock_guard lock(mutex_);
  return statistics_;
}

}  // namespace upkie_rl
