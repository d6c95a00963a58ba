// Object fragment shader: forward shading with a headlight (lighting.glsl,
// which programs.cpp puts before this file's code: the light sits at the eye),
// two-sided, colour = vertex colour x tint x (ambient + diffuse).
// Flat mode (u_flat.a > 0.5) outputs u_flat.rgb unlit: the weight renders
// that count visible pixels. Alpha is always 1; blending decides what it does.
// Compiled twice: with SEARCHLIGHT defined (only for the R1 guard's repair in active
// mode), u_searchlight limits it to a circle; without, it has no discard, so the
// driver can test depth before shading (llvmpipe tests late in any shader that
// may discard, which cost standard frames 25%).
// A method's own variants are its own files (lens.frag, screen_door.frag,
// vdt.frag, vdt_peel.frag, ghost.frag), compiled by the method's code.
// Compiled a third time with FLAT (weight frames: every object has a flat colour;
// with SEARCHLIGHT too for the repair): u_flat.rgb, nothing else. It reads no
// interpolated attribute, so the linker drops them and llvmpipe has fewer
// inputs to set up per triangle: the flat branch's output for less work.
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

vec4 with_alpha(vec4 c) {
  return c;
}

void main() {
#ifdef SEARCHLIGHT
  if (outside_searchlight(u_searchlight)) discard;
#endif
#ifdef FLAT
  frag_color = vec4(u_flat.rgb, 1.0);
#else
  if (u_flat.a > 0.5) {
    frag_color = with_alpha(vec4(u_flat.rgb, 1.0));
    return;
  }
  frag_color = with_alpha(vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), 1.0));
#endif
}
