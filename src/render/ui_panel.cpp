#include "ui_panel.h"

#include <imgui.h>

#include "colour_map.h"

namespace sph::render {

namespace {

void legend(const PanelModel& m) {
  const ColourMode mode = ColourMode(m.colour_mode);
  if (mode == ColourMode::Fluid || mode == ColourMode::Cell) return;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
  const int n = 32;
  for (int i = 0; i < n; ++i) {
    const Vec3 c0 = ramp(float(i) / n);
    const ImU32 col = IM_COL32(int(255 * c0.x), int(255 * c0.y), int(255 * c0.z), 255);
    dl->AddRectFilled(ImVec2(p.x + w * i / n, p.y), ImVec2(p.x + w * (i + 1) / n, p.y + h), col);
  }
  ImGui::Dummy(ImVec2(w, h));
  ImGui::Text("%.3g", double(m.legend.lo));
  ImGui::SameLine(w * 0.5f - 20.0f);
  ImGui::Text("%s", m.legend.unit);
  ImGui::SameLine(w - 40.0f);
  ImGui::Text("%.3g", double(m.legend.hi));
}

}  // namespace

bool surface_controls(bool& surface, SurfaceLook& look) {
  bool changed = ImGui::Checkbox("surface (S)", &surface);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("screen-space fluid surface (smoothed sphere depth) instead of spheres");
  if (!surface) return changed;
  changed |= ImGui::SliderInt("smoothing passes", &look.smoothing_iterations, 0, 20);
  changed |= ImGui::SliderFloat("sphere size", &look.radius_scale, 1.0f, 3.0f, "%.2f x d/2");
  changed |= ImGui::ColorEdit3("water colour", &look.colour.x);
  changed |= ImGui::SliderFloat("absorption [1/m]", &look.absorption, 0.0f, 400.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
  return changed;
}

bool draw_panel(PanelModel& m) {
  bool changed = false;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("SPH");
  ImGui::Text("%s on %s", m.scene.c_str(), m.backend.c_str());
  ImGui::Text("%ld particles, %s", m.particles, m.integrator.c_str());
  ImGui::Separator();
  ImGui::Text("%.1f fps   sim %.1f ms   draw %.1f ms", m.fps, m.sim_ms, m.draw_ms);
  ImGui::Text("t = %.4f s   dt = %.2e s", m.sim_time, m.dt);
  ImGui::Text("simulated / real time: %.3f", m.realtime_ratio);
  ImGui::Text("mean density error: %.2f %%", 100.0 * m.density_error);
  if (m.solver_iterations >= 0)
    ImGui::Text("solve: %d iterations, ends at %.3f %%", m.solver_iterations, 100.0 * m.solver_error);
  for (const std::string& text : m.messages) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.8f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", text.c_str());
    ImGui::PopStyleColor();
  }
  // Open by default when the checks changed what the scene asked for (particles removed or lattices refit).
  if (!m.setup_report.empty() &&
      ImGui::CollapsingHeader("set-up checks", m.setup_changed ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    for (const std::string& line : m.setup_report) ImGui::TextWrapped("%s", line.c_str());
  }
  if (ImGui::CollapsingHeader("ms per step by phase")) {
    for (int p = 0; p < int(Phase::Count); ++p)
      ImGui::Text("%-11s %7.3f", phase_name(Phase(p)), m.phase_per_step.seconds[std::size_t(p)]);
  }
  ImGui::Separator();
  changed |= ImGui::Checkbox("paused (space)", &m.paused);
  changed |= ImGui::SliderInt("substeps (+/-)", &m.substeps, 1, 64);
  ImGui::PushItemWidth(-ImGui::GetFontSize() * 10.5f);  // room for the labels right of the sliders
  changed |= ImGui::SliderFloat("viscosity [Pa s]", &m.viscosity, 0.0f, 20.0f, "%.4g", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the first fluid's viscosity; the scene's other fluids scale with it, keeping their ratios");
  changed |= ImGui::SliderFloat("speed of sound", &m.speed_of_sound, 0.5f, 200.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("near stiffness", &m.near_stiffness, 0.0f, 100.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("max time step", &m.dt_max, 1e-5f, 1e-2f, "%.2e", ImGuiSliderFlags_Logarithmic);
  ImGui::PopItemWidth();
  const char* modes[] = {"fluid", "speed", "density error", "pressure", "grid cell"};
  changed |= ImGui::Combo("colour (C)", &m.colour_mode, modes, IM_ARRAYSIZE(modes));
  changed |= ImGui::Checkbox("flat points (V)", &m.flat_points);
  changed |= surface_controls(m.surface, m.look);
  if (m.wall_particles > 0) {
    const std::string label = "wall particles (G): " + std::to_string(m.wall_particles);
    changed |= ImGui::Checkbox(label.c_str(), &m.show_walls);
  }
  legend(m);
  if (ImGui::CollapsingHeader("controls")) {
    ImGui::TextUnformatted(
        "space pause   N single step   R reset\n"
        "[ ] previous / next scene   B next back end\n"
        "arrows tilt gravity   J / L push sideways\n"
        "ctrl + left / right drag: pull / push water\n"
        "left drag orbit   right drag pan   wheel zoom\n"
        "+ / - substeps   C colour   V points   S surface\n"
        "P screenshot   Esc quit");
  }
  ImGui::End();
  return changed;
}

}  // namespace sph::render
