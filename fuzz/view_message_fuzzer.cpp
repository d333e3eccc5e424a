/// @file
/// libFuzzer target: what the viewer's server parses from a browser. An input is read in
/// three ways:
/// - as an HTTP request, with the server's parser and limits (Boost.Beast,
///   kViewMaxRequestBytes), whose Host header goes through is_allowed_host as every
///   request's does, and Origin and Host through is_same_origin as a WebSocket handshake's;
/// - as one text message of a page: parse_drive_message, whose accepted messages must be
///   within the limits (finite velocities inside them, a whole sequence number, a heading
///   in +-2 pi);
/// - as a session of several pages with a DriveControl: lines "<page digit><message>", or
///   "t" (the simulation loop takes the inputs and applies them), "d<page digit>" (the page
///   goes away), with the clock advancing 5 ms per line. Everything the control hands to
///   the loop must be within the limits, and its replies must be JSON.
/// A refusal is a DriveMessageError (a reply to the page); a crash, a hang, a sanitizer
/// report or another exception is a bug.

#include <algorithm>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "view/drive_control.hpp"
#include "view/drive_message.hpp"
#include "view/origin_check.hpp"
#include "view/view_server.hpp"

namespace {

namespace http = boost::beast::http;

constexpr upkie_rl::DriveLimits kLimits{1.0, 1.5};
constexpr int kMaxSessionLines = 64;

bool within(double value, double limit) { return std::isfinite(value) && std::abs(value) <= limit; }

bool starts_like_loopback(std::string_view host) {
  const auto lower = [](char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  };
  std::string name(host.substr(0, 9));
  std::transform(name.begin(), name.end(), name.begin(), lower);
  return name.rfind("localhost", 0) == 0 || name.rfind("127.", 0) == 0 || name.rfind("[", 0) == 0;
}

void check_http_request(std::string_view bytes) {
  http::request_parser<http::string_body> parser;
  parser.header_limit(upkie_rl::kViewMaxRequestBytes);
  parser.body_limit(upkie_rl::kViewMaxRequestBytes);
  parser.eager(true);
  boost::beast::error_code error;
  parser.put(boost::asio::buffer(bytes.data(), bytes.size()), error);
  if (error || !parser.is_header_done()) return;
  const auto& request = parser.get();
  const auto header = [&request](http::field field) {
    const auto found = request.find(field);
    return found == request.end() ? std::string_view{}
                                  : std::string_view(found->value().data(), found->value().size());
  };
  const std::string_view origin = header(http::field::origin);
  const std::string_view host = header(http::field::host);
  // The page's own origin is accepted; an empty Host never matches a browser's origin.
  if (upkie_rl::is_same_origin(origin, host) && !origin.empty() && host.empty()) std::abort();
  // Any Host is served on another address; on loopback only an empty one, localhost, or a
  // literal address (whose loopback check is Boost's).
  if (!upkie_rl::is_allowed_host(host, false)) std::abort();
  if (upkie_rl::is_allowed_host(host, true) && !host.empty() && !starts_like_loopback(host)) {
    std::abort();
  }
}

void check_message(std::string_view text) {
  try {
    const upkie_rl::DriveMessage message = upkie_rl::parse_drive_message(text, kLimits);
    if (!within(message.forward_velocity, kLimits.max_forward_velocity) ||
        !within(message.yaw_rate, kLimits.max_yaw_rate) || !within(message.heading, 2.0 * M_PI)) {
      std::abort();
    }
  } catch (const upkie_rl::DriveMessageError&) {
  }
}

void check_inputs(const upkie_rl::DriveInputs& inputs) {
  if (!within(inputs.forward_velocity, kLimits.max_forward_velocity) ||
      !within(inputs.yaw_rate, kLimits.max_yaw_rate) ||
      (inputs.push_heading && !within(*inputs.push_heading, 2.0 * M_PI))) {
    std::abort();
  }
}

void run_session(std::string_view text) {
  upkie_rl::DriveControl control(kLimits);
  auto now = upkie_rl::DriveControl::Clock::time_point{} + std::chrono::hours(1);
  std::size_t start = 0;
  // A page's messages come 5 ms apart at most 60 a second: past a few hundred lines, a
  // session only exercises the rate limiter, and slows the fuzzing down.
  for (int line_count = 0; start < text.size() && line_count < kMaxSessionLines; ++line_count) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    now += std::chrono::milliseconds(5);
    if (line.empty()) continue;
    if (line[0] == 't') {
      const upkie_rl::DriveInputs inputs = control.take();
      check_inputs(inputs);
      control.applied(inputs, now);
      if (const auto acknowledgement = control.take_acknowledgement()) {
        if (!nlohmann::json::accept(acknowledgement->second)) std::abort();
      }
    } else if (line[0] == 'd' && line.size() > 1) {
      control.disconnect(static_cast<unsigned char>(line[1]) % 4);
    } else {
      const upkie_rl::DriveControl::ClientId page = static_cast<unsigned char>(line[0]) % 4;
      const upkie_rl::DriveControl::Reply reply = control.receive(page, line.substr(1), now);
      if (!reply.to_sender.empty() && !nlohmann::json::accept(reply.to_sender)) std::abort();
      if (reply.status_changed && !nlohmann::json::accept(control.status_message(page))) {
        std::abort();
      }
    }
  }
  check_inputs(control.take());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check_http_request(text);
  check_message(text);
  run_session(text);
  return 0;
}
