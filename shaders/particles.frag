#version 330 core
// Sphere impostor: discard outside the disc, reconstruct the sphere's normal and depth, Blinn-Phong shade.
in vec3 v_colour;
in vec3 v_centre;
in float v_point_size;  // pixels

uniform mat4 u_projection;
uniform float u_radius;
uniform vec3 u_light;      // direction towards the light, view space, normalised
uniform int u_flat;        // 1: flat points (fast mode), 0: shaded spheres

out vec4 frag_colour;

void main() {
  vec2 disc = gl_PointCoord * 2.0 - 1.0;
  disc.y = -disc.y;
  // A sphere at most two pixels across covers a pixel or a few: shade it as its centre and discard nothing.
  // The disc test at that size dropped the sphere whenever its centre fell near a pixel's corner (a fifth of
  // them), and the shading varied with where in the pixel it fell: deep water drew dark and full of holes.
  if (v_point_size <= 2.0) disc = vec2(0.0);
  float r2 = dot(disc, disc);
  if (r2 > 1.0) discard;
  if (u_flat == 1) {
    frag_colour = vec4(v_colour, 1.0);
    return;
  }
  vec3 normal = vec3(disc, sqrt(1.0 - r2));
  vec3 surface = v_centre + normal * u_radius;
  vec4 clip = u_projection * vec4(surface, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
  float diffuse = max(dot(normal, u_light), 0.0);
  vec3 half_vector = normalize(u_light + vec3(0.0, 0.0, 1.0));
  float specular = pow(max(dot(normal, half_vector), 0.0), 48.0);
  frag_colour = vec4(v_colour * (0.25 + 0.75 * diffuse) + vec3(0.35 * specular), 1.0);
}
