// Transparent backgrounds without a renderer option for them: the same frame
// rendered over a black and over a white background differs exactly where no
// object is, so each rendered sample is either the object (identical in both)
// or background. Samples are box-filtered into output pixels with straight
// alpha. Pure integer arithmetic on RGBA8 images: deterministic bytes.
// Never: touches GL.
#pragma once
#include "study/render/image.h"

namespace dtlab::icons::detail {

// `over_black` and `over_white`: the same frame, (factor*n) x (factor*n), over backgrounds
// (0,0,0) and (1,1,1). Returns n x n RGBA: alpha = covered samples / factor^2 (rounded),
// colour = the mean of the covered samples (0 where none). Throws std::invalid_argument if
// the sizes differ or are not a multiple of `factor`.
render::Image key_and_downsample(const render::Image& over_black, const render::Image& over_white, int factor);

}  // namespace dtlab::icons::detail
