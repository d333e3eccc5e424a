#pragma once
/// @file
/// The EGL functions of the offscreen renderer, loaded from the system's libEGL at run time
/// (dlopen) instead of linked: a binary or Python wheel built here then starts on machines
/// without EGL, and only rendering fails there, with a RenderError naming what to install.

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace upkie_rl {

/// The library opened when UPKIE_RL_EGL_LIBRARY is unset: glvnd's or Mesa's libEGL.
inline constexpr const char* kDefaultEglLibrary = "libEGL.so.1";
/// The environment variable naming another EGL library (a path or a soname).
inline constexpr const char* kEglLibraryVariable = "UPKIE_RL_EGL_LIBRARY";

/// The EGL entry points the offscreen context uses.
struct EglLibrary {
  PFNEGLGETPROCADDRESSPROC get_proc_address = nullptr;
  PFNEGLGETERRORPROC get_error = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLTERMINATEPROC terminate = nullptr;
  PFNEGLCHOOSECONFIGPROC choose_config = nullptr;
  PFNEGLBINDAPIPROC bind_api = nullptr;
  PFNEGLCREATECONTEXTPROC create_context = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroy_context = nullptr;
  PFNEGLMAKECURRENTPROC make_current = nullptr;
};

/// Opens `library` (a soname or a path) into the process's global scope (MuJoCo's OpenGL
/// loader looks eglGetProcAddress up there) and resolves the entry points.
/// @throws RenderError naming the library and the packages that provide it when it cannot
///         be opened or lacks an entry point.
EglLibrary load_egl_library(const std::string& library);

/// The process's EGL library: load_egl_library of UPKIE_RL_EGL_LIBRARY, else of
/// kDefaultEglLibrary, loaded once. A failure is not cached: every call retries and throws.
const EglLibrary& egl_library();

}  // namespace upkie_rl
