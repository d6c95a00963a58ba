// Object vertex shader: model -> world -> clip. Shared by every program that
// draws scene geometry, with `invariant gl_Position`, so a depth pass and a
// later depth-EQUAL colour pass of the same object produce identical depths.
// With VERTEX_ALPHA it also passes on a per-vertex alpha from attribute 3,
// linearly interpolated (v_alpha; the vdt method's view-dependent alpha, eq. 2
// of Diepstraten et al.); the position maths is the same.
#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_color;

uniform mat4 u_model;
uniform mat4 u_view_proj;
uniform mat3 u_normal_matrix;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_color;
#ifdef VERTEX_ALPHA
layout(location = 3) in float a_alpha;
out float v_alpha;
#endif

invariant gl_Position;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_color = a_color;
#ifdef VERTEX_ALPHA
  v_alpha = a_alpha;
#endif
  gl_Position = u_view_proj * world;
}
