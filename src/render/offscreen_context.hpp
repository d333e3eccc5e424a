#pragma once
/// @file
/// OffscreenContext: an OpenGL context in memory (Mesa's OSMesa, software rendering), so
/// frames render with no display and no GPU.

#include <memory>
#include <vector>

namespace upkie_rl {

/// An OSMesa context made current on the calling thread for its lifetime. OpenGL contexts
/// belong to one thread: create, use and destroy it on the same one.
class OffscreenContext {
 public:
  /// @throws RenderError when Mesa cannot create or bind the context.
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
