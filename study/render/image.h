// RGBA8 images as plain data and their PNG encoding (stb_image_write).
// Guarantees: rows are stored top row first; write_png either writes the
// whole file or returns an Error naming the path; nothing here throws.
// Never: touches GL.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "study/common/error.h"

namespace dtlab::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, top row first
  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// How far image `a` is from image `b` (same size): over the RGB channels, in 8-bit levels.
struct ImageDiff {
  double mae = 0.0;             // mean absolute difference per channel, 0..255
  double pixels_off_pct = 0.0;  // share of pixels (percent) where some channel differs by more than 4
  int max_abs = 0;              // largest channel difference
  long pixels = 0;              // pixels compared
};
// Over every pixel. An invalid_input Error if the sizes differ.
[[nodiscard]] Result<ImageDiff> compare(const Image& a, const Image& b);
// Over the pixels whose byte in `region` (one per pixel, top row first, as Image) is non-zero;
// all zero if none is. An invalid_input Error if the sizes differ.
[[nodiscard]] Result<ImageDiff> compare_in(const Image& a, const Image& b, const std::vector<std::uint8_t>& region);

// Writes `image` as PNG. With `keep_alpha` false the alpha channel is written as 255
// (the renderer's alpha is its cumulative alpha buffer, not coverage).
Status write_png(const Image& image, const std::string& path, bool keep_alpha = false);

}  // namespace dtlab::render
