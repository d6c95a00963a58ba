// The contact sheet of icons (see icons.h): layout, compositing over grey
// cells, labels with stb_easy_font. Opaque output; pure CPU, no GL.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "study/icons/detail/text.h"
#include "study/icons/icons.h"

namespace dtlab::icons {

namespace {
constexpr std::array<std::uint8_t, 3> kSheetRgb{46, 49, 56};   // around the cells
constexpr std::array<std::uint8_t, 3> kCellRgb{98, 108, 128};  // behind each icon: a mid slate, so pale, grey and dark models all show
constexpr std::array<std::uint8_t, 3> kTextRgb{236, 236, 236};
constexpr std::array<std::uint8_t, 3> kFamilyRgb{250, 214, 120};

// Sheet metrics for one icon size.
struct Metrics {
  int size, scale, pad, line_h;
};
Metrics metrics(int size) {
  const int scale = std::clamp(size / 64, 1, 4);
  return {size, scale, std::max(4, size / 12), (detail::kLineAdvance - 2) * scale};
}

// Families in order of first appearance, with the icons of each.
std::vector<std::pair<std::string, std::vector<std::size_t>>> families(std::span<const Icon> icons) {
  std::vector<std::pair<std::string, std::vector<std::size_t>>> rows;
  for (std::size_t i = 0; i < icons.size(); ++i) {
    const std::string family(icons[i].model->family);
    auto it = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.first == family; });
    if (it == rows.end()) {
      rows.push_back({family, {}});
      it = rows.end() - 1;
    }
    it->second.push_back(i);
  }
  return rows;
}

std::string title_text(int size) {
  return "dtlab WALKTHROUGH object kinds: " + std::to_string(size) + " px icons, standard method";
}
}  // namespace

SheetLayout sheet_layout(std::span<const Icon> icons) {
  if (icons.empty()) throw std::invalid_argument("sheet_layout: no icons");
  const int size = icons[0].image.width;
  for (const Icon& ic : icons)
    if (ic.model == nullptr || ic.image.width != size || ic.image.height != size)
      throw std::invalid_argument("sheet_layout: every icon needs a model and the same square size");
  const Metrics m = metrics(size);
  std::size_t lines = 1;
  for (const Icon& ic : icons)
    lines = std::max(lines, detail::wrap(ic.model->label, size / m.scale).size());
  int gutter_text = 0;
  const auto rows = families(icons);
  for (const auto& r : rows) gutter_text = std::max(gutter_text, detail::text_width(r.first) * m.scale);

  SheetLayout L;
  L.text_scale = m.scale;
  L.rows = static_cast<int>(rows.size());
  for (const auto& r : rows) L.columns = std::max(L.columns, static_cast<int>(r.second.size()));
  const int cell_w = size + m.pad;
  const int label_h = static_cast<int>(lines) * m.line_h;
  const int cell_h = size + m.pad / 2 + label_h + m.pad;
  const int gutter = m.pad + gutter_text + m.pad;
  const int title_h = m.pad + m.line_h + m.pad;
  L.width = std::max(gutter + L.columns * cell_w, m.pad + detail::text_width(title_text(size)) * m.scale + m.pad);
  L.height = title_h + L.rows * cell_h;
  L.icon_rects.resize(icons.size());
  L.label_rects.resize(icons.size());
  for (int r = 0; r < L.rows; ++r)
    for (std::size_t c = 0; c < rows[r].second.size(); ++c) {
      const std::size_t i = rows[r].second[c];
      const int x = gutter + static_cast<int>(c) * cell_w, y = title_h + r * cell_h;
      L.icon_rects[i] = {x, y, size, size};
      L.label_rects[i] = {x, y + size + m.pad / 2, size, label_h};
    }
  return L;
}

render::Image contact_sheet(std::span<const Icon> icons) {
  const SheetLayout L = sheet_layout(icons);
  const int size = icons[0].image.width;
  const Metrics m = metrics(size);
  render::Image sheet;
  sheet.width = L.width;
  sheet.height = L.height;
  sheet.rgba.resize(static_cast<std::size_t>(L.width) * L.height * 4);
  for (std::size_t p = 0; p < sheet.rgba.size(); p += 4) {
    std::copy(kSheetRgb.begin(), kSheetRgb.end(), &sheet.rgba[p]);
    sheet.rgba[p + 3] = 255;
  }
  detail::draw_text(sheet, m.pad, m.pad, title_text(size), m.scale, kTextRgb);
  for (std::size_t i = 0; i < icons.size(); ++i) {
    const auto& rect = L.icon_rects[i];
    const render::Image& img = icons[i].image;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const std::uint8_t* src = img.pixel(x, y);
        std::uint8_t* dst = &sheet.rgba[(static_cast<std::size_t>(rect.y + y) * L.width + rect.x + x) * 4];
        const int a = src[3];
        for (int c = 0; c < 3; ++c) dst[c] = static_cast<std::uint8_t>((src[c] * a + kCellRgb[c] * (255 - a) + 127) / 255);
      }
    const auto& lr = L.label_rects[i];
    const auto lines = detail::wrap(icons[i].model->label, size / m.scale);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      const int w = detail::text_width(lines[k]) * m.scale;
      detail::draw_text(sheet, lr.x + std::max(0, (lr.w - w) / 2), lr.y + static_cast<int>(k) * m.line_h, lines[k],
                        m.scale, kTextRgb);
    }
  }
  // Family names in the left gutter, at the top of each row's icons.
  std::vector<std::string> seen;
  for (std::size_t i = 0; i < icons.size(); ++i) {
    const std::string family(icons[i].model->family);
    if (std::find(seen.begin(), seen.end(), family) != seen.end()) continue;
    seen.push_back(family);
    detail::draw_text(sheet, m.pad, L.icon_rects[i].y + m.pad, family, m.scale, kFamilyRgb);
  }
  return sheet;
}

}  // namespace dtlab::icons
