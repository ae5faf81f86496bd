#pragma once
// What the viewer's panel edits and shows: run controls, drawing toggles, the last StepReport and
// the plotted history. Plain data shared by ViewerApp (the loop) and ViewerPanel (the widgets).
#include <coulomb/engine/StepReport.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "SceneDrawer.hpp"

namespace coulomb::viewer {

/// The last `capacity` values of a per-step quantity, oldest first, for ImGui::PlotLines.
class StepHistory {
 public:
  explicit StepHistory(std::size_t capacity = 600) : capacity_(capacity) {}
  void push(float value) {
    if (values_.size() == capacity_) values_.erase(values_.begin());
    values_.push_back(value);
  }
  void clear() { values_.clear(); }
  [[nodiscard]] const std::vector<float>& values() const { return values_; }

 private:
  std::size_t capacity_;
  std::vector<float> values_;
};

struct ViewerState {
  // Run controls (set by keys and the panel, consumed by the loop).
  bool paused = false;
  bool stepOnce = false;  // one step while paused
  bool resetRequested = false;
  bool reframeRequested = false;
  bool quitRequested = false;
  double timeStep = 0.01;  // [s] h of each step (the scene's at start)
  int stepsPerFrame = 1;
  int solverIndex = 0;  // into the solver choices; 0 = the scene's own choice
  bool solverChanged = false;
  std::string message;  // last error (e.g. a solver the World refused)
  DrawOptions draw;

  // What the last step did.
  engine::StepReport lastReport;
  bool hasReport = false;
  StepHistory residual;      // log10 of the largest island residual of each step
  StepHistory milliseconds;  // wall clock of each step [ms]
};

}  // namespace coulomb::viewer
