// Occlusion culling (docs/render.md, "Occlusion culling"): one texel of the
// opacity map's depth per fragment, the farthest occluder depth over its block
// of u_block x u_block output pixels grown by one pixel on each side (1 where
// any of them is not covered), read from the full-resolution occluder depth.
// A texel is therefore covered only if every pixel of its block is, at depths
// no farther than it holds. Never discards.
#version 330 core
uniform sampler2D u_depth;
uniform int u_block;
uniform ivec2 u_size;  // the depth texture's size, output pixels

out vec4 frag_color;

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  ivec2 lo = max(t * u_block - 1, ivec2(0));
  ivec2 hi = min((t + 1) * u_block + 1, u_size);
  float d = 0.0;
  for (int y = lo.y; y < hi.y; ++y)
    for (int x = lo.x; x < hi.x; ++x) d = max(d, texelFetch(u_depth, ivec2(x, y), 0).r);
  frag_color = vec4(d);
}
