// Object fragment shader: forward shading with a headlight (lighting.glsl,
// which programs.cpp puts before this file's code: the light sits at the eye),
// two-sided, colour = vertex colour x tint x (ambient + diffuse).
// Flat mode (u_flat.a > 0.5) outputs u_flat.rgb unlit: the weight renders
// that count visible pixels. Alpha is always 1; blending decides what it does.
// Compiled twice: with SEARCHLIGHT defined (only for the R1 guard's repair in active
// mode), u_searchlight limits it to a circle; without, it has no discard, so the
// driver can test depth before shading (llvmpipe tests late in any shader that
// may discard, which cost standard frames 25%).
// Compiled a third time with LENS (the lens method, docs/render.md "lens"): the
// second depth test of Ropinski & Hinrichs (2004) against the lens's back- and
// front-face depth maps (texelFetch at the fragment's own window pixel: the
// maps are aligned with the view), keeping only the fragments of this pass's
// class: 0 behind the lens (z > back), 1 inside (front <= z <= back), 2 in
// front (z < front); outside the lens footprint back = 0 and front = 1, so
// class 0 keeps everything there. u_lens_tint.a > 0 mixes u_lens_tint.rgb in.
// Compiled a fourth time with SCREEN_DOOR (the screen-door method, docs/render.md
// "screen-door"): drawn on a buffer enlarged s times, each output pixel an s x s
// block of sub-pixels; sub-pixel (i, j) of pixel p is bit j s + i of the object's
// mask at p, u_sd_words 32-bit words per pixel in u_sd_masks, the block of the
// pixels u_sd_block from texel u_sd_origin (x: q.x words + word, y: q.y, q = p -
// block corner); a fragment whose bit is 0 is discarded. u_sd_origin.x < 0: no
// mask (alpha 1 over the whole chunk).
// Compiled a fifth time with VDT (docs/render.md "vdt"): alpha is the
// interpolated view-dependent alpha of the vertices (clamped to [0, 1]) in both
// the lit and the flat branch; the blend state decides what it weighs.
// Compiled a sixth time with FLAT (weight frames: every object has a flat colour;
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
#ifdef SCREEN_DOOR
uniform usampler2D u_sd_masks;
uniform int u_sd_side;     // s
uniform int u_sd_words;    // words per pixel: s s / 32
uniform ivec2 u_sd_origin; // this object's block in u_sd_masks; x < 0: none
uniform ivec4 u_sd_block;  // the chunk pixels the block holds: x0, y0, x1, y1 (outside: no mask)
#endif
#ifdef LENS
uniform sampler2D u_lens_back;   // depth of the lens's farthest surface (0 where no lens)
uniform sampler2D u_lens_front;  // depth of its nearest surface (1 where no lens; 0 with the eye inside)
uniform int u_lens_class;        // 0 behind, 1 inside, 2 in front
uniform vec4 u_lens_tint;        // rgb mixed in with weight a (a = 0: none)
#endif
#ifdef VDT
in float v_alpha;
#endif

out vec4 frag_color;

vec4 with_alpha(vec4 c) {
#ifdef VDT
  c.a = clamp(v_alpha, 0.0, 1.0);
#endif
  return c;
}

#ifdef LENS
vec4 lens_tinted(vec4 c) {
  return u_lens_tint.a > 0.0 ? vec4(mix(c.rgb, u_lens_tint.rgb, u_lens_tint.a), c.a) : c;
}
#endif

void main() {
#ifdef SEARCHLIGHT
  if (u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z) discard;
#endif
#ifdef FLAT
  frag_color = vec4(u_flat.rgb, 1.0);
#else
#ifdef SCREEN_DOOR
  if (u_sd_origin.x >= 0) {
    ivec2 e = ivec2(gl_FragCoord.xy);
    ivec2 p = e / u_sd_side;
    ivec2 sub = e - p * u_sd_side;
    int bit = sub.y * u_sd_side + sub.x;
    ivec2 q = p - u_sd_block.xy;
    if (p.x < u_sd_block.z && p.y < u_sd_block.w && q.x >= 0 && q.y >= 0) {
      uint word = texelFetch(u_sd_masks, u_sd_origin + ivec2(q.x * u_sd_words + bit / 32, q.y), 0).r;
      if (((word >> uint(bit % 32)) & 1u) == 0u) discard;
    }
  }
#endif
#ifdef LENS
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z;
  float back = texelFetch(u_lens_back, pixel, 0).r;
  float front = texelFetch(u_lens_front, pixel, 0).r;
  bool keep = u_lens_class == 0 ? z > back : (u_lens_class == 2 ? z < front : (z >= front && z <= back));
  if (!keep) discard;
#endif
  if (u_flat.a > 0.5) {
    frag_color = with_alpha(vec4(u_flat.rgb, 1.0));
#ifdef LENS
    frag_color = lens_tinted(frag_color);
#endif
    return;
  }
  frag_color = with_alpha(vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), 1.0));
#ifdef LENS
  frag_color = lens_tinted(frag_color);
#endif
#endif
}
