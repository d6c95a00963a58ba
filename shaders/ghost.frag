// Ghost fragment shader (the ghosting method, docs/render.md "ghosting"): the
// object lit as object.frag lights it (lighting.glsl's headlight, put before
// this file's code), output with weight u_alpha. Flat mode (u_flat.a > 0.5: weight
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
  frag_color = vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), u_alpha);
}
