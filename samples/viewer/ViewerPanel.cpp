#include "ViewerPanel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

namespace coulomb::viewer {
namespace {

void controls(ViewerState& state, const std::vector<std::string>& solverChoices) {
  if (ImGui::Button(state.paused ? "Run (space)" : "Pause (space)")) state.paused = !state.paused;
  ImGui::SameLine();
  if (ImGui::Button("Step (n)")) state.stepOnce = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset (r)")) state.resetRequested = true;
  ImGui::SameLine();
  if (ImGui::Button("Frame (f)")) state.reframeRequested = true;

  double dtMs = 1e3 * state.timeStep;
  const double lo = 0.1, hi = 50.0;  // [ms]
  if (ImGui::SliderScalar("dt [ms]", ImGuiDataType_Double, &dtMs, &lo, &hi, "%.3f",
                          ImGuiSliderFlags_Logarithmic))
    state.timeStep = std::clamp(dtMs, lo, hi) * 1e-3;
  ImGui::SliderInt("steps/frame", &state.stepsPerFrame, 1, 20);

  const char* current = solverChoices[static_cast<std::size_t>(state.solverIndex)].c_str();
  if (ImGui::BeginCombo("solver", current)) {
    for (std::size_t k = 0; k < solverChoices.size(); ++k) {
      const bool selected = static_cast<int>(k) == state.solverIndex;
      if (ImGui::Selectable(solverChoices[k].c_str(), selected)) {
        state.solverChanged = static_cast<int>(k) != state.solverIndex;
        state.solverIndex = static_cast<int>(k);
      }
    }
    ImGui::EndCombo();
  }
  ImGui::Checkbox("contacts (c)", &state.draw.contacts);
  ImGui::SameLine();
  ImGui::Checkbox("joints (j)", &state.draw.joints);
  ImGui::SameLine();
  ImGui::Checkbox("link frames (l)", &state.draw.linkFrames);
  if (!state.message.empty())
    ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", state.message.c_str());
}

void islandTable(const engine::StepReport& report) {
  constexpr ImGuiTableFlags kFlags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg |
                                     ImGuiTableFlags_ScrollY | ImGuiTableFlags_SizingFixedFit;
  const float height = ImGui::GetTextLineHeightWithSpacing() *
                       static_cast<float>(std::min<std::size_t>(report.islands.size(), 8) + 1.5);
  if (!ImGui::BeginTable("islands", 8, kFlags, ImVec2(0, height))) return;
  for (const char* name :
       {"island", "bodies", "contacts", "solver", "status", "iter", "residual", "ms"})
    ImGui::TableSetupColumn(name);
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableHeadersRow();
  for (const engine::IslandReport& island : report.islands) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("%d", island.island);
    ImGui::TableNextColumn();
    ImGui::Text("%zu", island.bodies);
    ImGui::TableNextColumn();
    ImGui::Text("%zu", island.contacts);
    ImGui::TableNextColumn();
    ImGui::Text("%s%s", island.solve.solver.c_str(), island.attempts.size() > 1 ? " *" : "");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s (%zu attempts)", island.reason().c_str(), island.attempts.size());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(solvers::statusName(island.status));
    ImGui::TableNextColumn();
    ImGui::Text("%d", island.solve.iterations);
    ImGui::TableNextColumn();
    ImGui::Text("%.2e", island.solve.residual);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", 1e3 * island.solve.seconds);
  }
  ImGui::EndTable();
}

void plot(const char* label, const StepHistory& history, const char* format) {
  const std::vector<float>& v = history.values();
  char overlay[64] = "";
  if (!v.empty()) std::snprintf(overlay, sizeof overlay, format, static_cast<double>(v.back()));
  ImGui::PlotLines(label, v.data(), static_cast<int>(v.size()), 0, overlay, FLT_MAX, FLT_MAX,
                   ImVec2(0, 70));
}

}  // namespace

void drawPanel(ViewerState& state, const engine::World& world,
               const std::vector<std::string>& solverChoices, const std::string& title) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(520, 560), ImGuiCond_FirstUseEver);
  ImGui::Begin(title.c_str());
  ImGui::Text("t = %.3f s   step %llu   %zu bodies   %zu joints", world.time(),
              static_cast<unsigned long long>(world.stepCount()), world.bodyCount(),
              world.jointCount());
  controls(state, solverChoices);
  ImGui::Separator();
  if (state.hasReport) {
    const engine::StepReport& r = state.lastReport;
    ImGui::Text("last step: %.3f ms, %zu islands, %zu contact points, %zu fallbacks",
                1e3 * r.seconds, r.islands.size(), r.collision.contactPoints, r.fallbacks());
    if (r.joints.joints > 0)
      ImGui::Text("joints: gap %.2e m, angle %.2e rad", r.joints.maxLinearError,
                  r.joints.maxAngularError);
    if (!r.quarantined.empty())
      ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "quarantined: %s (%s)",
                         r.quarantined.front().name.c_str(), r.quarantined.front().reason.c_str());
    islandTable(r);
  } else {
    ImGui::TextUnformatted("no step yet");
  }
  plot("log10 residual", state.residual, "%.2f");
  plot("ms / step", state.milliseconds, "%.3f ms");
  ImGui::TextDisabled("drag: orbit  right-drag: pan  wheel: zoom  esc: quit");
  ImGui::End();
}

}  // namespace coulomb::viewer
