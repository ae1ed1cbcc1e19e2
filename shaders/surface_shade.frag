#version 330 core
// Screen-space fluid, shading: the smoothed eye depth becomes view-space positions, their differences the
// normals (the smaller of the one-sided differences, so an edge does not bend them); Schlick's Fresnel
// mixes the reflection of a sky gradient with the light through the water, tinted by Beer-Lambert
// absorption over the thickness, plus a specular highlight. Writes the depth so the lines compose.
in vec2 v_uv;

uniform sampler2D u_depth;      // smoothed eye depth [m], 0 where no fluid
uniform sampler2D u_thickness;  // [m]
uniform vec2 u_texel;
uniform mat4 u_projection;
uniform mat4 u_view;            // for the sky's up direction
uniform vec3 u_light;           // towards the light, view space
uniform vec3 u_colour;          // the water's colour (what it transmits)
uniform float u_absorption;     // [1/m]
uniform vec3 u_background;      // what is seen through the water

out vec4 frag_colour;

vec3 eye_position(vec2 uv, float depth) {
  vec2 ndc = 2.0 * uv - 1.0;
  return vec3(ndc.x * depth / u_projection[0][0], ndc.y * depth / u_projection[1][1], -depth);
}

void main() {
  float depth = texture(u_depth, v_uv).r;
  if (depth <= 0.0) discard;
  vec3 p = eye_position(v_uv, depth);
  vec3 ddx = eye_position(v_uv + vec2(u_texel.x, 0.0), texture(u_depth, v_uv + vec2(u_texel.x, 0.0)).r) - p;
  vec3 ddx2 = p - eye_position(v_uv - vec2(u_texel.x, 0.0), texture(u_depth, v_uv - vec2(u_texel.x, 0.0)).r);
  if (abs(ddx2.z) < abs(ddx.z)) ddx = ddx2;
  vec3 ddy = eye_position(v_uv + vec2(0.0, u_texel.y), texture(u_depth, v_uv + vec2(0.0, u_texel.y)).r) - p;
  vec3 ddy2 = p - eye_position(v_uv - vec2(0.0, u_texel.y), texture(u_depth, v_uv - vec2(0.0, u_texel.y)).r);
  if (abs(ddy2.z) < abs(ddy.z)) ddy = ddy2;
  vec3 n = normalize(cross(ddx, ddy));
  vec3 v = normalize(-p);
  if (dot(n, v) < 0.0) n = -n;

  float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(n, v), 0.0), 5.0);
  vec3 r = reflect(-v, n);
  vec3 up = normalize((u_view * vec4(0.0, 1.0, 0.0, 0.0)).xyz);
  float sky_t = clamp(0.5 + 0.5 * dot(r, up), 0.0, 1.0);
  vec3 sky = mix(vec3(0.25, 0.27, 0.30), vec3(0.75, 0.85, 1.0), sky_t);
  float thickness = texture(u_thickness, v_uv).r;
  vec3 transmit = exp(-u_absorption * thickness * (vec3(1.05) - u_colour));
  vec3 through = mix(u_colour * 0.9, u_background, transmit);
  float diffuse = 0.5 + 0.5 * max(dot(n, u_light), 0.0);
  vec3 h = normalize(u_light + v);
  float specular = pow(max(dot(n, h), 0.0), 96.0);
  vec3 colour = mix(through * diffuse + u_colour * 0.15, sky, fresnel) + vec3(0.6 * specular);
  frag_colour = vec4(colour, 1.0);
  vec4 clip = u_projection * vec4(p, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
}
