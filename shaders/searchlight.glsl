// Shared GLSL chunk (not a shader of its own; programs.h puts it before the
// code of a fragment shader that names it): the searchlight cut of active
// mode, written once. outside_searchlight(s) is true when this fragment lies
// outside the circle s = (x, y, radius), window pixels with the origin at the
// bottom left; radius < 0 (the searchlight off, or passive mode): never.
// Declares nothing but this function; never discards (the caller decides).
bool outside_searchlight(vec3 s) {
  return s.z >= 0.0 && distance(gl_FragCoord.xy, s.xy) > s.z;
}
