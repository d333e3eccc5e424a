#pragma once
/// @file
/// Pixels of an image file, decoded by ffmpeg, for tests that check what a figure shows.

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <array>
#include <cstdio>
#include <memory>

namespace upkie_rl::testing {

/// How many pixels of the image at `path` are within `tolerance` (per channel) of the
/// colour 0xRRGGBB; -1 when ffmpeg cannot decode it.
inline long count_pixels_near(const std::filesystem::path& path, std::uint32_t rgb,
                              int tolerance = 12) {
  // Binary output: read with fread (shell_output stops at the first zero byte).
  const std::string command =
      "ffmpeg -v error -i '" + path.string() + "' -f rawvideo -pix_fmt rgb24 - 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string raw;
  std::array<char, 65536> buffer{};
  for (std::size_t read = 0;
       pipe && (read = std::fread(buffer.data(), 1, buffer.size(), pipe.get())) > 0;) {
    raw.append(buffer.data(), read);
  }
  if (raw.empty() || raw.size() % 3 != 0) return -1;
  const int target[3] = {static_cast<int>(rgb >> 16 & 0xff), static_cast<int>(rgb >> 8 & 0xff),
                         static_cast<int>(rgb & 0xff)};
  long count = 0;
  for (std::size_t i = 0; i < raw.size(); i += 3) {
    bool near = true;
    for (int c = 0; c < 3; ++c) {
      near = near && std::abs(static_cast<unsigned char>(raw[i + c]) - target[c]) <= tolerance;
    }
    count += near ? 1 : 0;
  }
  return count;
}

}  // namespace upkie_rl::testing
