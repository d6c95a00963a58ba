// Shared GLSL chunk (not a shader of its own; programs.h puts it before the
// code of a fragment shader that names it): the headlight every lit program
// shades with, written once. Colour = vertex colour x tint x (ambient 0.3 +
// diffuse 0.7 |n . l|), l towards the eye (the light sits at the eye), two-
// sided. Never outputs NaN: a degenerate normal or the eye on the surface
// falls back to full diffuse light. Declares nothing but this function.
vec3 headlight(vec3 world, vec3 normal, vec3 color, vec3 tint, vec3 eye) {
  vec3 to_eye = eye - world;
  float le = length(to_eye);
  vec3 l = le > 1e-12 ? to_eye / le : vec3(0.0, 0.0, 1.0);
  float ln = length(normal);
  float diffuse = ln > 1e-12 ? abs(dot(normal / ln, l)) : 1.0;
  return clamp(color * tint, 0.0, 1.0) * (0.3 + 0.7 * clamp(diffuse, 0.0, 1.0));
}
