// dt-fast, distance pass 2 of 2 (columns): Chebyshev distance in texels,
// d(x, y) = min over |dy| <= reach of max(|dy|, rows(x, y + dy)), exact for
// the tile's coverage up to u_reach (beyond it: u_reach + 1).
#version 330 core
uniform sampler2D u_rows;
uniform ivec4 u_tile;
uniform int u_reach;

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
  frag_color = vec4(best);
}
