#pragma once
/// @file
/// NamedKey: one key of a wire format declared by an X-macro list (the checkpoint header,
/// the normalisation state, the provenance), with the name of its C++ constant, so that the
/// Python bindings can hand every list to Python under the same names.

#include <string_view>

namespace upkie_rl {

/// One key: its constant's name ("kNumTimesteps") and its wire text ("num_timesteps").
struct NamedKey {
  std::string_view constant;
  const char* text;
};

}  // namespace upkie_rl

// The two expansions of a key list X(constant, wire text, ...): the constant, and its entry
// of the list's kAllKeys. A list may carry more columns after the text (the provenance's).
// NOLINTBEGIN(cppcoreguidelines-macro-usage): X-macro expansions, see above.
#define UPKIE_RL_NAMED_KEY_CONSTANT(name, text, ...) inline constexpr const char* name = text;
#define UPKIE_RL_NAMED_KEY_ENTRY(name, text, ...) ::upkie_rl::NamedKey{#name, text},
// NOLINTEND(cppcoreguidelines-macro-usage)
