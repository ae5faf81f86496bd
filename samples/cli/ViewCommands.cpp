// `coulomb view` and `coulomb render` (docs/viewer.md). Both exist in every build; without the
// optional viewer component (COULOMB_BUILD_VIEWER) they say how to enable it.
#include <iostream>
#include <memory>
#include <optional>

#include "Commands.hpp"
#include "SceneRun.hpp"

#ifdef COULOMB_HAVE_VIEWER
#include "Game.hpp"
#include "Renderer.hpp"
#include "Viewer.hpp"
#endif

namespace coulomb::cli {
namespace {

struct ViewCommandOptions {
  std::string scene;
  SceneOverrides overrides;
  std::uint64_t frames = 0;
  std::string screenshot;
  std::optional<int> width;
  std::optional<int> height;
  std::uint64_t every = 1;
  std::string out;
  bool noContacts = false;
  bool noJoints = false;
};

void addSceneOptions(CLI::App* command, ViewCommandOptions& o) {
  command
      ->add_option(
          "scene", o.scene,
          "Built-in scene name, path to a .json scene or a .urdf robot (placed on a floor); "
          "`view embedding` runs the game-like sample of samples/embedding")
      ->required();
  command->add_flag("--floating", o.overrides.urdfFloating, "A .urdf robot gets a floating base");
  command->add_flag("--limp", o.overrides.urdfLimp, "A .urdf robot's joints are not held");
  command->add_flag("--maximal", o.overrides.urdfMaximal,
                    "A .urdf robot as free bodies and maximal joints (needs --limp)");
  command->add_option("--solver", o.overrides.solver,
                      "Contact solver of every island (as `coulomb run --solver`)");
  command->add_option("--dt", o.overrides.timeStep, "Time step [s] (default: the scene's)");
  command->add_option("--mu", o.overrides.friction, "Friction coefficient of every material");
  command->add_option("--width", o.width, "Image or window width [pixels]")
      ->check(CLI::Range(16, 8192));
  command->add_option("--height", o.height, "Image or window height [pixels]")
      ->check(CLI::Range(16, 8192));
}

#ifdef COULOMB_HAVE_VIEWER

// `coulomb view embedding`: the game-like sample of samples/embedding, driven frame by frame.
void viewGame(viewer::ViewOptions options) {
  options.title = "embedding (samples/embedding)";
  auto bodies = std::make_shared<samples::GameBodies>();
  auto director = std::make_shared<std::optional<samples::GameDirector>>();
  const samples::GameSettings settings;
  viewer::runViewer([bodies] { return samples::makeGameWorld(*bodies); }, settings.frameTime,
                    options,
                    [bodies, director](engine::World& world, bool fresh) {
                      if (fresh) director->emplace(*bodies);
                      (*director)->beforeStep(world);
                    });
}

void view(const ViewCommandOptions& o) {
  if (o.scene == "embedding") {
    viewer::ViewOptions options;
    options.width = o.width.value_or(options.width);
    options.height = o.height.value_or(options.height);
    options.frames = o.frames;
    options.screenshot = o.screenshot;
    viewGame(options);
    if (!o.screenshot.empty()) std::cout << "screenshot " << o.screenshot << "\n";
    return;
  }
  const engine::io::Scene scene = loadScene(o.scene, o.overrides);
  viewer::ViewOptions options;
  options.title = scene.name;
  options.width = o.width.value_or(options.width);
  options.height = o.height.value_or(options.height);
  options.frames = o.frames;
  options.screenshot = o.screenshot;
  try {
    viewer::runViewer([&scene] { return buildWorldFor(scene); }, scene.settings.timeStep, options);
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const CommandError*>(&e) != nullptr) throw;
    throw CommandError(std::string("view: ") + e.what());
  }
  if (!o.screenshot.empty()) std::cout << "screenshot " << o.screenshot << "\n";
}

void render(const ViewCommandOptions& o) {
  const engine::io::Scene scene = loadScene(o.scene, o.overrides);
  engine::World world = buildWorldFor(scene);
  viewer::RenderOptions options;
  options.steps = scene.steps;
  options.every = o.every;
  options.out = o.out;
  options.width = o.width.value_or(options.width);
  options.height = o.height.value_or(options.height);
  options.draw.contacts = !o.noContacts;
  options.draw.joints = !o.noJoints;
  viewer::RenderResult result;
  try {
    result = viewer::renderRun(world, scene.settings.timeStep, options);
  } catch (const std::runtime_error& e) {
    throw CommandError(e.what());
  }
  std::cout << "rendered " << result.frames << " frames of " << scene.name << " (" << options.width
            << "x" << options.height << ", " << scene.steps << " steps of "
            << scene.settings.timeStep << " s, every " << options.every << ") to " << options.out
            << "\n";
}

#else

[[noreturn]] void notBuilt(const char* command) {
  throw CommandError(std::string("coulomb ") + command +
                         ": this build has no viewer component. Install the Debian packages "
                         "libglfw3-dev libimgui-dev libosmesa6-dev libstb-dev libgif-dev (and "
                         "xvfb for headless CI), then reconfigure with -DCOULOMB_BUILD_VIEWER=ON "
                         "(AUTO, the default, turns it on when they are found); see docs/viewer.md",
                     2);
}
void view(const ViewCommandOptions&) {
  notBuilt("view");
}
void render(const ViewCommandOptions&) {
  notBuilt("render");
}

#endif

}  // namespace

void registerViewCommands(CLI::App& app) {
  auto viewOptions = std::make_shared<ViewCommandOptions>();
  CLI::App* viewCommand = app.add_subcommand(
      "view", "Watch a scene in a window: orbit camera, run controls, solver reports (viewer)");
  addSceneOptions(viewCommand, *viewOptions);
  viewCommand
      ->add_option("--frames", viewOptions->frames,
                   "Draw this many frames (stepping), then exit (for CI under xvfb-run)")
      ->check(CLI::PositiveNumber);
  viewCommand
      ->add_option("--screenshot", viewOptions->screenshot,
                   "Write the last frame as PNG (with --frames)")
      ->needs("--frames");
  viewCommand->callback([viewOptions] { view(*viewOptions); });

  auto renderOptions = std::make_shared<ViewCommandOptions>();
  CLI::App* renderCommand = app.add_subcommand(
      "render", "Render a scene offscreen to PNG frames or an animated GIF (no display needed)");
  addSceneOptions(renderCommand, *renderOptions);
  renderCommand
      ->add_option("--steps", renderOptions->overrides.steps,
                   "Number of steps (default: the scene's)")
      ->check(CLI::PositiveNumber);
  renderCommand->add_option("--every", renderOptions->every, "A frame every K steps (default 1)")
      ->check(CLI::PositiveNumber);
  renderCommand
      ->add_option("--out", renderOptions->out,
                   "Folder for frame_0000.png, ... or a FILE.gif for one animated GIF")
      ->required();
  renderCommand->add_flag("--no-contacts", renderOptions->noContacts, "Do not draw contacts");
  renderCommand->add_flag("--no-joints", renderOptions->noJoints, "Do not draw joint frames");
  renderCommand->callback([renderOptions] { render(*renderOptions); });
}

}  // namespace coulomb::cli
