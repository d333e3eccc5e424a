#pragma once
/// @file
/// The POSIX shared memory that carries the spine link: a request word, a payload size
/// and a msgpack payload (spine.md section 1).

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "spine/request.hpp"

namespace upkie_rl {

/// A mapped shared-memory object with the spine layout, native byte order:
/// bytes [0, 4) request word, [4, 8) payload size n, [8, 8 + n) msgpack payload.
/// The spine creates (and at destruction unlinks) it; agents open the existing one.
/// Movable, not copyable.
class SharedMemory {
 public:
  /// Default size of the spine's shared memory [bytes] (1 MiB).
  static constexpr std::size_t kDefaultSize = 1 << 20;
  /// Bytes before the payload: request word and payload size.
  static constexpr std::size_t kHeaderSize = 8;

  /// Default permissions of a spine's object: its owner alone may read and write it (any
  /// process that can write it can drive the robot). `upkie-rl spine --shm-mode` widens it.
  static constexpr unsigned kDefaultMode = 0600;

  /// Creates the object for a spine: shm_open(O_CREAT | O_EXCL) under a private staging
  /// name, permissions set to `mode` exactly (not filtered by the umask), ftruncate, mmap,
  /// an exclusive flock held until destruction, then an atomic rename to `name`, so agents
  /// never see it unsized. A stale object left by a spine that died (nobody holds its lock,
  /// and it still has the spine layout: a size within it, a protocol request code and a
  /// payload size that fits) is replaced; an object whose spine is alive, or that is no
  /// spine segment (another program's file, a link, a directory), is refused and left
  /// untouched, the message saying how to remove it if it is stale. The request
  /// word starts at None and the payload is empty. The destructor unlinks the name only
  /// while it still names this object.
  /// @param name POSIX name, "/" followed by up to 250 characters other than "/".
  /// @param mode Permission bits, at most 0666.
  /// @throws SpineError naming the object and the failing call, or the live spine's or
  ///         foreign object's name.
  static SharedMemory create(const std::string& name, std::size_t size = kDefaultSize,
                             unsigned mode = kDefaultMode);

  /// Opens an existing object for an agent (never unlinks it). Its size is checked before
  /// it is mapped.
  /// @throws SpineError when it does not exist, is smaller than the header or larger than
  ///         2 GiB, or cannot be mapped; the message names the object.
  static SharedMemory open(const std::string& name);

  /// Checks a shared-memory name. @throws SpineError explaining what is wrong.
  static void validate_name(const std::string& name);

  SharedMemory(SharedMemory&& other) noexcept;
  SharedMemory& operator=(SharedMemory&& other) noexcept;
  SharedMemory(const SharedMemory&) = delete;
  SharedMemory& operator=(const SharedMemory&) = delete;
  ~SharedMemory();

  /// Current request word (raw: it may hold a code outside the protocol). Acquire load.
  /// @throws SpineError when the object shrank (check_not_shrunk).
  std::uint32_t request() const;
  /// Sets the request word. Release store: the payload written before is visible.
  /// @throws SpineError when the object shrank (check_not_shrunk).
  void set_request(Request request);

  /// Payload size word as written in memory (not validated).
  std::uint32_t payload_size() const;
  /// Largest accepted payload [bytes]: a payload with n + 8 >= size is refused.
  std::size_t max_payload_size() const { return size_ - kHeaderSize - 1; }
  /// The payload, validated against the object size.
  /// @throws SpineError when the size word is too large, or when the object shrank below
  ///         its mapped size (check_not_shrunk).
  std::span<const char> payload() const;
  /// Writes size and payload bytes (not the request word).
  /// @throws SpineError when the payload is too large for the object or the object shrank.
  void write_payload(std::span<const char> bytes);

  /// Throws SpineError when another process truncated the object below the size mapped
  /// here: touching the lost pages would raise SIGBUS. One fstat per call.
  void check_not_shrunk() const;

  const std::string& name() const { return name_; }
  std::size_t size() const { return size_; }
  /// True for the creating side, which unlinks the object on destruction.
  bool owner() const { return owner_; }

 private:
  SharedMemory(std::string name, std::size_t size, char* data, bool owner, int descriptor);
  void release() noexcept;
  std::atomic_ref<std::uint32_t> word(std::size_t offset) const;

  std::string name_;
  std::size_t size_ = 0;
  char* data_ = nullptr;
  bool owner_ = false;
  int descriptor_ = -1;  // kept open: size checks, and the owner's flock
};

}  // namespace upkie_rl
