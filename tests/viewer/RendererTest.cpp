// Offscreen rendering (samples/viewer/Renderer, OSMesa): images of the asked size that are not
// blank, differ between two scenes, and PNG/GIF files with the right headers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <coulomb/io/SceneLoader.hpp>

#include "Renderer.hpp"
#include "scenes/SceneRegistry.hpp"

namespace coulomb::viewer {
namespace {

engine::World builtin(const std::string& name) {
  return engine::io::buildWorld(scenes::loadBuiltinScene(name));
}

std::vector<unsigned char> readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t bigEndian32(const std::vector<unsigned char>& b, std::size_t at) {
  return (std::uint32_t(b[at]) << 24) | (std::uint32_t(b[at + 1]) << 16) |
         (std::uint32_t(b[at + 2]) << 8) | b[at + 3];
}

TEST(Renderer, ImageHasTheSizeAskedAndIsNotBlank) {
  const engine::World world = builtin("pyramid_10");
  const Image image = renderImage(world, 160, 120);
  ASSERT_EQ(image.width, 160);
  ASSERT_EQ(image.height, 120);
  ASSERT_EQ(image.rgb.size(), 160u * 120u * 3u);
  // The framed pyramid covers a good part of the picture, and not all of it (the sky shows).
  const std::size_t drawn = image.countDifferent(kBackground);
  EXPECT_GT(drawn, 160u * 120u / 10);
  EXPECT_LT(drawn, 160u * 120u);
}

TEST(Renderer, TwoScenesGiveDifferentPictures) {
  const Image pyramid = renderImage(builtin("pyramid_10"), 160, 120);
  const Image loop = renderImage(builtin("double_loop"), 160, 120);
  ASSERT_EQ(pyramid.rgb.size(), loop.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < pyramid.rgb.size(); i += 3)
    differ += (pyramid.rgb[i] != loop.rgb[i] || pyramid.rgb[i + 1] != loop.rgb[i + 1] ||
               pyramid.rgb[i + 2] != loop.rgb[i + 2])
                  ? 1
                  : 0;
  EXPECT_GT(differ, 160u * 120u / 10);
  EXPECT_GT(loop.countDifferent(kBackground), 160u * 120u / 400);  // the thin track is drawn
}

TEST(Renderer, RenderingIsRepeatable) {
  const engine::World world = builtin("box_on_plane");
  EXPECT_EQ(renderImage(world, 64, 48).rgb, renderImage(world, 64, 48).rgb);
}

TEST(Renderer, WritesPngFramesAndAnAnimatedGif) {
  const auto dir = std::filesystem::path(COULOMB_BINARY_DIR) / "tests" / "viewer_frames";
  std::filesystem::remove_all(dir);
  engine::World world = builtin("box_on_plane");
  RenderOptions options;
  options.steps = 6;
  options.every = 3;
  options.out = dir.string();
  options.width = 96;
  options.height = 64;
  options.draw.contacts = false;  // fewer GL states: each costs llvmpipe a shader compile
  const RenderResult pngs = renderRun(world, 0.01, options);
  ASSERT_EQ(pngs.frames, 3u);  // initial state, after 3 and after 6 steps
  ASSERT_EQ(pngs.files.size(), 3u);
  const std::vector<unsigned char> png = readFile(pngs.files.back());
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(std::string(png.begin() + 1, png.begin() + 4), "PNG");
  EXPECT_EQ(bigEndian32(png, 16), 96u);  // IHDR width and height
  EXPECT_EQ(bigEndian32(png, 20), 64u);

  options.out = (dir / "run.gif").string();
  engine::World again = builtin("box_on_plane");
  const RenderResult gif = renderRun(again, 0.01, options);
  EXPECT_EQ(gif.frames, 3u);
  const std::vector<unsigned char> bytes = readFile(options.out);
  ASSERT_GT(bytes.size(), 13u);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 6), "GIF89a");
  EXPECT_EQ(bytes[6] | (bytes[7] << 8), 96);  // logical screen width and height
  EXPECT_EQ(bytes[8] | (bytes[9] << 8), 64);
}

TEST(Renderer, BadOptionsAreClearErrors) {
  engine::World world = builtin("projectile");
  RenderOptions options;
  options.out = "/proc/no_such_dir/frames";
  EXPECT_THROW(renderRun(world, 0.01, options), std::runtime_error);
  options.out = "x.gif";
  options.every = 0;
  EXPECT_THROW(renderRun(world, 0.01, options), std::runtime_error);
  EXPECT_THROW(renderImage(world, 0, 10), std::runtime_error);
}

}  // namespace
}  // namespace coulomb::viewer
