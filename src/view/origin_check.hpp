#pragma once
/// @file
/// Which browser pages may open the viewer's WebSocket: only the viewer's own.
///
/// A browser sends an `Origin` header with every WebSocket handshake, and lets any page it
/// shows open a WebSocket to any address, 127.0.0.1 included. Since pages can drive the
/// robot (`upkie-rl drive`), a page of another site open in the same browser must not reach
/// the frame stream: its Origin names its own site, not the server the viewer's page came
/// from. Clients that are not browsers (tests, scripts) send no Origin and are accepted, as
/// they could forge one anyway; the check protects browsers' users from other sites.

#include <string_view>

namespace upkie_rl {

/// True when a WebSocket handshake with these headers comes from a page of this server:
/// `origin` empty (not a browser), or its host and port (after "http://" or "https://")
/// equal `host`, the Host header the browser sent, compared without regard to case.
bool is_same_origin(std::string_view origin, std::string_view host);

/// True when a request's Host header may reach a server listening on a loopback address:
/// empty (not a browser), or naming `localhost`, an address in 127.0.0.0/8 or `[::1]`, with
/// any port. A page of another site can make its own name resolve to 127.0.0.1 (DNS
/// rebinding); its requests then pass the Origin check but still carry that name here.
/// A server listening on another address (`--host`) has been opened to the network on
/// purpose, and takes any Host.
bool is_allowed_host(std::string_view host, bool listening_on_loopback);

}  // namespace upkie_rl
