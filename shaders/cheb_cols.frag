// dt-fast, mask pass 2 of 2 (columns): the Chebyshev distance in texels,
// d(x, y) = min over |dy| <= reach of max(|dy|, rows(x, y + dy)), exact for
// the tile's coverage up to u_reach; written as the mask's alpha for that
// distance in output pixels, a0 + (1 - a0) clamp((d - 1) / n, 0, 1) (1 past
// the gradient), so the apply step is one bilinear fetch (an 8-bit texture,
// llvmpipe's fastest filtering path).
#version 330 core
uniform sampler2D u_rows;
uniform ivec4 u_tile;
uniform int u_reach;
uniform float u_texel_px;     // output pixels per texel
uniform float u_alpha_start;  // a0
uniform float u_gradient_px;  // n

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float best = float(u_reach + 1);
  for (int d = 0; d <= u_reach; ++d) {
    if (float(d) >= best) break;
    int yd = p.y - d, yu = p.y + d;
    if (yd >= u_tile.y) best = min(best, max(float(d), texelFetch(u_rows, ivec2(p.x, yd), 0).r));
    if (yu < u_tile.w) best = min(best, max(float(d), texelFetch(u_rows, ivec2(p.x, yu), 0).r));
  }
  float px = best * u_texel_px;
  float a = u_gradient_px > 0.0 ? u_alpha_start + (1.0 - u_alpha_start) * clamp((px - 1.0) / u_gradient_px, 0.0, 1.0)
                                : 1.0;
  frag_color = vec4(a);
}
