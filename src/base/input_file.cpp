#include "base/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>

namespace upkie_rl {

namespace {

/// Closes a file descriptor when it goes out of scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int descriptor) : descriptor_(descriptor) {}
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  ~FileDescriptor() {
    if (descriptor_ >= 0) ::close(descriptor_);
  }
  int get() const { return descriptor_; }

 private:
  int descriptor_;
};

std::string lowercase_error(int error) {
  std::string text = std::strerror(error);
  if (!text.empty()) text[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
  return text;
}

/// Why a file of status `status` is not read: not regular, or above `max_bytes`; "" if fine.
std::string status_problem(const struct stat& status, std::uintmax_t max_bytes) {
  if (S_ISDIR(status.st_mode)) return "is a directory";
  if (!S_ISREG(status.st_mode)) return "not a regular file (a FIFO, a device or a socket)";
  if (static_cast<std::uintmax_t>(status.st_size) > max_bytes) {
    return std::to_string(status.st_size) + " bytes, more than the limit of " +
           std::to_string(max_bytes) + " bytes";
  }
  return "";
}

}  // namespace

std::optional<std::string> read_input_file(const std::filesystem::path& path,
                                           std::uintmax_t max_bytes, std::string& bytes) {
  bytes.clear();
  struct stat status {};
  // stat first: a device or a FIFO is refused without being opened at all.
  if (::stat(path.c_str(), &status) != 0) return "cannot open: " + lowercase_error(errno);
  if (std::string problem = status_problem(status, max_bytes); !problem.empty()) return problem;
  // Non-blocking: should the path become a FIFO between stat and open, open does not wait
  // for a writer; fstat then refuses it.
  const FileDescriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (file.get() < 0) return "cannot open: " + lowercase_error(errno);
  if (::fstat(file.get(), &status) != 0) return lowercase_error(errno);
  if (std::string problem = status_problem(status, max_bytes); !problem.empty()) return problem;
  bytes.resize(static_cast<std::size_t>(status.st_size));
  std::size_t filled = 0;
  while (true) {
    // One byte beyond the limit tells a file that grew past it since fstat.
    if (filled == bytes.size()) {
      if (filled > max_bytes) break;
      bytes.resize(filled + std::min<std::uintmax_t>(max_bytes + 1 - filled, 1 << 16));
    }
    const ssize_t count = ::read(file.get(), bytes.data() + filled, bytes.size() - filled);
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) {
      bytes.clear();
      return "read error: " + lowercase_error(errno);
    }
    if (count == 0) break;
    filled += static_cast<std::size_t>(count);
  }
  bytes.resize(filled);
  if (filled > max_bytes) {
    bytes.clear();
    return "more than the limit of " + std::to_string(max_bytes) + " bytes";
  }
  return std::nullopt;
}

}  // namespace upkie_rl
