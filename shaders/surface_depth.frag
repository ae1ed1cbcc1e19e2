#version 330 core
// Screen-space fluid, pass 1 (van der Laan, Green and Sainz 2009): each particle's sphere (particles.vert's
// point sprite) writes the distance of its front surface along -z in view space [m] to a float texture,
// nearest kept by the depth test.
in vec3 v_colour;
in vec3 v_centre;

uniform mat4 u_projection;
uniform float u_radius;

out float eye_depth;

void main() {
  vec2 disc = gl_PointCoord * 2.0 - 1.0;
  disc.y = -disc.y;
  float r2 = dot(disc, disc);
  if (r2 > 1.0) discard;
  vec3 surface = v_centre + vec3(disc, sqrt(1.0 - r2)) * u_radius;
  vec4 clip = u_projection * vec4(surface, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
  eye_depth = -surface.z;
}
