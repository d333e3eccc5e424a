#include "spine/shared_memory.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <utility>

#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

std::string errno_text() { return std::strerror(errno); }

/// Where glibc keeps POSIX shared-memory objects (a tmpfs): renaming there is atomic.
constexpr const char* kShmDirectory = "/dev/shm";

/// Closes a file descriptor at scope exit; the mapping outlives it.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }
  /// Hands the descriptor over (it is no longer closed here).
  int release() { return std::exchange(fd_, -1); }

 private:
  int fd_;
};

char* map(int fd, std::size_t size, const std::string& name) {
  void* data = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  if (data == MAP_FAILED) {
    throw SpineError("cannot map shared memory " + name + ": " + errno_text());
  }
  return static_cast<char*>(data);
}

/// Largest object mapped (as in create).
constexpr std::size_t kMaxSize = std::size_t{1} << 31;

/// Whether the object open as `fd` looks like a spine segment: a regular file whose size
/// fits the layout (kHeaderSize + 2 to kMaxSize), whose request word is a protocol code and
/// whose payload size fits the object. The layout has no magic number (it is the public
/// Upkie protocol's), so this is what tells a stale spine segment from someone else's
/// file; an agent that wrote junk into a spine's header makes it look foreign, which only
/// costs its owner an `rm`.
bool looks_like_a_spine_segment(int fd) {
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) return false;
  const auto size = static_cast<std::size_t>(status.st_size);
  if (size < SharedMemory::kHeaderSize + 2 || size > kMaxSize) return false;
  std::uint32_t header[2] = {};
  if (::pread(fd, header, sizeof(header), 0) != static_cast<ssize_t>(sizeof(header))) {
    return false;
  }
  return header[0] <= static_cast<std::uint32_t>(Request::kError) &&
         header[1] <= size - SharedMemory::kHeaderSize - 1;
}

/// Throws when `path` names an object that is not ours to replace: one whose spine is alive
/// (it holds the flock), or one that is no spine's segment at all (a file of another
/// program, a symbolic link, a directory). A stale spine segment passes and is replaced.
void refuse_live_or_foreign_object(const std::string& path, const std::string& name) {
  struct stat link_status {};
  if (::lstat(path.c_str(), &link_status) != 0) return;  // absent: nothing to judge
  const std::string remedy =
      "; if it is a stale one of yours, remove it (rm " + path + ") or choose another name";
  if (!S_ISREG(link_status.st_mode)) {
    throw SpineError("shared memory " + name + " exists and is not a spine's (" + path +
                     " is not a regular file)" + remedy);
  }
  FileDescriptor existing(::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  if (existing.get() < 0) return;  // not ours to read (another user's): the rename decides
  if (::flock(existing.get(), LOCK_EX | LOCK_NB) != 0) {
    throw SpineError("shared memory " + name +
                     " is in use by a running spine; stop it first or choose another name");
  }
  if (!looks_like_a_spine_segment(existing.get())) {
    throw SpineError("shared memory " + name + " exists and is not a spine's (" +
                     std::to_string(link_status.st_size) + " bytes, no valid spine header)" +
                     remedy);
  }
}

}  // namespace

void SharedMemory::validate_name(const std::string& name) {
  if (name.size() < 2 || name[0] != '/') {
    throw SpineError("invalid shared-memory name '" + name +
                     "': it must be '/' followed by at least one character");
  }
  if (name.find('/', 1) != std::string::npos) {
    throw SpineError("invalid shared-memory name '" + name +
                     "': only the first character may be '/'");
  }
  if (name.size() > 251) {
    throw SpineError("invalid shared-memory name '" + name + "': longer than 251 characters");
  }
}

SharedMemory SharedMemory::create(const std::string& name, std::size_t size, unsigned mode) {
  validate_name(name);
  if (mode > 0666) throw SpineError("invalid shared-memory mode " + std::to_string(mode));
  if (size <= kHeaderSize + 1 || size > kMaxSize) {
    throw SpineError("invalid shared-memory size " + std::to_string(size) + " for " + name);
  }
  // The object is built under a private name and renamed into place once sized and
  // initialised: an agent polling for `name` never sees it empty, and the rename also
  // replaces a stale object left by a spine that crashed (its agents are gone with it).
  static std::atomic<unsigned> creation_count{0};
  const std::string staging_name = "/upkie_rl_staging_" + std::to_string(::getpid()) + "_" +
                                   std::to_string(creation_count.fetch_add(1));
  ::shm_unlink(staging_name.c_str());  // a leftover of a crashed process with our pid
  FileDescriptor fd(::shm_open(staging_name.c_str(), O_RDWR | O_CREAT | O_EXCL, 0600));
  if (fd.get() < 0) {
    throw SpineError("cannot create shared memory " + name + " (staged as " + staging_name +
                     "): " + errno_text());
  }
  char* data = nullptr;
  try {
    // Exactly `mode`: the umask would strip bits a widened mode asks for.
    if (::fchmod(fd.get(), static_cast<mode_t>(mode)) != 0 ||
        ::flock(fd.get(), LOCK_EX | LOCK_NB) != 0) {
      throw SpineError("cannot set up shared memory " + name + ": " + errno_text());
    }
    if (::ftruncate(fd.get(), static_cast<off_t>(size)) != 0) {
      throw SpineError("cannot size shared memory " + name + ": " + errno_text());
    }
    data = map(fd.get(), size, name);
    std::memset(data, 0, kHeaderSize);  // request None, empty payload
    const std::string staging_path = std::string(kShmDirectory) + staging_name;
    const std::string final_path = std::string(kShmDirectory) + name;
    refuse_live_or_foreign_object(final_path, name);
    if (::rename(staging_path.c_str(), final_path.c_str()) != 0) {
      throw SpineError("cannot publish shared memory " + name + " (rename from " + staging_path +
                       "): " + errno_text());
    }
  } catch (...) {
    if (data != nullptr) ::munmap(data, size);
    ::shm_unlink(staging_name.c_str());
    throw;
  }
  return SharedMemory(name, size, data, true, fd.release());
}

