#include "render/video_writer.hpp"

#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "render/render_error.hpp"

extern char** environ;

namespace upkie_rl {
namespace {

bool ffmpeg_on_path() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string directories(path);
  std::size_t start = 0;
  while (start <= directories.size()) {
    const std::size_t end = std::min(directories.find(':', start), directories.size());
    const std::filesystem::path candidate =
        std::filesystem::path(directories.substr(start, end - start)) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

VideoFormat VideoWriter::check_path(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  VideoFormat format;
  if (extension == ".mp4") {
    format = VideoFormat::kMp4;
  } else if (extension == ".gif") {
    format = VideoFormat::kGif;
  } else {
    throw RenderError("video " + path.string() + ": unsupported extension \"" + extension +
                      "\"; use .mp4 (H.264) or .gif");
  }
  const std::filesystem::path directory =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  std::error_code error;
  if (!std::filesystem::is_directory(directory, error)) {
    throw RenderError("video " + path.string() + ": directory " + directory.string() +
                      " does not exist");
  }
  if (::access(directory.c_str(), W_OK) != 0) {
    throw RenderError("video " + path.string() + ": directory " + directory.string() +
                      " is not writable");
  }
  if (std::filesystem::is_directory(path, error)) {
    throw RenderError("video " + path.string() + " is a directory");
  }
  if (!ffmpeg_on_path()) {
    throw RenderError("video " + path.string() +
                      ": ffmpeg not found on the PATH (Debian package ffmpeg; make deps)");
  }
  return format;
}

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, int fps)
    : path_(path), width_(width), height_(height), fps_(fps) {
  const VideoFormat format = check_path(path);
  if (fps < 1 || fps > 240)
    throw RenderError("video frame rate must be 1 to 240, got " + std::to_string(fps));
  if (format == VideoFormat::kMp4 && (width % 2 != 0 || height % 2 != 0)) {
    throw RenderError("H.264 needs an even frame size, got " + std::to_string(width) + "x" +
                      std::to_string(height));
  }
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string rate = std::to_string(fps);
  std::vector<std::string> args = {"ffmpeg", "-nostdin", "-y",       "-loglevel", "error",
                                   "-f",     "rawvideo", "-pix_fmt", "rgb24",     "-s",
                                   size,     "-r",       rate,       "-i",        "pipe:0"};
  if (format == VideoFormat::kMp4) {
    args.insert(args.end(), {"-c:v", "libx264", "-preset", "veryfast", "-crf", "23", "-pix_fmt",
                             "yuv420p", "-movflags", "+faststart"});
  } else {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse",
                             "-loop", "0"});
  }
  args.push_back(path.string());

  // A socket, not a pipe, so that writes after ffmpeg died fail with EPIPE (MSG_NOSIGNAL)
  // instead of raising SIGPIPE in the whole process.
  int sockets[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
    throw RenderError(std::string("cannot create the pipe to ffmpeg: ") + std::strerror(errno));
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sockets[1], STDIN_FILENO);
  std::vector<char*> argv;
  for (std::string& arg : args) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int status = ::posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(sockets[1]);
  if (status != 0) {
    ::close(sockets[0]);
    throw RenderError(std::string("cannot start ffmpeg: ") + std::strerror(status));
  }
  ::shutdown(sockets[0], SHUT_RD);
  stdin_fd_ = sockets[0];
  pid_ = pid;
}

VideoWriter::~VideoWriter() {
  if (pid_ < 0) return;
  try {
    close();
  } catch (const RenderError& error) {
    spdlog::error("{}", error.what());
  }
}

void VideoWriter::write(std::span<const std::uint8_t> rgb) {
  const std::size_t expected = static_cast<std::size_t>(width_) * height_ * 3;
  if (rgb.size() != expected) {
    throw RenderError("video frame has " + std::to_string(rgb.size()) + " bytes, expected " +
                      std::to_string(expected));
  }
  if (stdin_fd_ < 0) throw RenderError("video " + path_.string() + " is already closed");
  std::size_t written = 0;
  while (written < rgb.size()) {
    const ssize_t sent =
        ::send(stdin_fd_, rgb.data() + written, rgb.size() - written, MSG_NOSIGNAL);
    if (sent < 0) {
      if (errno == EINTR) continue;
      throw RenderError("ffmpeg stopped while writing " + path_.string() + ": " +
                        std::strerror(errno));
    }
    written += static_cast<std::size_t>(sent);
  }
  ++frames_;
}

void VideoWriter::close() {
  if (pid_ < 0) return;
  if (stdin_fd_ >= 0) {
    ::close(stdin_fd_);
    stdin_fd_ = -1;
  }
  int status = 0;
  while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw RenderError("ffmpeg failed writing " + path_.string() + " (exit status " +
                      std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  }
}

}  // namespace upkie_rl
