#include "OffscreenContext.hpp"

#include <GL/osmesa.h>

#include <stdexcept>
#include <string>

// LeakSanitizer (COULOMB_SANITIZE builds) reads this hook: Mesa keeps a few allocations for the
// life of the process (Debian 12, Mesa 22.3.6: 480 bytes in 5 blocks from OSMesaCreateContextExt
// and OSMesaMakeCurrent, not freed by OSMesaDestroyContext). They are Mesa's; ours stay checked.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libLLVM-15.so\nleak:libglapi.so\n";
}

namespace coulomb::viewer {

OffscreenContext::OffscreenContext(int width, int height) : width_(width), height_(height) {
  constexpr int kMaxSize = 8192;
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize)
    throw std::runtime_error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                             " is outside 1..8192 pixels");
  buffer_.assign(std::size_t(width) * height * 4, 0);
  context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (context_ == nullptr) throw std::runtime_error("OSMesa could not create a GL context");
  if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(context_);
    throw std::runtime_error("OSMesa could not make its GL context current");
  }
}

OffscreenContext::~OffscreenContext() {
  OSMesaDestroyContext(context_);
}

Image OffscreenContext::image() const {
  glFinish();
  return imageFromGlRgba(buffer_, width_, height_);
}

}  // namespace coulomb::viewer
