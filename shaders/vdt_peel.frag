// The vdt method's peeling shader (method_vdt.cpp, pass vdt-second;
// docs/render.md "vdt"): discards every fragment at or in front of the depth
// in u_peel at its own pixel, so one layer is peeled off (Everitt's depth
// peeling; the paper's z - z_shift test); the rest write u_alpha to every
// channel, as flat_alpha.frag does (the pass writes depth only). Always
// linked with object.vert.
#version 330 core
uniform float u_alpha;
uniform sampler2D u_peel;  // depth of the nearest layer, aligned with the view

out vec4 frag_color;

void main() {
  if (gl_FragCoord.z <= texelFetch(u_peel, ivec2(gl_FragCoord.xy), 0).r) discard;
  frag_color = vec4(u_alpha);
}
