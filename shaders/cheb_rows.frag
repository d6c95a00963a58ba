// dt-fast, mask pass 1 of 2 (rows), over each atlas tile's cover rows: for each texel,
// the distance in texels to the nearest covered texel of the same row up to
// u_reach, else u_reach + 1. Tiles are padded so that no other tile's
// coverage is within u_reach of a tile's texels.
#version 330 core
uniform sampler2D u_coverage;  // r > 0.5: covered by the target (silhouette or shape)
uniform int u_reach;

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int width = textureSize(u_coverage, 0).x;
  float best = float(u_reach + 1);
  for (int d = 0; d <= u_reach; ++d) {
    int xl = p.x - d, xr = p.x + d;
    bool hit = (xl >= 0 && texelFetch(u_coverage, ivec2(xl, p.y), 0).r > 0.5) ||
               (xr < width && texelFetch(u_coverage, ivec2(xr, p.y), 0).r > 0.5);
    if (hit) { best = float(d); break; }
  }
  frag_color = vec4(best);
}
