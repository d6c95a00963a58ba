// dt-fast, mask pass 2 of 2 (columns): the Chebyshev distance d in grid
// texels to the nearest covered texel, min over |dy| <= n' of
// max(|dy|, rows(x, y + dy)), exact up to n' (Algorithm 3's 8-neighbour
// dilation grows exactly these rings); written as the value dt-seed's
// ping-pong passes leave in that texel: aT where covered (d = 0), a0 + (1 -
// a0)(d - 1)/n' on ring d = 1..n', 1 beyond. Over each tile's cover grown
// by n' (method_fast.cpp).
#version 330 core
uniform sampler2D u_rows;
uniform int u_layers;          // n'
uniform float u_alpha_target;  // aT
uniform float u_alpha_start;   // a0

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int height = textureSize(u_rows, 0).y;
  float best = float(u_layers + 1);
  for (int d = 0; d <= u_layers; ++d) {
    if (float(d) >= best) break;
    int yd = p.y - d, yu = p.y + d;
    if (yd >= 0) best = min(best, max(float(d), texelFetch(u_rows, ivec2(p.x, yd), 0).r));
    if (yu < height) best = min(best, max(float(d), texelFetch(u_rows, ivec2(p.x, yu), 0).r));
  }
  float a = best == 0.0 ? u_alpha_target
          : best <= float(u_layers) ? u_alpha_start + (1.0 - u_alpha_start) * (best - 1.0) / float(u_layers)
          : 1.0;
  frag_color = vec4(a);
}
