#include "render/offscreen_context.hpp"

#include <GL/osmesa.h>

#include <string>

#include "render/render_error.hpp"

namespace upkie_rl {

struct OffscreenContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  ///< The default framebuffer (MuJoCo draws offscreen).
  int width = 0;
  int height = 0;
};

OffscreenContext::OffscreenContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  // RGBA, 24-bit depth, 8-bit stencil, no accumulation buffer; compatibility profile,
  // which MuJoCo's fixed-function renderer needs.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            8,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl_->context == nullptr) {
    throw RenderError("OSMesa could not create an OpenGL context (is libosmesa6 installed?)");
  }
  impl_->width = width;
  impl_->height = height;
  impl_->buffer.resize(static_cast<std::size_t>(width) * height * 4);
  make_current();
}

OffscreenContext::~OffscreenContext() {
  if (impl_ && impl_->context != nullptr) OSMesaDestroyContext(impl_->context);
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, impl_->width,
                         impl_->height)) {
    throw RenderError("OSMesa could not make its context current (" + std::to_string(impl_->width) +
                      "x" + std::to_string(impl_->height) + ")");
  }
}

}  // namespace upkie_rl
