// The lens method's fragment shader (method_lens.cpp; docs/render.md "lens"):
// the second depth test of Ropinski & Hinrichs (2004) against the lens's back-
// and front-face depth maps (texelFetch at the fragment's own window pixel:
// the maps are aligned with the view), keeping only the fragments of this
// pass's class: 0 behind the lens (z > back), 1 inside (front <= z <= back),
// 2 in front (z < front); outside the lens footprint back = 0 and front = 1,
// so class 0 keeps everything there. A kept fragment is shaded as object.frag
// shades it (lighting.glsl's headlight; u_flat.a > 0.5: u_flat.rgb), then
// u_lens_tint.a > 0 mixes u_lens_tint.rgb in. Always discards the other
// classes; never outputs NaN.
#version 330 core
in vec3 v_world;
in vec3 v_normal;
in vec3 v_color;

uniform vec3 u_tint;
uniform vec3 u_eye;
uniform vec4 u_flat;
uniform sampler2D u_lens_back;   // depth of the lens's farthest surface (0 where no lens)
uniform sampler2D u_lens_front;  // depth of its nearest surface (1 where no lens; 0 with the eye inside)
uniform int u_lens_class;        // 0 behind, 1 inside, 2 in front
uniform vec4 u_lens_tint;        // rgb mixed in with weight a (a = 0: none)

out vec4 frag_color;

vec4 lens_tinted(vec4 c) {
  return u_lens_tint.a > 0.0 ? vec4(mix(c.rgb, u_lens_tint.rgb, u_lens_tint.a), c.a) : c;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  float z = gl_FragCoord.z;
  float back = texelFetch(u_lens_back, pixel, 0).r;
  float front = texelFetch(u_lens_front, pixel, 0).r;
  bool keep = u_lens_class == 0 ? z > back : (u_lens_class == 2 ? z < front : (z >= front && z <= back));
  if (!keep) discard;
  if (u_flat.a > 0.5) {
    frag_color = lens_tinted(vec4(u_flat.rgb, 1.0));
    return;
  }
  frag_color = lens_tinted(vec4(headlight(v_world, v_normal, v_color, u_tint, u_eye), 1.0));
}
