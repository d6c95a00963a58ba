// Screen-door resolve (docs/render.md, "screen-door"): the box filter of Poon's
// (2000) Figure 7, "the frame buffer is shrunk back to its original size": each
// output pixel is the mean of its s x s sub-pixels in u_enlarged, whose texel
// (0, 0) is the first sub-pixel of window pixel u_origin. Alpha out is 1.
#version 330 core
uniform sampler2D u_enlarged;
uniform int u_side;       // s
uniform ivec2 u_origin;   // window pixel of the chunk's corner
out vec4 frag_color;

void main() {
  ivec2 base = (ivec2(gl_FragCoord.xy) - u_origin) * u_side;
  vec3 sum = vec3(0.0);
  for (int j = 0; j < u_side; ++j)
    for (int i = 0; i < u_side; ++i) sum += texelFetch(u_enlarged, base + ivec2(i, j), 0).rgb;
  frag_color = vec4(sum / float(u_side * u_side), 1.0);
}
