#include "policy/checkpoint_file.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include "common/temp_files.hpp"
#include "policy/crc32c.hpp"

namespace upkie_rl {
namespace {

using testing::read_bytes;
using testing::write_bytes;

std::filesystem::path temp_path(const std::string& name) {
  return testing::temp_path(name, "upkie_rl_checkpoint_file");
}

/// A file with this header text and tensor bytes, and a correct CRC: only the header's or
/// the tensors' problem is left to find.
std::string craft(const std::string& header, const std::string& data) {
  std::string bytes = "UPKIERL1";
  const std::uint64_t size = header.size();
  bytes.append(reinterpret_cast<const char*>(&size), sizeof(size));
  bytes += header + data;
  const std::uint32_t crc = crc32c(bytes);
  bytes.append(reinterpret_cast<const char*>(&crc), sizeof(crc));
  return bytes;
}

void expect_error(const std::filesystem::path& path, const std::string& text) {
  try {
    read_checkpoint_file(path);
    FAIL() << "expected an error containing '" << text << "'";
  } catch (const CheckpointError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(text), std::string::npos) << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
}

TEST(CheckpointFile, RoundTripKeepsHeaderShapesAndValues) {
  CheckpointFile file;
  file.header = {{"format", "test"}, {"n", 3}};
  file.tensors["a"] = {{2, 3}, {1, 2, 3, 4, 5, 6}};
  file.tensors["b"] = {{}, {7.5f}};
  file.tensors["empty"] = {{0}, {}};
  const auto path = temp_path("round_trip.ckpt");
  write_checkpoint_file(file, path);
  const CheckpointFile read = read_checkpoint_file(path);
  EXPECT_EQ(read.header, file.header);  // the tensor table is not part of the header
  ASSERT_EQ(read.tensors.size(), 3u);
  EXPECT_EQ(read.tensor("a", 6).shape, (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(read.tensor("a").values, file.tensors["a"].values);
  EXPECT_EQ(read.tensor("b", 1).values[0], 7.5f);
  EXPECT_THROW(read.tensor("a", 5), CheckpointError);
  EXPECT_THROW(read.tensor("c"), CheckpointError);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp." + std::to_string(::getpid())));
}

TEST(CheckpointFile, DamagedFilesNameTheProblem) {
  CheckpointFile file;
  file.header = {{"k", 1}};
  file.tensors["w"] = {{100}, std::vector<float>(100, 1.0f)};
  const auto path = temp_path("damaged.ckpt");
  write_checkpoint_file(file, path);
  const std::string bytes = read_bytes(path);

  std::string corrupted = bytes;
  corrupted[bytes.size() / 2] ^= 0x10;
  write_bytes(path, corrupted);
  expect_error(path, "CRC mismatch");
  write_bytes(path, bytes.substr(0, bytes.size() - 1));
  expect_error(path, "CRC mismatch");
  write_bytes(path, bytes.substr(0, 12));
  expect_error(path, "truncated");
  write_bytes(path, "UPKIE");
  expect_error(path, "bad magic");
  write_bytes(path, "");
  expect_error(path, "bad magic");
  write_bytes(path, "model weights, honest");
  expect_error(path, "not an upkie-rl checkpoint");
  expect_error(temp_path("missing.ckpt"), "cannot open");
  expect_error(temp_path(""), "is a directory");
}

TEST(CheckpointFile, InconsistentHeadersNameTheProblem) {
  const auto path = temp_path("crafted.ckpt");
  const std::string eight_bytes(8, '\0');
  write_bytes(path, craft(R"({"tensors":[{"name":"w","shape":[2]}]})", eight_bytes));
  EXPECT_EQ(read_checkpoint_file(path).tensor("w", 2).values, (std::vector<float>{0.0f, 0.0f}));
  write_bytes(path, craft("{not json", ""));
  expect_error(path, "header: malformed JSON");
  write_bytes(path, craft(R"({"k":1})", ""));
  expect_error(path, "malformed header");  // no tensor table
  write_bytes(path, craft(R"({"tensors":[{"name":"w","shape":[3]}]})", eight_bytes));
  expect_error(path, "tensor 'w' exceeds the file");
  write_bytes(path, craft(R"({"tensors":[{"name":"w","shape":[-2]}]})", eight_bytes));
  expect_error(path, "negative size in tensor 'w'");
  write_bytes(path,
              craft(R"({"tensors":[{"name":"w","shape":[4294967296,4294967296]}]})", eight_bytes));
  expect_error(path, "tensor 'w' is too large");
  write_bytes(path, craft(R"({"tensors":[{"name":"w","shape":[1]}]})", eight_bytes));
  expect_error(path, "unexpected bytes after the tensors");
  write_bytes(path, craft(R"({"tensors":[{"name":"w","shape":"two"}]})", eight_bytes));
  expect_error(path, "malformed header");
  std::string lying = craft("{}", "");
  lying[8] = 100;  // header size beyond the file (CRC made right below)
  std::string body = lying.substr(0, lying.size() - 4);
  const std::uint32_t crc = crc32c(body);
  body.append(reinterpret_cast<const char*>(&crc), sizeof(crc));
  write_bytes(path, body);
  expect_error(path, "header size exceeds the file");
}

TEST(CheckpointFile, RefusesTensorsThatDoNotMatchTheirShape) {
  CheckpointFile file;
  file.tensors["w"] = {{2, 2}, {1.0f, 2.0f, 3.0f}};
  EXPECT_THROW(write_checkpoint_file(file, temp_path("mismatch.ckpt")), CheckpointError);
  file.tensors["w"] = {{-1}, {}};
  EXPECT_THROW(write_checkpoint_file(file, temp_path("negative.ckpt")), CheckpointError);
}

TEST(CheckpointFile, UnwritablePathIsAnError) {
  CheckpointFile file;
  EXPECT_THROW(write_checkpoint_file(file, "/proc/upkie_rl/model.ckpt"), std::exception);
}

}  // namespace
}  // namespace upkie_rl
