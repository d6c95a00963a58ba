// A screen-aligned rectangle from gl_VertexID (triangle strip of 4 vertices,
// no vertex buffer): u_rect = (x0, y0, x1, y1) in normalized device coordinates,
// at depth u_z (NDC, default 0).
// TILES: one rectangle per instance instead, u_tiles[gl_InstanceID] in texels
// of a u_size buffer, grown by u_grow texels (x, y) on each side: a mask pass
// over the texels of every tile it can change, all tiles in one draw.
#version 330 core
uniform float u_z;
#ifdef TILES
const int kMaxTiles = 64;  // keep equal to kTilesPerDraw (mask_atlas.cpp)
uniform vec4 u_tiles[kMaxTiles];
uniform vec2 u_grow;
uniform vec2 u_size;
#else
uniform vec4 u_rect;
#endif

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
#ifdef TILES
  vec4 r = u_tiles[gl_InstanceID] + vec4(-u_grow, u_grow);
  gl_Position = vec4(mix(r.xy, r.zw, corner) / u_size * 2.0 - 1.0, u_z, 1.0);
#else
  gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), u_z, 1.0);
#endif
}
