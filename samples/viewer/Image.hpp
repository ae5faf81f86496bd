#pragma once
// An RGB image, top row first, and the writers the renderer and the viewer use: PNG through
// stb_image_write and animated GIF through giflib (Debian libstb-dev, libgif-dev).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

struct GifFileType;

namespace coulomb::viewer {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes per pixel, rows top to bottom

  /// Pixels whose colour differs from `background` by more than `tolerance` in some channel.
  [[nodiscard]] std::size_t countDifferent(const std::uint8_t background[3],
                                           int tolerance = 8) const;
};

/// Flips OpenGL's bottom-up RGBA rows (glReadPixels) into an Image.
Image imageFromGlRgba(const std::vector<std::uint8_t>& rgba, int width, int height);

/// Throws std::runtime_error naming the path if it cannot be written.
void writePng(const std::string& path, const Image& image);

/// An animated GIF written frame by frame; each frame gets its own 256-colour palette
/// (giflib's median-cut GifQuantizeBuffer) and the animation loops.
class GifWriter {
 public:
  /// delayCentiseconds: time each frame is shown. Throws std::runtime_error naming the path.
  GifWriter(const std::string& path, int width, int height, int delayCentiseconds);
  ~GifWriter();
  GifWriter(const GifWriter&) = delete;
  GifWriter& operator=(const GifWriter&) = delete;

  void add(const Image& frame);  // must have the writer's size
  void finish();                 // writes the trailer; also done by the destructor

 private:
  void fail(const std::string& what, int error) const;
  std::string path_;
  int width_;
  int height_;
  int delay_;
  GifFileType* gif_ = nullptr;
  int frames_ = 0;
};

}  // namespace coulomb::viewer
