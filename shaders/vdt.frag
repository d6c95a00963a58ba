// The vdt method's blend shader (method_vdt.cpp; docs/render.md "vdt"):
// shaded as object.frag shades (lighting.glsl's headlight; u_flat.a > 0.5:
// u_flat.rgb), with alpha the interpolated view-dependent alpha of the
// vertices (object.vert's VERTEX_ALPHA: eq. 2 of Diepstraten et al., per
// vertex, attribute 3), clamped to [0, 1]; the blend state decides what it
// weighs. Linked with object.vert compiled with VERTEX_ALPHA. Never discards,
// never outputs NaN.
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;
in float v_alpha;

uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec4 u_flat;

out vec4 frag_color;

void main() {
  float alpha = clamp(v_alpha, 0.0, 1.0);
  if (u_flat.a > 0.5) {
    frag_color = vec4(u_flat.rgb, alpha);
    return;
  }
  frag_color = vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), alpha);
}
