// The screen-door method's fragment shader (method_screen_door.cpp;
// docs/render.md "screen-door"): drawn on a buffer enlarged s times, each
// output pixel an s x s block of sub-pixels; sub-pixel (i, j) of pixel p is
// bit j s + i of the object's mask at p, u_sd_words 32-bit words per pixel in
// u_sd_masks, the block of the pixels u_sd_block from texel u_sd_origin (x:
// q.x words + word, y: q.y, q = p - block corner); a fragment whose bit is 0
// is discarded. u_sd_origin.x < 0: no mask (alpha 1 over the whole chunk).
// A kept fragment is shaded as object.frag shades it (lighting.glsl's
// headlight; u_flat.a > 0.5: u_flat.rgb), alpha 1. Never outputs NaN.
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;

uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec4 u_flat;
uniform usampler2D u_sd_masks;
uniform int u_sd_side;     // s
uniform int u_sd_words;    // words per pixel: s s / 32
uniform ivec2 u_sd_origin; // this object's block in u_sd_masks; x < 0: none
uniform ivec4 u_sd_block;  // the chunk pixels the block holds: x0, y0, x1, y1 (outside: no mask)

out vec4 frag_color;

void main() {
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
  if (u_flat.a > 0.5) {
    frag_color = vec4(u_flat.rgb, 1.0);
    return;
  }
  frag_color = vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), 1.0);
}
