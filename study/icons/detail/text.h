// Text on RGBA8 images with stb_easy_font (libstb-dev): the font's quads are
// axis-aligned rectangles, filled at an integer scale, so text is crisp and
// deterministic. ASCII 32..126 only; other bytes draw as '?'. Never: loads a
// font file or draws outside the image (quads are clipped).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "study/render/image.h"

namespace dtlab::icons::detail {

inline constexpr int kLineAdvance = 12;  // stb_easy_font's line step, font units

int text_width(std::string_view text);  // one line, font units (scale 1 pixels)

// Draws one line with its top-left at (x, y) pixels, each font unit `scale` pixels, in `rgb`.
void draw_text(render::Image& image, int x, int y, std::string_view text, int scale, std::array<std::uint8_t, 3> rgb);

// Greedy word wrap at spaces: lines no wider than `max_width` font units where possible
// (a single word wider than that gets its own line).
std::vector<std::string> wrap(std::string_view text, int max_width);

}  // namespace dtlab::icons::detail
