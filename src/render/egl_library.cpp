#include "render/egl_library.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <optional>

#include "render/render_error.hpp"

namespace upkie_rl {

namespace {

constexpr const char* kInstallHint =
    "rendering needs Mesa's EGL: on Debian and Ubuntu `apt install libegl1 libegl-mesa0 "
    "libgl1-mesa-dri`, on Fedora and RHEL `dnf install mesa-libEGL mesa-dri-drivers`";

template <typename Function>
void resolve(void* handle, const std::string& library, const char* name, Function& function) {
  function = reinterpret_cast<Function>(dlsym(handle, name));
  if (function == nullptr) {
    throw RenderError(library + " has no " + name + " (is it an EGL library?); " + kInstallHint);
  }
}

}  // namespace

EglLibrary load_egl_library(const std::string& library) {
  if (library.empty()) throw RenderError(std::string(kEglLibraryVariable) + " is empty");
  // RTLD_GLOBAL: MuJoCo's renderer finds eglGetProcAddress by looking it up in the global
  // scope. The handle is never closed: the context's functions live as long as the process.
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_GLOBAL);
  if (handle == nullptr) {
    const char* reason = dlerror();
    throw RenderError("cannot load " + library + " (" + (reason ? reason : "unknown error") +
                      "); " + kInstallHint);
  }
  EglLibrary egl;
  resolve(handle, library, "eglGetProcAddress", egl.get_proc_address);
  resolve(handle, library, "eglGetError", egl.get_error);
  resolve(handle, library, "eglInitialize", egl.initialize);
  resolve(handle, library, "eglTerminate", egl.terminate);
  resolve(handle, library, "eglChooseConfig", egl.choose_config);
  resolve(handle, library, "eglBindAPI", egl.bind_api);
  resolve(handle, library, "eglCreateContext", egl.create_context);
  resolve(handle, library, "eglDestroyContext", egl.destroy_context);
  resolve(handle, library, "eglMakeCurrent", egl.make_current);
  return egl;
}

const EglLibrary& egl_library() {
  static std::mutex mutex;
  static std::optional<EglLibrary> loaded;
  std::lock_guard lock(mutex);
  if (!loaded) {
    const char* chosen = std::getenv(kEglLibraryVariable);
    loaded = load_egl_library(chosen != nullptr ? chosen : kDefaultEglLibrary);
  }
  return *loaded;
}

}  // namespace upkie_rl
