// Algorithm 2, line 10: multiplies the (bilinearly upsampled) mask into the
// framebuffer alpha (blend: dst.a *= src.a). Pixels where the mask is 1, or
// outside the searchlight in active mode, are discarded (nothing to multiply;
// the layer-limit stencil counter only restarts where the mask is below 1).
#version 330 core
uniform sampler2D u_mask;
uniform vec2 u_screen;       // output size in pixels
uniform vec3 u_searchlight;  // as in flat_alpha.frag

out vec4 frag_color;

void main() {
  if (u_searchlight.z >= 0.0 && distance(gl_FragCoord.xy, u_searchlight.xy) > u_searchlight.z) discard;
  float m = texture(u_mask, gl_FragCoord.xy / u_screen).r;
  if (m >= 1.0) discard;
  frag_color = vec4(m);
}
