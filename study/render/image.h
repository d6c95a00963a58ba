// RGBA8 images as plain data and their PNG encoding (stb_image_write).
// Guarantees: rows are stored top row first; write_png either writes the
// whole file or returns an Error naming the path. Never: touches GL.
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

// Writes `image` as PNG. With `keep_alpha` false the alpha channel is written as 255
// (the renderer's alpha is its cumulative alpha buffer, not coverage).
Status write_png(const Image& image, const std::string& path, bool keep_alpha = false);

}  // namespace dtlab::render
