// dt-fast, distance pass 1 of 2 (rows): for each texel of a target's atlas
// tile, the distance in texels to the nearest covered texel of the same row
// within u_reach, else u_reach + 1. Reads never leave the tile (u_tile).
#version 330 core
uniform sampler2D u_coverage;  // r > 0.5: covered by the target (silhouette or shape)
uniform ivec4 u_tile;          // x0, y0, x1, y1 (exclusive) in atlas texels
uniform int u_reach;

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float best = float(u_reach + 1);
  for (int d = 0; d <= u_reach; ++d) {
    int xl = p.x - d, xr = p.x + d;
    bool hit = (xl >= u_tile.x && texelFetch(u_coverage, ivec2(xl, p.y), 0).r > 0.5) ||
               (xr < u_tile.z && texelFetch(u_coverage, ivec2(xr, p.y), 0).r > 0.5);
    if (hit) { best = float(d); break; }
  }
  frag_color = vec4(best);
}
