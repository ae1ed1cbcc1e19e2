#version 330 core
// Particles as sphere impostors: one point sprite per particle, sized to the sphere's projected diameter.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_colour;

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;           // world-space sphere radius
uniform float u_viewport_height;  // pixels
uniform float u_min_size;         // the least point size, pixels: 1, or 2 for a culled set (occlusion_cull.h)

out vec3 v_colour;
out vec3 v_centre;  // sphere centre in view space
out float v_point_size;  // pixels

void main() {
  vec4 centre = u_view * vec4(a_position, 1.0);
  v_centre = centre.xyz;
  v_colour = a_colour;
  gl_Position = u_projection * centre;
  // Projected diameter: 2 r * (focal length in pixels) / depth, focal = P[1][1] * H / 2.
  gl_PointSize = max(u_min_size, u_projection[1][1] * u_viewport_height * u_radius / max(-centre.z, 1e-4));
  v_point_size = gl_PointSize;
}
