#version 330 core
// Screen-space fluid, thickness pass: every sphere adds the length of fluid the view ray crosses in it [m]
// (additive blending, no depth test), for the absorption of light through the water.
in vec3 v_colour;
in vec3 v_centre;

uniform float u_radius;

out float thickness;

void main() {
  vec2 disc = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(disc, disc);
  if (r2 > 1.0) discard;
  thickness = 2.0 * u_radius * sqrt(1.0 - r2);
}
