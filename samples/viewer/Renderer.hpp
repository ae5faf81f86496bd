#pragma once
// Headless rendering (`coulomb render`): runs a World and writes frames offscreen (OSMesa) as
// PNG files in a folder or as one animated GIF. No window, no display, no GPU needed.
#include <coulomb/engine/World.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "Camera.hpp"
#include "Image.hpp"
#include "SceneDrawer.hpp"

namespace coulomb::viewer {

/// The automatic camera: looks at sceneBounds(world) from the default yaw and pitch, far enough
/// back to hold the whole sphere (aspect = width / height).
Camera autoCamera(const engine::World& world, double aspect);

/// One frame of the world as it is now, from autoCamera.
Image renderImage(const engine::World& world, int width, int height,
                  const DrawOptions& options = {});

struct RenderOptions {
  std::uint64_t steps = 0;  // steps of the run after the first frame
  std::uint64_t every = 1;  // a frame every this many steps (and one of the initial state)
  std::string out;          // a folder (frame_0000.png, ...) or a path ending in .gif
  int width = 480;          // [pixels]
  int height = 360;
  DrawOptions draw;
};

struct RenderResult {
  std::size_t frames = 0;
  std::vector<std::string> files;  // the PNG files, or the one GIF
};

/// Frame 0 is the initial state, then one after every `every` steps of `timeStep` up to `steps`:
/// 1 + steps / every frames. The camera is framed once on the initial state and stays put. A GIF
/// shows each frame for every * timeStep (real time, at least 2 centiseconds). Throws
/// std::runtime_error naming the output on a write failure or bad options.
RenderResult renderRun(engine::World& world, double timeStep, const RenderOptions& options);

}  // namespace coulomb::viewer
