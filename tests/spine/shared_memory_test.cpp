#include "spine/shared_memory.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <thread>

#include "fake_simulation.hpp"
#include "spine/spine_error.hpp"

namespace upkie_rl {
namespace {

bool shm_exists(const std::string& name) { return std::filesystem::exists("/dev/shm" + name); }

TEST(SharedMemory, CreateOpenAndUnlink) {
  const std::string name = testing::unique_shm_name("shm");
  {
    SharedMemory spine = SharedMemory::create(name);
    EXPECT_TRUE(shm_exists(name));
    const auto permissions = std::filesystem::status("/dev/shm" + name).permissions();
    // Owner only (issue 26): any process that can write it can drive the robot.
    EXPECT_EQ(permissions & std::filesystem::perms::all,
              std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    EXPECT_EQ(spine.size(), SharedMemory::kDefaultSize);
    EXPECT_EQ(spine.request(), 0u);
    EXPECT_EQ(spine.payload_size(), 0u);
    SharedMemory agent = SharedMemory::open(name);
    EXPECT_FALSE(agent.owner());
    EXPECT_EQ(agent.size(), SharedMemory::kDefaultSize);

    const std::string payload = "\x81\xa1x\xc3";  // {"x": true}
    agent.write_payload({payload.data(), payload.size()});
    agent.set_request(Request::kAction);
    EXPECT_EQ(spine.request(), static_cast<std::uint32_t>(Request::kAction));
    EXPECT_EQ(std::string(spine.payload().data(), spine.payload().size()), payload);
    SharedMemory moved = std::move(agent);  // closing the agent must not unlink
  }
  EXPECT_FALSE(shm_exists(name));
}

TEST(SharedMemory, AgentNeverUnlinks) {
  const std::string name = testing::unique_shm_name("shm");
  SharedMemory spine = SharedMemory::create(name);
  { SharedMemory agent = SharedMemory::open(name); }
  EXPECT_TRUE(shm_exists(name));
}

TEST(SharedMemory, CreateReplacesAStaleObject) {
  const std::string name = testing::unique_shm_name("stale");
  // A crashed spine's leftover: wrong size and a request word stuck at Action.
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0666);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4096), 0);
  const std::uint32_t stuck = 1;
  ASSERT_EQ(::write(fd, &stuck, sizeof(stuck)), 4);
  ::close(fd);
  SharedMemory spine = SharedMemory::create(name);
  EXPECT_EQ(spine.size(), SharedMemory::kDefaultSize);
  EXPECT_EQ(spine.request(), 0u);
}

TEST(SharedMemory, AgentsNeverSeeAnUnsizedObject) {
  // An agent polling for the name (as the public Upkie tools do) must never find the
  // object before it is sized: a watcher opens it the moment it appears, 300 times.
  const std::string name = testing::unique_shm_name("publish");
  std::atomic<bool> done{false};
  std::atomic<bool> failed{false};
  std::string failure;  // written by the watcher only, read after join
  std::thread watcher([&] {
    while (!done.load()) {
      if (!shm_exists(name)) continue;
      try {
        const SharedMemory agent = SharedMemory::open(name);
        if (agent.size() != 4096) failure = "size " + std::to_string(agent.size());
      } catch (const SpineError& error) {
        // Unlinked between the check and the open: fine. Anything else is the bug.
        if (std::string(error.what()).find("too small") != std::string::npos) {
          failure = error.what();
        }
      }
      if (!failure.empty()) {
        failed.store(true);
        return;
      }
    }
  });
  for (int cycle = 0; cycle < 300 && !failed.load(); ++cycle) {
    const SharedMemory spine = SharedMemory::create(name, 4096);
    std::this_thread::yield();
  }
  done.store(true);
  watcher.join();
  EXPECT_EQ(failure, "");
  EXPECT_FALSE(shm_exists(name));
  // Nothing staged is left behind in /dev/shm.
  const std::string staging_prefix = "upkie_rl_staging_" + std::to_string(::getpid()) + "_";
  for (const auto& entry : std::filesystem::directory_iterator("/dev/shm")) {
    EXPECT_NE(entry.path().filename().string().rfind(staging_prefix, 0), 0u) << entry.path();
  }
}

TEST(SharedMemory, OpenMissingNamesTheObject) {
  const std::string name = testing::unique_shm_name("missing");
  try {
    SharedMemory::open(name);
    FAIL();
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find(name), std::string::npos);
  }
}

TEST(SharedMemory, RefusesOversizedPayloads) {
  const std::string name = testing::unique_shm_name("size");
  SharedMemory spine = SharedMemory::create(name, 64);
  EXPECT_EQ(spine.max_payload_size(), 55u);  // n + 8 >= 64 refused
  const std::string fits(55, 'a');
  EXPECT_NO_THROW(spine.write_payload({fits.data(), fits.size()}));
  const std::string too_big(56, 'a');
  EXPECT_THROW(spine.write_payload({too_big.data(), too_big.size()}), SpineError);
  // A size word written by someone else is checked when reading.
  SharedMemory agent = SharedMemory::open(name);
  const std::uint32_t lie = 1000;
  std::memcpy(const_cast<char*>(agent.payload().data()) - 4, &lie, 4);
  EXPECT_EQ(spine.payload_size(), 1000u);
  EXPECT_THROW(spine.payload(), SpineError);
}

