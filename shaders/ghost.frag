// Ghost fragment shader (the ghosting method, docs/render.md "ghosting"): the
// object lit as object.frag lights it (headlight, two-sided, ambient 0.3 +
// diffuse 0.7), output with weight u_alpha. Flat mode (u_flat.a > 0.5: weight
// frames, and the ghosts' edge lines) outputs u_flat.rgb with weight u_alpha.
// Never discards (llvmpipe may test depth before shading), never outputs NaN.
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;

uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec4 u_flat;
uniform float u_alpha;  // the ghost's weight, [0, 1]; 1 for its edges

out vec4 frag_color;

void main() {
  if (u_flat.a > 0.5) {
    frag_color = vec4(u_flat.rgb, u_alpha);
    return;
  }
  vec3 to_eye = u_eye - v_world;
  float le = length(to_eye);
  vec3 l = le > 1e-12 ? to_eye / le : vec3(0.0, 0.0, 1.0);
  float ln = length(v_normal);
  float diffuse = ln > 1e-12 ? abs(dot(v_normal / ln, l)) : 1.0;
  vec3 c = clamp(v_color * u_tint, 0.0, 1.0) * (0.3 + 0.7 * clamp(diffuse, 0.0, 1.0));
  frag_color = vec4(c, u_alpha);
}
