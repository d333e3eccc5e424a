#pragma once
/// @file
/// How upkie-rl ends a process some of whose threads are stuck (in a socket, in a
/// collective): the application's decision, taken for the rendezvous watchdog and for a rank
/// of a data-parallel run that its RankWatchdog reports abandoned.

#include <string>

namespace upkie_rl::apps {

/// Prints "upkie-rl: error: <message>" on stderr and ends the process with status 1 at once
/// (std::_Exit: the stuck threads cannot be unwound, nor destructors waiting on them run).
/// Callable from any thread.
[[noreturn]] void exit_stuck_process(const std::string& message);

}  // namespace upkie_rl::apps
