// Writes u_alpha to every channel: the target silhouette into a mask buffer
// (Algorithm 2, line 2), the alpha multiply of a re-rendered target region
// (line 11), and depth/stencil-only passes (colour writes off). Compiled with
// SEARCHLIGHT defined for active mode: fragments outside the searchlight
// circle (searchlight.glsl) are discarded, or with u_outside_one written as alpha 1 (so stencil
// operations still happen there); without it, it never discards. (vdt's
// depth peeling is vdt_peel.frag, the vdt method's own.)
#version 330 core
uniform float u_alpha;
#ifdef SEARCHLIGHT
uniform vec3 u_searchlight;  // centre x, y in window pixels (origin bottom-left), radius; radius < 0: off
uniform int u_outside_one;   // 1: outside the searchlight write alpha 1 (a no-op multiply) instead of discarding
#endif

out vec4 frag_color;

void main() {
#ifdef SEARCHLIGHT
  bool outside = outside_searchlight(u_searchlight);
  if (outside && u_outside_one == 0) discard;
  frag_color = vec4(outside ? 1.0 : u_alpha);
#else
  frag_color = vec4(u_alpha);
#endif
}
