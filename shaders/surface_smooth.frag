#version 330 core
// Screen-space fluid, smoothing: one direction of a separable bilateral filter on the eye depth (van der
// Laan et al. 2009 use curvature flow or a bilateral filter; this is the latter, split into a horizontal
// and a vertical pass as is usual for speed, which the filter's depth weight makes an approximation).
// Neighbours are weighted by their distance in pixels (Gaussian, u_sigma_px) and by their depth difference
// (Gaussian, u_sigma_depth in metres), so the spheres' bumps are smoothed while a depth jump (a fluid edge
// in front of another) is kept. Pixels without fluid (depth 0) stay empty and are not averaged in.
in vec2 v_uv;

uniform sampler2D u_depth;
uniform vec2 u_step;         // one pixel along the pass's direction, in texture coordinates
uniform float u_sigma_px;
uniform float u_sigma_depth;
uniform int u_radius_px;

out float eye_depth;

void main() {
  float centre = texture(u_depth, v_uv).r;
  if (centre <= 0.0) {
    eye_depth = 0.0;
    return;
  }
  float sum = 0.0, weights = 0.0;
  for (int k = -u_radius_px; k <= u_radius_px; ++k) {
    float d = texture(u_depth, v_uv + float(k) * u_step).r;
    if (d <= 0.0) continue;
    float r = float(k) / u_sigma_px;
    float dz = (d - centre) / u_sigma_depth;
    float w = exp(-0.5 * r * r - 0.5 * dz * dz);
    sum += w * d;
    weights += w;
  }
  eye_depth = sum / weights;
}
