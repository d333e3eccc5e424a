#include "render/offscreen_context.hpp"

#include <cstdio>
#include <string>

#include "render/egl_library.hpp"
#include "render/llvm_target_registry.hpp"
#include "render/render_error.hpp"

namespace upkie_rl {

// EGL on Mesa's surfaceless platform, not OSMesa: processes that also load libGL (PyTorch
// from Debian does, through Qt) resolve GL functions through glvnd's dispatcher, which
// knows EGL contexts but not OSMesa's, and MuJoCo's loader then fails.
struct OffscreenContext::Impl {
  const EglLibrary& egl = egl_library();  // throws RenderError where EGL is missing
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

namespace {

std::string egl_error(const EglLibrary& egl, const char* what) {
  char code[16];
  std::snprintf(code, sizeof(code), "0x%04x", static_cast<unsigned>(egl.get_error()));
  return std::string(what) + " failed (EGL error " + code +
         "); is Mesa's EGL installed (libegl-mesa0, libgl1-mesa-dri)?";
}

}  // namespace

OffscreenContext::OffscreenContext(int /*width*/, int /*height*/)
    : impl_(std::make_unique<Impl>()) {
  const EglLibrary& egl = impl_->egl;
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      egl.get_proc_address("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) {
    throw RenderError("EGL has no eglGetPlatformDisplayEXT (Mesa's EGL is needed)");
  }
  impl_->display =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (impl_->display == EGL_NO_DISPLAY)
    throw RenderError(egl_error(egl, "eglGetPlatformDisplayEXT"));
  // libEGL has loaded Mesa by now; its llvmpipe must find its targets in its own libLLVM
  // before eglInitialize (see llvm_target_registry.hpp: Debian 13's libtorch).
  register_shadowed_llvm_targets();
  EGLint major = 0, minor = 0;
  if (!egl.initialize(impl_->display, &major, &minor)) {
    throw RenderError(egl_error(egl, "eglInitialize"));
  }
  // clang-format off
  const EGLint config_attributes[] = {
      EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
      EGL_DEPTH_SIZE, 24, EGL_STENCIL_SIZE, 8,
      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
      EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,  // surfaceless offers pbuffer configs only
      EGL_NONE};
  // clang-format on
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!egl.choose_config(impl_->display, config_attributes, &config, 1, &count) || count < 1) {
    egl.terminate(impl_->display);
    throw RenderError(egl_error(egl, "eglChooseConfig"));
  }
  if (!egl.bind_api(EGL_OPENGL_API)) {
    egl.terminate(impl_->display);
    throw RenderError(egl_error(egl, "eglBindAPI(OpenGL)"));
  }
  // A compatibility-profile context: MuJoCo's renderer uses fixed-function OpenGL.
  const EGLint context_attributes[] = {EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT, EGL_NONE};
  impl_->context = egl.create_context(impl_->display, config, EGL_NO_CONTEXT, context_attributes);
  if (impl_->context == EGL_NO_CONTEXT) {
    egl.terminate(impl_->display);
    throw RenderError(egl_error(egl, "eglCreateContext"));
  }
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (!impl_ || impl_->display == EGL_NO_DISPLAY) return;
  const EglLibrary& egl = impl_->egl;
  egl.make_current(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (impl_->context != EGL_NO_CONTEXT) egl.destroy_context(impl_->display, impl_->context);
  // The display is shared by the process (EGL returns the same one each time): it is not
  // terminated, so that other renderers keep theirs.
}

void OffscreenContext::make_current() {
  // Surfaceless: MuJoCo draws into its own framebuffer object.
  const EglLibrary& egl = impl_->egl;
  if (!egl.make_current(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context)) {
    throw RenderError(egl_error(egl, "eglMakeCurrent"));
  }
}

}  // namespace upkie_rl
