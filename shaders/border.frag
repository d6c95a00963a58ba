// Algorithm 3 of Assarsson, Elmqvist & Tsigas (2006): one ping-pong pass of
// the mask border. A pixel still at 1.0 (unmarked) with a marked neighbour
// (8-neighbourhood) becomes u_border_alpha; every other pixel keeps its value.
// Departure (docs/render.md): as printed, the algorithm outputs 1.0 for
// non-border pixels, which would erase the layers of earlier passes; we output
// F(P) instead, so the n layers accumulate into the gradient.
#version 330 core
uniform sampler2D u_source;
uniform float u_border_alpha;

out vec4 frag_color;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 size = textureSize(u_source, 0);
  float centre = texelFetch(u_source, p, 0).r;
  bool border = false;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = clamp(p + ivec2(dx, dy), ivec2(0), size - 1);
      border = border || texelFetch(u_source, q, 0).r != 1.0;
    }
  }
  border = border && centre == 1.0;
  frag_color = vec4(border ? u_border_alpha : centre);
}
