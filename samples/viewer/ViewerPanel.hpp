#pragma once
// The Dear ImGui panel of the viewer: controls (pause, step, reset, dt, steps per frame, solver,
// drawing toggles), the scene's counts, the last step's per-island StepReport table and the live
// plots. Called between ImGui::NewFrame and ImGui::Render.
#include <coulomb/engine/World.hpp>

#include <string>
#include <vector>

#include "ViewerState.hpp"

namespace coulomb::viewer {

/// `solverChoices[0]` is the scene's own choice; the others are solver names or "auto".
void drawPanel(ViewerState& state, const engine::World& world,
               const std::vector<std::string>& solverChoices, const std::string& title);

}  // namespace coulomb::viewer
