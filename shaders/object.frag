// Object fragment shader: forward shading with a headlight (the light sits at
// the eye), two-sided, colour = vertex colour x tint x (ambient + diffuse).
// Flat mode (u_flat.a > 0.5) outputs u_flat.rgb unlit: the weight renders
// that count visible pixels. Alpha is always 1; blending decides what it does.
// Compiled twice: with SEARCHLIGHT defined (only for the R1 guard's repair in active
// mode), u_searchlight limits it to a circle; without, it has no discard, so the
// driver can test depth before shading (llvmpipe tests late in any shader that
// may discard, which cost standard frames 25%).
// Never outputs NaN: degenerate normals and eye-on-surface fall back safely.
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;

uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec4 u_flat;
#ifdef SEARCHLIGHT
uniform vec3 u_searchlight;  // (x, y, radius) window pixels; radius < 0: off (fragments outside are discarded)
#endif

out vec4 frag_color;

void main() {
#ifdef SEARCHLIGHT
  if (u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z) discard;
#endif
  if (u_flat.a > 0.5) {
    frag_color = vec4(u_flat.rgb, 1.0);
    return;
  }
  vec3 to_eye = u_eye - v_world;
  float le = length(to_eye);
  vec3 l = le > 1e-12 ? to_eye / le : vec3(0.0, 0.0, 1.0);
  float ln = length(v_normal);
  float diffuse = ln > 1e-12 ? abs(dot(v_normal / ln, l)) : 1.0;
  vec3 c = clamp(v_color * u_tint, 0.0, 1.0) * (0.3 + 0.7 * clamp(diffuse, 0.0, 1.0));
  frag_color = vec4(c, 1.0);
}
