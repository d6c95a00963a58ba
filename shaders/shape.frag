// Circle and ellipse masks (Figure 2 a, b): fragments inside the axis-aligned
// ellipse with centre u_center and semi-axes u_radii (pixels of the target
// being drawn) get u_alpha; fragments outside are discarded. A circle is an
// ellipse with equal radii. Searchlight (searchlight.glsl) as in flat_alpha.frag.
#version 330 core
uniform vec2 u_center;
uniform vec2 u_radii;
uniform float u_alpha;
uniform vec3 u_searchlight;
uniform int u_outside_one;  // 1: outside the searchlight write alpha 1 (a no-op multiply) instead of discarding

out vec4 frag_color;

void main() {
  bool outside = outside_searchlight(u_searchlight);
  if (outside && u_outside_one == 0) discard;
  vec2 d = (gl_FragCoord.xy - u_center) / max(u_radii, vec2(1e-6));
  if (dot(d, d) > 1.0) discard;
  frag_color = vec4(outside ? 1.0 : u_alpha);
}
