// runViewer (Viewer.hpp): the GLFW window, input, the stepping loop and the screenshot.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl2.h>
#include <imgui.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "Image.hpp"
#include "SceneBounds.hpp"
#include "Viewer.hpp"
#include "ViewerPanel.hpp"

namespace coulomb::viewer {
namespace {

// Owns GLFW and the ImGui context for the viewer's lifetime (released in reverse order).
struct WindowSession {
  GLFWwindow* window = nullptr;
  bool imgui = false;
  ~WindowSession() {
    if (imgui) {
      ImGui_ImplOpenGL2_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    if (window != nullptr) glfwDestroyWindow(window);
    glfwTerminate();
  }
};

struct InputState {
  ViewerState* state = nullptr;
  Camera* camera = nullptr;
};

void onScroll(GLFWwindow* window, double, double dy) {
  auto* input = static_cast<InputState*>(glfwGetWindowUserPointer(window));
  if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureMouse) return;
  input->camera->zoom(dy);
}

void onKey(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureKeyboard) return;
  ViewerState& s = *static_cast<InputState*>(glfwGetWindowUserPointer(window))->state;
  switch (key) {
    case GLFW_KEY_SPACE:
      s.paused = !s.paused;
      break;
    case GLFW_KEY_N:
    case GLFW_KEY_RIGHT:
      s.stepOnce = true;
      break;
    case GLFW_KEY_R:
      s.resetRequested = true;
      break;
    case GLFW_KEY_F:
      s.reframeRequested = true;
      break;
    case GLFW_KEY_C:
      s.draw.contacts = !s.draw.contacts;
      break;
    case GLFW_KEY_J:
      s.draw.joints = !s.draw.joints;
      break;
    case GLFW_KEY_L:
      s.draw.linkFrames = !s.draw.linkFrames;
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      s.quitRequested = true;
      break;
    default:
      break;
  }
}

void onGlfwError(int code, const char* description) {
  (void)code;
  (void)description;  // reported through the failing call's exception instead
}

// Solver choices: the scene's own, "auto", then every registry name.
std::vector<std::string> solverChoices(engine::World& world) {
  std::vector<std::string> choices{"(scene's choice)", "auto"};
  for (const std::string& name : world.solverRegistry().names()) choices.push_back(name);
  return choices;
}

// Every island solved by `name`: the world's solver, and no body keeps an override.
void applySolver(engine::World& world, const std::string& name) {
  world.setSolver(coulomb::solvers::solverChoice(name));
  for (std::size_t i = 0; i < world.state().size(); ++i) {
    const geometry::BodyId id = world.idAt(i);
    if (id.valid()) world.setSolverOverride(id, std::nullopt);
  }
}

void record(ViewerState& state, const engine::StepReport& report) {
  double residual = 0.0;
  for (const engine::IslandReport& island : report.islands)
    if (std::isfinite(island.solve.residual)) residual = std::max(residual, island.solve.residual);
  state.residual.push(static_cast<float>(std::log10(std::max(residual, 1e-16))));
  state.milliseconds.push(static_cast<float>(1e3 * report.seconds));
  state.lastReport = report;
  state.hasReport = true;
}

void handleMouse(GLFWwindow* window, Camera& camera, double& lastX, double& lastY) {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window, &x, &y);
  const double dx = x - lastX, dy = y - lastY;
  lastX = x;
  lastY = y;
  if (ImGui::GetIO().WantCaptureMouse) return;
  int width = 0, height = 0;
  glfwGetWindowSize(window, &width, &height);
  const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
  if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
      (shift && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS))
    camera.pan(dx, dy, height);
  else if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
    camera.orbit(dx, dy);
}

Image readFramebuffer(int width, int height) {
  std::vector<std::uint8_t> rgba(std::size_t(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  return imageFromGlRgba(rgba, width, height);
}

}  // namespace

void runViewer(const WorldFactory& makeWorld, double timeStep, const ViewOptions& options,
               const StepHook& beforeStep) {
  glfwSetErrorCallback(onGlfwError);
  WindowSession session;
  if (glfwInit() == GLFW_FALSE)
    throw std::runtime_error(
        "cannot open a window: no display (set DISPLAY, or run under `xvfb-run -a`; "
        "`coulomb render` needs no display)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 2);  // legacy GL: the same drawing code as OSMesa
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  session.window =
      glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (session.window == nullptr)
    throw std::runtime_error("cannot open an OpenGL 2.1 window (GLFW refused)");
  GLFWwindow* window = session.window;
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.frames > 0 ? 0 : 1);  // a scripted run does not wait for vsync

  ViewerState state;
  state.timeStep = timeStep;
  Camera camera;
  InputState input{&state, &camera};
  glfwSetWindowUserPointer(window, &input);
  // Ours first: ImGui's GLFW backend chains to callbacks installed before it.
  glfwSetScrollCallback(window, onScroll);
  glfwSetKeyCallback(window, onKey);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  session.imgui = true;
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL2_Init();

  auto world = std::make_unique<engine::World>(makeWorld());
  bool fresh = true;  // for beforeStep
  const std::vector<std::string> choices = solverChoices(*world);
  SceneDrawer drawer;
  int fbWidth = 0, fbHeight = 0;
  glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
  camera.frame(sceneBounds(*world), static_cast<double>(fbWidth) / std::max(1, fbHeight));
  double lastX = 0.0, lastY = 0.0;
  glfwGetCursorPos(window, &lastX, &lastY);

  for (std::uint64_t frame = 1; !glfwWindowShouldClose(window) && !state.quitRequested; ++frame) {
    glfwPollEvents();
    handleMouse(window, camera, lastX, lastY);
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    if (state.resetRequested) {
      state.resetRequested = false;
      world = std::make_unique<engine::World>(makeWorld());
      fresh = true;
      drawer.clear();
      state.solverChanged = state.solverIndex != 0;
      state.hasReport = false;
      state.residual.clear();
      state.milliseconds.clear();
    }
    if (state.solverChanged) {
      state.solverChanged = false;
      state.message.clear();
      try {
        if (state.solverIndex > 0)
          applySolver(*world, choices[std::size_t(state.solverIndex)]);
        else
          state.resetRequested = true;  // the scene's own choice: rebuild it
      } catch (const std::exception& e) {
        state.message = e.what();
      }
    }
    if (state.reframeRequested) {
      state.reframeRequested = false;
      camera.frame(sceneBounds(*world), static_cast<double>(fbWidth) / std::max(1, fbHeight));
    }
    const int steps = state.paused ? (state.stepOnce ? 1 : 0) : state.stepsPerFrame;
    state.stepOnce = false;
    for (int k = 0; k < steps; ++k) {
      if (beforeStep) beforeStep(*world, std::exchange(fresh, false));
      record(state, world->step(state.timeStep));
    }

    drawer.draw(*world, camera, fbWidth, fbHeight, state.draw);
    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    drawPanel(state, *world, choices, options.title);
    ImGui::Render();
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());

    const bool last = options.frames > 0 && frame >= options.frames;
    if (last && !options.screenshot.empty())
      writePng(options.screenshot, readFramebuffer(fbWidth, fbHeight));
    glfwSwapBuffers(window);
    if (last) break;
  }
}

}  // namespace coulomb::viewer
