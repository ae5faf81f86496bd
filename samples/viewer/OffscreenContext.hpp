#pragma once
// An OpenGL context without a window: Mesa's OSMesa (software rendering into our own buffer),
// so `coulomb render` and the renderer tests run on machines with neither display nor GPU.
#include <cstdint>
#include <vector>

#include "Image.hpp"

struct osmesa_context;

namespace coulomb::viewer {

class OffscreenContext {
 public:
  /// Creates an RGBA context with a 24-bit depth buffer and makes it current. Throws
  /// std::runtime_error on a size outside [1, 8192] or when Mesa refuses.
  OffscreenContext(int width, int height);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }
  /// What has been drawn so far (waits for GL to finish).
  [[nodiscard]] Image image() const;

 private:
  int width_;
  int height_;
  std::vector<std::uint8_t> buffer_;  // RGBA, bottom row first, written by Mesa
  osmesa_context* context_ = nullptr;
};

}  // namespace coulomb::viewer
