#include "view/origin_check.hpp"

#include <algorithm>
#include <cctype>

#include <boost/asio/ip/address.hpp>

namespace upkie_rl {

namespace {

bool equal_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

/// The name in a Host header, without its port: "[::1]:7000" -> "::1", "a:7000" -> "a".
std::string_view host_name(std::string_view host) {
  if (!host.empty() && host.front() == '[') {
    const std::size_t close = host.find(']');
    return close == std::string_view::npos ? std::string_view() : host.substr(1, close - 1);
  }
  return host.substr(0, host.find(':'));
}

}  // namespace

bool is_allowed_host(std::string_view host, bool listening_on_loopback) {
  if (!listening_on_loopback || host.empty()) return true;
  const std::string_view name = host_name(host);
  if (equal_ignoring_case(name, "localhost")) return true;
  boost::system::error_code error;
  const boost::asio::ip::address address = boost::asio::ip::make_address(name, error);
  return !error && address.is_loopback();
}

bool is_same_origin(std::string_view origin, std::string_view host) {
  if (origin.empty()) return true;
  for (const std::string_view scheme : {"http://", "https://"}) {
    if (origin.size() > scheme.size() &&
        equal_ignoring_case(origin.substr(0, scheme.size()), scheme)) {
      return !host.empty() && equal_ignoring_case(origin.substr(scheme.size()), host);
    }
  }
  return false;  // "null" (a file or sandboxed page) or another scheme
}

}  // namespace upkie_rl
