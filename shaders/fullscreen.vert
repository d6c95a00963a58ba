// A screen-aligned rectangle from gl_VertexID (triangle strip of 4 vertices,
// no vertex buffer): u_rect = (x0, y0, x1, y1) in normalized device coordinates.
#version 330 core
uniform vec4 u_rect;

void main() {
  vec2 corner = vec2(float(gl_VertexID & 1), float((gl_VertexID >> 1) & 1));
  gl_Position = vec4(mix(u_rect.xy, u_rect.zw, corner), 0.0, 1.0);
}
