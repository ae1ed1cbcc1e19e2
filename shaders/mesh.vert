#version 330 core
// Triangle meshes (the exported fluid surface in the replay): positions only; the fragment shader takes the
// face's normal from the view-space position's derivatives.
layout(location = 0) in vec3 a_position;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_view_position;

void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_view_position = p.xyz;
  gl_Position = u_projection * p;
}
