// dt-fast: multiplies one target's mask into the framebuffer alpha over its
// screen rectangle. The Chebyshev distance (texels of the atlas tile, sampled
// bilinearly) becomes output pixels, then alpha: a0 + (1 - a0)(d - 1)/n for
// 1 <= d <= n + 1, clamped to [a0, 1]. The target's own silhouette is handled
// by the stencil (it gets exactly aT); fragments with alpha 1 are discarded.
#version 330 core
uniform sampler2D u_distance;
uniform vec2 u_atlas_size;     // texels
uniform vec2 u_tile_origin;    // atlas texel of the tile's lower-left corner
uniform vec2 u_tile_size;      // texels (samples stay inside the tile: no bleeding between tiles)
uniform vec2 u_screen_origin;  // window pixel of that corner
uniform float u_texel_px;      // output pixels per atlas texel
uniform float u_alpha_start;   // a0
uniform float u_gradient_px;   // n
uniform vec3 u_searchlight;

out vec4 frag_color;

void main() {
  if (u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z) discard;
  vec2 t = clamp(u_tile_origin + (gl_FragCoord.xy - u_screen_origin) / u_texel_px, u_tile_origin + 0.5,
                u_tile_origin + u_tile_size - 0.5);
  float d = texture(u_distance, t / u_atlas_size).r * u_texel_px;
  float a = u_gradient_px > 0.0 ? u_alpha_start + (1.0 - u_alpha_start) * clamp((d - 1.0) / u_gradient_px, 0.0, 1.0)
                                : 1.0;
  if (a >= 1.0) discard;
  frag_color = vec4(a);
}
