// sph_demo's controls as pure functions of the input: the tilted gravity of the arrow keys, the panel's
// live parameters onto the constants, and the point under the cursor for the mouse force.
#pragma once

#include "../common/params.h"
#include "../common/scene.h"
#include "../render/camera.h"
#include "../render/ui_panel.h"

namespace sph {

// Gravity g0 [m/s^2] rotated by tilt_z about z (left/right arrows), then by tilt_x about x (up/down), in
// radians: the tank tilted under the fluid.
Vec3 tilted_gravity(Vec3 g0, float tilt_x, float tilt_z);

// The panel's viscosity (scaled onto every fluid as the first fluid's changes), speed of sound (with each
// fluid's Tait B) and near stiffness, from the scene's constants `base` into `c`; its step limit into `ts`
// (the fixed step or the adaptive step's cap, s).
void apply_panel(const render::PanelModel& panel, const SimConstants& base, SimConstants& c, TimeStepSpec& ts);

// The point [m] under the cursor (mx, my pixels in a w x h window) on the plane through the camera's
// target that faces the camera.
Vec3 cursor_point(const render::OrbitCamera& camera, int w, int h, double mx, double my);

}  // namespace sph
