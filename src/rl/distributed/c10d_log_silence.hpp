#pragma once
/// @file
/// C10dLogSilence: libtorch's c10d log lines kept off stderr during the rendezvous.

#include <c10/util/Logging.h>

namespace upkie_rl {

/// While it lives, libtorch's c10d logs nothing: during a rendezvous it writes a glog line
/// per retry ("[c10d] The server socket has failed to bind", "The IPv6 network addresses
/// ... cannot be retrieved" once a second for the whole timeout), which buried the one
/// line of our own naming the cause. c10d logs only at levels of at least
/// caffe2_log_level, which this raises to FATAL and restores afterwards. Not thread-safe:
/// make it where no other thread of libtorch's runs (before the store exists).
class C10dLogSilence {
 public:
  C10dLogSilence() : saved_level_(FLAGS_caffe2_log_level) { FLAGS_caffe2_log_level = kFatal; }
  ~C10dLogSilence() { FLAGS_caffe2_log_level = saved_level_; }
  C10dLogSilence(const C10dLogSilence&) = delete;
  C10dLogSilence& operator=(const C10dLogSilence&) = delete;

 private:
  static constexpr int kFatal = 3;  // c10's levels: 0 INFO, 1 WARNING, 2 ERROR, 3 FATAL.
  int saved_level_;
};

}  // namespace upkie_rl
