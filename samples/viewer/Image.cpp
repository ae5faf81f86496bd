#include "Image.hpp"

#include <fcntl.h>
#include <gif_lib.h>
#include <stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace coulomb::viewer {

std::size_t Image::countDifferent(const std::uint8_t background[3], int tolerance) const {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) {
    bool differs = false;
    for (int c = 0; c < 3; ++c)
      differs |= std::abs(int(rgb[i + c]) - int(background[c])) > tolerance;
    n += differs ? 1 : 0;
  }
  return n;
}

Image imageFromGlRgba(const std::vector<std::uint8_t>& rgba, int width, int height) {
  Image image{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 3)};
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* src = rgba.data() + std::size_t(height - 1 - y) * width * 4;
    std::uint8_t* dst = image.rgb.data() + std::size_t(y) * width * 3;
    for (int x = 0; x < width; ++x) std::copy_n(src + 4 * x, 3, dst + 3 * x);
  }
  return image;
}

void writePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != std::size_t(image.width) * image.height * 3)
    throw std::runtime_error("cannot write '" + path + "': empty or inconsistent image");
  if (stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(),
                     image.width * 3) == 0)
    throw std::runtime_error("cannot write the PNG file '" + path + "'");
}

GifWriter::GifWriter(const std::string& path, int width, int height, int delayCentiseconds)
    : path_(path), width_(width), height_(height), delay_(std::max(2, delayCentiseconds)) {
  int error = 0;
  // Our own open(2): EGifOpenFileName would create the file readable by its owner only.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd < 0) fail("cannot create", E_GIF_ERR_OPEN_FAILED);
  gif_ = EGifOpenFileHandle(fd, &error);  // owns fd from here (closed by EGifCloseFile)
  if (gif_ == nullptr) {
    ::close(fd);
    fail("cannot open", error);
  }
  EGifSetGifVersion(gif_, true);  // GIF89a: needed for the delay and loop extensions
  if (EGifPutScreenDesc(gif_, width, height, 8, 0, nullptr) == GIF_ERROR)
    fail("cannot write the screen of", gif_->Error);
  // NETSCAPE2.0 application extension: loop forever (count 0).
  const unsigned char loop[3] = {1, 0, 0};
  if (EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, 11, "NETSCAPE2.0") == GIF_ERROR ||
      EGifPutExtensionBlock(gif_, 3, loop) == GIF_ERROR ||
      EGifPutExtensionTrailer(gif_) == GIF_ERROR)
    fail("cannot write the loop extension of", gif_->Error);
}

GifWriter::~GifWriter() {
  try {
    finish();
  } catch (const std::runtime_error&) {
    // a destructor cannot report; finish() explicitly to see the error
  }
}

void GifWriter::fail(const std::string& what, int error) const {
  const char* reason = GifErrorString(error);
  throw std::runtime_error(what + " the GIF file '" + path_ + "'" +
                           (reason ? std::string(": ") + reason : std::string()));
}

void GifWriter::add(const Image& frame) {
  if (gif_ == nullptr) throw std::runtime_error("GIF file '" + path_ + "' already finished");
  if (frame.width != width_ || frame.height != height_)
    throw std::runtime_error("GIF file '" + path_ + "': frame size differs from the first");
  const std::size_t n = std::size_t(width_) * height_;
  std::vector<GifByteType> r(n), g(n), b(n), indices(n);
  for (std::size_t i = 0; i < n; ++i) {
    r[i] = frame.rgb[3 * i];
    g[i] = frame.rgb[3 * i + 1];
    b[i] = frame.rgb[3 * i + 2];
  }
  int colours = 256;
  std::vector<GifColorType> palette(256);
  if (GifQuantizeBuffer(width_, height_, &colours, r.data(), g.data(), b.data(), indices.data(),
                        palette.data()) == GIF_ERROR)
    fail("cannot quantize a frame of", E_GIF_ERR_NOT_ENOUGH_MEM);
  ColorMapObject* map = GifMakeMapObject(256, palette.data());
  GraphicsControlBlock control{DISPOSAL_UNSPECIFIED, false, delay_, NO_TRANSPARENT_COLOR};
  GifByteType extension[4];
  EGifGCBToExtension(&control, extension);
  const bool ok = EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, 4, extension) != GIF_ERROR &&
                  EGifPutImageDesc(gif_, 0, 0, width_, height_, false, map) != GIF_ERROR;
  GifFreeMapObject(map);
  if (!ok) fail("cannot write a frame of", gif_->Error);
  for (int y = 0; y < height_; ++y)
    if (EGifPutLine(gif_, indices.data() + std::size_t(y) * width_, width_) == GIF_ERROR)
      fail("cannot write a frame of", gif_->Error);
  ++frames_;
}

void GifWriter::finish() {
  if (gif_ == nullptr) return;
  int error = 0;
  const int status = EGifCloseFile(gif_, &error);  // frees gif_ whatever the outcome
  gif_ = nullptr;
  if (status == GIF_ERROR) fail("cannot close", error);
}

}  // namespace coulomb::viewer
