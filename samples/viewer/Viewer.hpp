#pragma once
// The interactive viewer (`coulomb view`): a GLFW window drawing the World with SceneDrawer, an
// orbit camera, and a Dear ImGui panel with the run controls, the last step's per-island report
// and live plots of the residual and the step time. docs/viewer.md lists keys and mouse.
#include <coulomb/engine/World.hpp>

#include <cstdint>
#include <functional>
#include <string>

namespace coulomb::viewer {

struct ViewOptions {
  std::string title = "coulomb";  // window title (the scene's name)
  int width = 1280;               // [pixels] initial window size
  int height = 800;
  std::uint64_t frames = 0;  // > 0: draw this many frames (stepping), write the screenshot, exit
  std::string screenshot;    // PNG of the last frame (window contents, panel included)
};

/// Builds the scene's World afresh: at start and on every reset.
using WorldFactory = std::function<engine::World()>;

/// Called before every step the viewer takes: a game's logic (spawning, kinematic targets,
/// reading the last step's events). `fresh` is true on the first call after the World was built
/// or rebuilt (reset). Empty: none.
using StepHook = std::function<void(engine::World& world, bool fresh)>;

/// Opens the window and runs until it is closed (or for options.frames frames). Throws
/// std::runtime_error when no window can be opened (no display: use `xvfb-run -a`) or the
/// screenshot cannot be written.
void runViewer(const WorldFactory& makeWorld, double timeStep, const ViewOptions& options,
               const StepHook& beforeStep = {});

}  // namespace coulomb::viewer