SharedMemory SharedMemory::open(const std::string& name) {
  validate_name(name);
  FileDescriptor fd(::shm_open(name.c_str(), O_RDWR, 0666));
  if (fd.get() < 0) {
    throw SpineError("cannot open shared memory " + name + ": " + errno_text());
  }
  struct stat status {};
  if (::fstat(fd.get(), &status) != 0) {
    throw SpineError("cannot stat shared memory " + name + ": " + errno_text());
  }
  const auto size = static_cast<std::size_t>(status.st_size);
  if (size <= kHeaderSize + 1 || size > kMaxSize) {
    throw SpineError("shared memory " + name + " has " + std::to_string(size) +
                     " bytes, outside the spine layout's [" + std::to_string(kHeaderSize + 2) +
                     ", " + std::to_string(kMaxSize) + "]");
  }
  char* data = map(fd.get(), size, name);
  return SharedMemory(name, size, data, false, fd.release());
}

SharedMemory::SharedMemory(std::string name, std::size_t size, char* data, bool owner,
                           int descriptor)
    : name_(std::move(name)), size_(size), data_(data), owner_(owner), descriptor_(descriptor) {}

SharedMemory::SharedMemory(SharedMemory&& other) noexcept
    : name_(std::move(other.name_)),
      size_(std::exchange(other.size_, 0)),
      data_(std::exchange(other.data_, nullptr)),
      owner_(std::exchange(other.owner_, false)),
      descriptor_(std::exchange(other.descriptor_, -1)) {}

SharedMemory& SharedMemory::operator=(SharedMemory&& other) noexcept {
  if (this != &other) {
    release();
    name_ = std::move(other.name_);
    size_ = std::exchange(other.size_, 0);
    data_ = std::exchange(other.data_, nullptr);
    owner_ = std::exchange(other.owner_, false);
    descriptor_ = std::exchange(other.descriptor_, -1);
  }
  return *this;
}

SharedMemory::~SharedMemory() { release(); }

void SharedMemory::release() noexcept {
  if (data_ != nullptr) {
    ::munmap(data_, size_);
    data_ = nullptr;
  }
  if (owner_) {
    // Only while the name is still ours: never another spine's object.
    struct stat mine {};
    struct stat named {};
    const std::string path = std::string(kShmDirectory) + name_;
    if (::fstat(descriptor_, &mine) == 0 && ::stat(path.c_str(), &named) == 0 &&
        mine.st_ino == named.st_ino && mine.st_dev == named.st_dev) {
      ::shm_unlink(name_.c_str());
    }
    owner_ = false;
  }
  if (descriptor_ >= 0) {
    ::close(descriptor_);  // releases the owner's flock
    descriptor_ = -1;
  }
}

void SharedMemory::check_not_shrunk() const {
  struct stat status {};
  if (::fstat(descriptor_, &status) == 0 && static_cast<std::size_t>(status.st_size) >= size_) {
    return;
  }
  throw SpineError("shared memory " + name_ + " shrank to " + std::to_string(status.st_size) +
                   " bytes under its " + std::to_string(size_) + "-byte mapping");
}

std::atomic_ref<std::uint32_t> SharedMemory::word(std::size_t offset) const {
  // mmap returns page-aligned memory, so both words are 4-byte aligned.
  return std::atomic_ref<std::uint32_t>(*reinterpret_cast<std::uint32_t*>(data_ + offset));
}

std::uint32_t SharedMemory::request() const {
  check_not_shrunk();
  return word(0).load(std::memory_order_acquire);
}

void SharedMemory::set_request(Request request) {
  check_not_shrunk();
  word(0).store(static_cast<std::uint32_t>(request), std::memory_order_release);
}

std::uint32_t SharedMemory::payload_size() const { return word(4).load(std::memory_order_acquire); }

std::span<const char> SharedMemory::payload() const {
  check_not_shrunk();
  const std::uint32_t size = payload_size();
  if (size > max_payload_size()) {
    throw SpineError("payload of " + std::to_string(size) + " bytes refused: shared memory " +
                     name_ + " holds at most " + std::to_string(max_payload_size()));
  }
  return {data_ + kHeaderSize, size};
}

void SharedMemory::write_payload(std::span<const char> bytes) {
  if (bytes.size() > max_payload_size()) {
    throw SpineError("payload of " + std::to_string(bytes.size()) +
                     " bytes does not fit in shared memory " + name_ + " (at most " +
                     std::to_string(max_payload_size()) + ")");
  }
  check_not_shrunk();
  std::memcpy(data_ + kHeaderSize, bytes.data(), bytes.size());
  word(4).store(static_cast<std::uint32_t>(bytes.size()), std::memory_order_release);
}

}  // namespace upkie_rl
