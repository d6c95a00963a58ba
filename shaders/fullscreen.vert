// A screen-aligned rectangle from gl_VertexID (triangle strip of 4 vertices,
// no vertex buffer): u_rect = (x0, y0, x1, y1) in normalized device coordinates,
// at depth u_z (NDC, default 0).
#version 330 core
uniform vec4 u_rect;
uniform float u_z;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), u_z, 1.0);
}
