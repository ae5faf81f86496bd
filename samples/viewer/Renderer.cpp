#include "Renderer.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "OffscreenContext.hpp"
#include "SceneBounds.hpp"

namespace coulomb::viewer {

Camera autoCamera(const engine::World& world, double aspect) {
  Camera camera;
  camera.frame(sceneBounds(world), aspect);
  return camera;
}

Image renderImage(const engine::World& world, int width, int height, const DrawOptions& options) {
  OffscreenContext context(width, height);
  SceneDrawer drawer;
  drawer.draw(world, autoCamera(world, static_cast<double>(width) / height), width, height,
              options);
  return context.image();
}

RenderResult renderRun(engine::World& world, double timeStep, const RenderOptions& options) {
  if (options.out.empty()) throw std::runtime_error("render: no output (--out DIR or FILE.gif)");
  if (options.every == 0) throw std::runtime_error("render: --every must be >= 1");
  if (!std::isfinite(timeStep) || timeStep <= 0.0)
    throw std::runtime_error("render: the time step must be finite and > 0 s");
  const bool gif = options.out.ends_with(".gif") || options.out.ends_with(".GIF");
  RenderResult result;
  std::unique_ptr<GifWriter> writer;
  if (gif) {
    const double centiseconds = std::round(100.0 * timeStep * static_cast<double>(options.every));
    writer = std::make_unique<GifWriter>(options.out, options.width, options.height,
                                         static_cast<int>(std::min(centiseconds, 6000.0)));
    result.files.push_back(options.out);
  } else {
    std::error_code error;
    std::filesystem::create_directories(options.out, error);
    if (error || !std::filesystem::is_directory(options.out))
      throw std::runtime_error("render: cannot create the folder '" + options.out + "'");
  }

  OffscreenContext context(options.width, options.height);
  SceneDrawer drawer;
  const Camera camera = autoCamera(world, static_cast<double>(options.width) / options.height);
  auto emit = [&] {
    drawer.draw(world, camera, options.width, options.height, options.draw);
    const Image image = context.image();
    if (writer) {
      writer->add(image);
    } else {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04zu.png", result.frames);
      const std::string path = (std::filesystem::path(options.out) / name).string();
      writePng(path, image);
      result.files.push_back(path);
    }
    ++result.frames;
  };
  emit();
  for (std::uint64_t step = 1; step <= options.steps; ++step) {
    world.step(timeStep);
    if (step % options.every == 0) emit();
  }
  if (writer) writer->finish();
  return result;
}

}  // namespace coulomb::viewer
