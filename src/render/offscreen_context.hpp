#pragma once
/// @file
/// OffscreenContext: an OpenGL context with no window (EGL on Mesa's surfaceless platform,
/// llvmpipe software rendering without a GPU), so frames render with no display.

#include <memory>

namespace upkie_rl {

/// An EGL context made current on the calling thread for its lifetime. OpenGL contexts
/// belong to one thread: create, use and destroy it on the same one.
class OffscreenContext {
 public:
  /// @throws RenderError when Mesa cannot create or bind the context. The size is that of
  ///         the frames drawn (MuJoCo renders into its own offscreen framebuffer).
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  /// Makes the context current on the calling thread again (after another context was).
  void make_current();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace upkie_rl
