/// @file
/// libFuzzer target: the spine's shared-memory segment as an agent finds it, whatever the
/// peer wrote into it. An input is [segment size: 2 bytes, little-endian][shrink: 1 byte]
/// [size after the shrink: 2 bytes][the segment's bytes]. The target, as the peer, sizes a
/// real POSIX shared-memory object and writes the bytes into it (request word, payload size
/// word and payload included); then, as the agent (SpineBackend), opens it with
/// SharedMemory::open, reads the request word and the payload, and decodes the payload as an
/// observation with the agent's unpacker. When the shrink byte is odd, the peer truncates
/// the object after the agent mapped it (a spine that dies or resizes under its agent).
/// Refusing with SpineError is the expected outcome; a crash (SIGBUS on a page the peer cut
/// off), a hang, a sanitizer report or another exception is a bug. What is decoded must lie
/// within the segment.

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sim/observation.hpp"
#include "spine/observation_reader.hpp"
#include "spine/payload_unpacker.hpp"
#include "spine/request.hpp"
#include "spine/shared_memory.hpp"
#include "spine/spine_error.hpp"

namespace {

/// The peer's side: one object per fuzzing process, resized and rewritten for each input.
class Peer {
 public:
  Peer() : name_("/upkie_rl_fuzz_segment_" + std::to_string(::getpid())) {
    descriptor_ = ::shm_open(name_.c_str(), O_RDWR | O_CREAT | O_TRUNC, 0600);
    if (descriptor_ < 0) std::abort();
  }
  ~Peer() {
    ::close(descriptor_);
    ::shm_unlink(name_.c_str());
  }
  const std::string& name() const { return name_; }

  /// Sizes the object to `size` zero bytes, then writes `bytes` at its start.
  void write(std::size_t size, const std::uint8_t* bytes, std::size_t count) {
    resize(0);
    resize(size);
    if (size == 0 || count == 0) return;
    void* data = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, descriptor_, 0);
    if (data == MAP_FAILED) std::abort();
    std::memcpy(data, bytes, std::min(size, count));
    ::munmap(data, size);
  }
  void resize(std::size_t size) {
    if (::ftruncate(descriptor_, static_cast<off_t>(size)) != 0) std::abort();
  }

 private:
  std::string name_;
  int descriptor_ = -1;
};

/// The agent's reads of one cycle (SpineBackend::wait_for_spine, read_observation_payload).
void read_as_agent(const upkie_rl::SharedMemory& memory) {
  const std::uint32_t request = memory.request();
  if (request != static_cast<std::uint32_t>(upkie_rl::Request::kNone)) return;  // still waiting
  const std::span<const char> payload = memory.payload();
  if (payload.size() > memory.max_payload_size()) std::abort();
  upkie_rl::PayloadUnpacker unpacker(memory.max_payload_size());
  upkie_rl::Observation observation;
  upkie_rl::read_observation(unpacker.unpack(payload), observation);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Peer peer;
  if (size < 5) return 0;
  const std::size_t segment_size = data[0] | (std::size_t{data[1]} << 8);
  const bool shrink = (data[2] & 1) != 0;
  const std::size_t shrunk_size = data[3] | (std::size_t{data[4]} << 8);
  peer.write(segment_size, data + 5, size - 5);
  try {
    const upkie_rl::SharedMemory memory = upkie_rl::SharedMemory::open(peer.name());
    if (memory.owner() || memory.size() != segment_size) std::abort();
    if (shrink) peer.resize(shrunk_size);
    read_as_agent(memory);
  } catch (const upkie_rl::SpineError&) {
  }
  return 0;
}
