#include "render/egl_library.hpp"

#include <gtest/gtest.h>

#include <string>

#include "render/render_error.hpp"

namespace upkie_rl {
namespace {

std::string load_error(const std::string& library) {
  try {
    load_egl_library(library);
  } catch (const RenderError& error) {
    return error.what();
  }
  return "";
}

TEST(EglLibrary, LoadsTheSystemLibraryWithEveryEntryPoint) {
  const EglLibrary egl = load_egl_library(kDefaultEglLibrary);
  EXPECT_NE(egl.get_proc_address, nullptr);
  EXPECT_NE(egl.make_current, nullptr);
  EXPECT_NE(egl.get_proc_address("eglGetPlatformDisplayEXT"), nullptr);
}

TEST(EglLibrary, AMissingLibraryNamesItselfAndThePackagesToInstall) {
  const std::string message = load_error("libupkie-rl-no-such-egl.so.1");
  EXPECT_NE(message.find("cannot load libupkie-rl-no-such-egl.so.1"), std::string::npos) << message;
  EXPECT_NE(message.find("libegl-mesa0"), std::string::npos) << message;
  EXPECT_NE(message.find("mesa-libEGL"), std::string::npos) << message;
}

TEST(EglLibrary, ALibraryWithoutEglEntryPointsIsRefused) {
  // libm is loadable everywhere and has no eglGetProcAddress.
  const std::string message = load_error("libm.so.6");
  EXPECT_NE(message.find("libm.so.6 has no eglGetProcAddress"), std::string::npos) << message;
}

TEST(EglLibrary, AnEmptyNameIsRefused) {
  EXPECT_NE(load_error("").find("UPKIE_RL_EGL_LIBRARY is empty"), std::string::npos);
}

}  // namespace
}  // namespace upkie_rl
