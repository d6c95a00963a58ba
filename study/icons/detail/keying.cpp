// Background keying and box-filter downsampling for icons (see keying.h).
#include "study/icons/detail/keying.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace dtlab::icons::detail {

render::Image key_and_downsample(const render::Image& over_black, const render::Image& over_white, int factor) {
  if (factor < 1) throw std::invalid_argument("key_and_downsample: factor must be >= 1");
  if (over_black.width != over_white.width || over_black.height != over_white.height ||
      over_black.width % factor != 0 || over_black.height % factor != 0)
    throw std::invalid_argument("key_and_downsample: images must be the same size, a multiple of " +
                                std::to_string(factor) + " (got " + std::to_string(over_black.width) + "x" +
                                std::to_string(over_black.height) + " and " + std::to_string(over_white.width) +
                                "x" + std::to_string(over_white.height) + ")");
  render::Image out;
  out.width = over_black.width / factor;
  out.height = over_black.height / factor;
  out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 0);
  const int samples = factor * factor;
  for (int oy = 0; oy < out.height; ++oy)
    for (int ox = 0; ox < out.width; ++ox) {
      int covered = 0;
      int sum[3] = {0, 0, 0};
      for (int sy = 0; sy < factor; ++sy)
        for (int sx = 0; sx < factor; ++sx) {
          const std::uint8_t* b = over_black.pixel(ox * factor + sx, oy * factor + sy);
          const std::uint8_t* w = over_white.pixel(ox * factor + sx, oy * factor + sy);
          // Background: 0 in one frame, 255 in the other. An object sample is the same in both.
          int diff = 0;
          for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(w[c]) - int(b[c])));
          if (diff >= 128) continue;
          ++covered;
          for (int c = 0; c < 3; ++c) sum[c] += b[c];
        }
      std::uint8_t* o = &out.rgba[(static_cast<std::size_t>(oy) * out.width + ox) * 4];
      if (covered == 0) continue;
      for (int c = 0; c < 3; ++c) o[c] = static_cast<std::uint8_t>((sum[c] + covered / 2) / covered);
      o[3] = static_cast<std::uint8_t>((covered * 255 + samples / 2) / samples);
    }
  return out;
}

}  // namespace dtlab::icons::detail
