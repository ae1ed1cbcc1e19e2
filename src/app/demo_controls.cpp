#include "demo_controls.h"

#include <algorithm>
#include <cmath>

namespace sph {

Vec3 tilted_gravity(Vec3 g0, float tilt_x, float tilt_z) {
  const float cz = std::cos(tilt_z), sz = std::sin(tilt_z), cx = std::cos(tilt_x), sx = std::sin(tilt_x);
  const Vec3 gr{cz * g0.x - sz * g0.y, sz * g0.x + cz * g0.y, g0.z};
  return Vec3{gr.x, cx * gr.y - sx * gr.z, sx * gr.y + cx * gr.z};
}

void apply_panel(const render::PanelModel& panel, const SimConstants& base, SimConstants& c, TimeStepSpec& ts) {
  for (int32_t f = 0; f < c.num_fluids; ++f) {
    FluidConstants& fc = c.fluids[f];
    const float scale_mu = base.fluids[0].viscosity > 0.0f ? panel.viscosity / base.fluids[0].viscosity : 1.0f;
    fc.viscosity = base.fluids[0].viscosity > 0.0f ? base.fluids[f].viscosity * scale_mu : panel.viscosity;
    fc.speed_of_sound = panel.speed_of_sound;
    fc.tait_b = fc.rest_density * fc.speed_of_sound * fc.speed_of_sound / 7.0f;
    fc.near_stiffness = panel.near_stiffness;
  }
  c.near_enabled = panel.near_stiffness > 0.0f;
  if (ts.mode == TimeStepMode::Fixed) ts.dt = panel.dt_max; else ts.max = panel.dt_max;
}

Vec3 cursor_point(const render::OrbitCamera& camera, int w, int h, double mx, double my) {
  const float ndc_x = float(2.0 * mx / std::max(w, 1) - 1.0), ndc_y = float(1.0 - 2.0 * my / std::max(h, 1));
  const render::Mat4 v = camera.view();
  const Vec3 right{v[0], v[4], v[8]}, up{v[1], v[5], v[9]};
  const float half = std::tan(0.5f * camera.fovy) * camera.distance;
  const float aspect = float(w) / float(std::max(h, 1));
  return camera.target + (ndc_x * half * aspect) * right + (ndc_y * half) * up;
}

}  // namespace sph
