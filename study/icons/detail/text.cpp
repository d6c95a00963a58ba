// Text rendering with stb_easy_font (see text.h).
#include "study/icons/detail/text.h"

#include <algorithm>
#include <cmath>

#include <stb_easy_font.h>

namespace dtlab::icons::detail {

namespace {
// stb_easy_font takes a mutable C string of printable ASCII.
std::vector<char> c_text(std::string_view text) {
  std::vector<char> s;
  s.reserve(text.size() + 1);
  for (char ch : text) s.push_back(ch >= 32 && ch <= 126 ? ch : '?');
  s.push_back('\0');
  return s;
}

struct FontVertex {  // stb_easy_font's vertex layout
  float x, y, z;
  std::uint8_t color[4];
};
static_assert(sizeof(FontVertex) == 16);
}  // namespace

int text_width(std::string_view text) {
  std::vector<char> s = c_text(text);
  return stb_easy_font_width(s.data());
}

void draw_text(render::Image& image, int x, int y, std::string_view text, int scale, std::array<std::uint8_t, 3> rgb) {
  std::vector<char> s = c_text(text);
  // At most ~30 quads per character (the font's segment tables), 4 vertices each.
  std::vector<FontVertex> quads(s.size() * 30 * 4 + 4);
  const int n = stb_easy_font_print(0.0f, 0.0f, s.data(), nullptr, quads.data(),
                                    static_cast<int>(quads.size() * sizeof(FontVertex)));
  for (int q = 0; q < n; ++q) {
    float x0 = quads[q * 4].x, x1 = x0, y0 = quads[q * 4].y, y1 = y0;
    for (int k = 1; k < 4; ++k) {
      x0 = std::min(x0, quads[q * 4 + k].x);
      x1 = std::max(x1, quads[q * 4 + k].x);
      y0 = std::min(y0, quads[q * 4 + k].y);
      y1 = std::max(y1, quads[q * 4 + k].y);
    }
    const int px0 = std::max(0, x + static_cast<int>(std::lround(x0 * scale)));
    const int px1 = std::min(image.width, x + static_cast<int>(std::lround(x1 * scale)));
    const int py0 = std::max(0, y + static_cast<int>(std::lround(y0 * scale)));
    const int py1 = std::min(image.height, y + static_cast<int>(std::lround(y1 * scale)));
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) {
        std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(py) * image.width + px) * 4];
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
        p[3] = 255;
      }
  }
}

std::vector<std::string> wrap(std::string_view text, int max_width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ') ++i;
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ') ++j;
    if (j == i) break;
    const std::string word(text.substr(i, j - i));
    const std::string joined = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(joined) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = joined;
    }
    i = j;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace dtlab::icons::detail
