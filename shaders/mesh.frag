#version 330 core
// Flat-shaded triangles: the face normal from dFdx / dFdy of the view-space position, a diffuse term from
// u_light and a little ambient light, facing the viewer whichever way the triangle winds.
in vec3 v_view_position;

uniform vec3 u_colour;
uniform vec3 u_light;  // towards the light, view space, normalised

out vec4 frag_colour;

void main() {
  vec3 n = normalize(cross(dFdx(v_view_position), dFdy(v_view_position)));
  if (dot(n, -v_view_position) < 0.0) n = -n;
  float diffuse = max(dot(n, u_light), 0.0);
  frag_colour = vec4(u_colour * (0.3 + 0.7 * diffuse), 1.0);
}
