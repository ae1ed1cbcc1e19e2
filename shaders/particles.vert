#version 330 core
// Particles as sphere impostors: one point sprite per particle, sized to the sphere's projected diameter.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_colour;

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;           // world-space sphere radius
uniform float u_viewport_height;  // pixels

out vec3 v_colour;
out vec3 v_centre;  // sphere centre in view space

void main() {
  vec4 centre = u_view * vec4(a_position, 1.0);
  v_centre = centre.xyz;
  v_colour = a_colour;
  gl_Position = u_projection * centre;
  // Projected diameter: 2 r * (focal length in pixels) / depth, focal = P[1][1] * H / 2.
  gl_PointSize = max(1.0, u_projection[1][1] * u_viewport_height * u_radius / max(-centre.z, 1e-4));
}