TEST(SharedMemory, ValidatesNames) {
  EXPECT_THROW(SharedMemory::validate_name("upkie"), SpineError);
  EXPECT_THROW(SharedMemory::validate_name("/"), SpineError);
  EXPECT_THROW(SharedMemory::validate_name("/a/b"), SpineError);
  EXPECT_THROW(SharedMemory::validate_name("/" + std::string(300, 'x')), SpineError);
  EXPECT_NO_THROW(SharedMemory::validate_name("/upkie"));
}

// Fault injection (issue 26, item 4): one owner per spine, private segments, shrinking.

TEST(SharedMemory, SecondSpineOnANameInUseIsRefusedAndTouchesNothing) {
  const std::string name = testing::unique_shm_name("owned");
  SharedMemory first = SharedMemory::create(name);
  first.set_request(Request::kStop);
  try {
    SharedMemory second = SharedMemory::create(name);
    FAIL() << "a second spine took " << name;
  } catch (const SpineError& error) {
    EXPECT_NE(std::string(error.what()).find("in use by a running spine"), std::string::npos)
        << error.what();
  }
  // The first spine's object is still there, still its own, still in the same state.
  SharedMemory agent = SharedMemory::open(name);
  EXPECT_EQ(agent.request(), static_cast<std::uint32_t>(Request::kStop));
  EXPECT_EQ(agent.size(), first.size());
}

/// Writes `bytes` to /dev/shm<name> as another program would (a plain file, mode 0644).
std::string write_foreign_object(const std::string& name, const std::string& bytes) {
  std::string path = "/dev/shm" + name;  // not const: returned by move
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::string read_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

/// create(name) throws a SpineError naming the object and how to remove it.
void expect_refused_as_foreign(const std::string& name) {
  try {
    SharedMemory spine = SharedMemory::create(name);
    FAIL() << "a spine took the foreign object " << name;
  } catch (const SpineError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("shared memory " + name + " exists and is not a spine's"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("rm /dev/shm" + name), std::string::npos) << message;
  }
}

// Fault injection (issue 26): a spine replaced, then unlinked at exit, any unlocked object of
// its name, another program's file included.
TEST(SharedMemory, ForeignObjectsAreRefusedAndLeftByteIdentical) {
  const std::string text_name = testing::unique_shm_name("foreign_text");
  const std::string text_path = write_foreign_object(text_name, "data\n");
  expect_refused_as_foreign(text_name);
  EXPECT_EQ(read_bytes(text_path), "data\n");
  // Of a plausible size, but its request word is no protocol code.
  const std::string sized_name = testing::unique_shm_name("foreign_sized");
  const std::string sized(SharedMemory::kDefaultSize, '\xff');
  const std::string sized_path = write_foreign_object(sized_name, sized);
  expect_refused_as_foreign(sized_name);
  EXPECT_TRUE(read_bytes(sized_path) == sized);
  // A symbolic link: neither it nor its target is replaced.
  const std::string link_name = testing::unique_shm_name("foreign_link");
  const std::string link_path = "/dev/shm" + link_name;
  std::filesystem::create_symlink(text_path, link_path);
  expect_refused_as_foreign(link_name);
  EXPECT_TRUE(std::filesystem::is_symlink(link_path));
  EXPECT_EQ(read_bytes(text_path), "data\n");
  for (const std::string& path : {text_path, sized_path, link_path}) {
    std::filesystem::remove(path);
  }
}

TEST(SharedMemory, OwnerDoesNotUnlinkAnObjectThatIsNoLongerItsOwn) {
  const std::string name = testing::unique_shm_name("renamed");
  std::optional<SharedMemory> first(SharedMemory::create(name));
  ::shm_unlink(name.c_str());                        // someone removed it by hand...
  SharedMemory second = SharedMemory::create(name);  // ...and a new spine took the name
  first.reset();
  EXPECT_TRUE(shm_exists(name));
}

TEST(SharedMemory, SegmentsArePrivateByDefaultAndTheModeWidensThem) {
  const std::string name = testing::unique_shm_name("mode");
  {
    SharedMemory spine = SharedMemory::create(name);
    EXPECT_EQ(std::filesystem::status("/dev/shm" + name).permissions(),
              std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  }
  SharedMemory shared = SharedMemory::create(name, SharedMemory::kDefaultSize, 0660);
  EXPECT_EQ(static_cast<unsigned>(std::filesystem::status("/dev/shm" + name).permissions()), 0660u);
}

TEST(SharedMemory, ShrunkSegmentIsAnErrorNotSigbus) {
  const std::string name = testing::unique_shm_name("shrunk");
  SharedMemory spine = SharedMemory::create(name, 65536);
  SharedMemory agent = SharedMemory::open(name);
  const int fd = ::shm_open(name.c_str(), O_RDWR, 0);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 0), 0);
  ::close(fd);
  EXPECT_THROW(agent.request(), SpineError);
  EXPECT_THROW(agent.payload(), SpineError);
  EXPECT_THROW(spine.set_request(Request::kNone), SpineError);
  const char bytes[4] = {1, 2, 3, 4};
  EXPECT_THROW(spine.write_payload(bytes), SpineError);
}

TEST(SharedMemory, ReaderRefusesAnUnmappableSizeBeforeMapping) {
  const std::string name = testing::unique_shm_name("tiny");
  const int fd = ::shm_open(name.c_str(), O_RDWR | O_CREAT, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::ftruncate(fd, 4), 0);
  ::close(fd);
  EXPECT_THROW(SharedMemory::open(name), SpineError);
  ::shm_unlink(name.c_str());
}

}  // namespace
}  // namespace upkie_rl
