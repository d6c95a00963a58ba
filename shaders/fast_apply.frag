// Algorithm 2, line 10 (dt-seed and dt-fast): multiplies one target's upsampled
// mask into the framebuffer alpha (blend: dst.a *= src.a) over rectangles of
// its support. The target's atlas tile (mask_atlas.h) holds the texels of the
// R x R grid, so one bilinear fetch at the same grid coordinates gives the
// article's upsampled mask (samples are clamped to the tile's texels inside
// the grid: its border texels are 1, as beyond them, and at the grid's edge
// the clamp is a whole-grid buffer's). The silhouette itself is the stencil's
// business. Outside the searchlight the factor is 1. Compiled with COUNTER
// (layer limit): discards where the factor is 1 instead, so the stencil
// counter restarts only where alpha drops.
#version 330 core
uniform sampler2D u_mask;
uniform vec2 u_atlas_size;   // texels of the atlas page
uniform vec2 u_tile_origin;  // atlas texel of the tile's first texel
uniform vec4 u_clamp;        // atlas texel centres of the tile's texels inside the grid: x0, y0, x1, y1
uniform vec2 u_tile_texel0;  // grid texel of the tile's first texel
uniform vec2 u_texel_px;     // output pixels per grid texel, x and y
uniform vec3 u_searchlight;  // as in flat_alpha.frag

out vec4 frag_color;

void main() {
  vec2 grid = gl_FragCoord.xy / u_texel_px;  // dt-seed: gl_FragCoord / screen * R
  vec2 t = clamp(u_tile_origin + grid - u_tile_texel0, u_clamp.xy, u_clamp.zw);
  float a = texture(u_mask, t / u_atlas_size).r;
  bool outside = u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z;
#ifdef COUNTER
  if (outside || a >= 1.0) discard;
#else
  if (outside) a = 1.0;
#endif
  frag_color = vec4(a);
}
