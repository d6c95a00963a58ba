// dt-fast: multiplies one target's mask into the framebuffer alpha over its
// screen rectangle: one bilinear fetch of the target's atlas tile, which
// already holds the gradient's alpha (cheb_cols.frag). The target's own
// silhouette is handled by the stencil (it gets exactly aT); fragments where
// the mask is 1 are discarded.
#version 330 core
uniform sampler2D u_mask;
uniform vec2 u_atlas_size;     // texels
uniform vec2 u_tile_origin;    // atlas texel of the tile's lower-left corner
uniform vec2 u_tile_size;      // texels (samples stay inside the tile: no bleeding between tiles)
uniform vec2 u_screen_origin;  // window pixel of that corner
uniform float u_texel_px;      // output pixels per atlas texel
uniform vec3 u_searchlight;    // as in flat_alpha.frag

out vec4 frag_color;

void main() {
  if (u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z) discard;
  vec2 t = clamp(u_tile_origin + (gl_FragCoord.xy - u_screen_origin) / u_texel_px, u_tile_origin + 0.5,
                 u_tile_origin + u_tile_size - 0.5);
  float a = texture(u_mask, t / u_atlas_size).r;
  if (a >= 1.0) discard;
  frag_color = vec4(a);
}
