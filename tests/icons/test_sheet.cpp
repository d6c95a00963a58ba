// The contact sheet: its size from the layout rules (worked out by hand for
// 96 px icons), one row per family, icons drawn where the layout says over the
// grey cell, a label under every icon, nothing outside the sheet. Uses
// synthetic icons (no GL): the sheet is pure CPU work.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "study/icons/detail/text.h"
#include "study/icons/icons.h"

namespace dtlab::icons {
namespace {

// A synthetic icon: an opaque square of `rgb` in the middle half, transparent elsewhere.
render::Image square_icon(int size, std::array<std::uint8_t, 3> rgb) {
  render::Image img;
  img.width = img.height = size;
  img.rgba.assign(static_cast<std::size_t>(size) * size * 4, 0);
  for (int y = size / 4; y < 3 * size / 4; ++y)
    for (int x = size / 4; x < 3 * size / 4; ++x) {
      std::uint8_t* p = &img.rgba[(static_cast<std::size_t>(y) * size + x) * 4];
      p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
    }
  return img;
}

std::vector<Icon> catalogue_icons(int size) {
  std::vector<Icon> icons;
  for (const scene::ModelInfo& m : scene::model_catalogue())
    icons.push_back({&m, square_icon(size, {200, static_cast<std::uint8_t>(10 * icons.size()), 20})});
  return icons;
}

TEST(Sheet, DimensionsFollowTheLayoutRules) {
  // 96 px icons: text scale 1, padding 8, line height 10; "director's chair" (the longest label)
  // fits 96 font units on one line. A cell is 96 + 8 wide and 96 + 4 + 10 + 8 = 118 tall (icon,
  // half a pad, one label line, a pad). Rows: pet, vehicle, furniture (3); columns: furniture's
  // 6 kinds. Title band 8 + 10 + 8 = 26; left gutter: the widest family name plus two pads.
  const auto icons = catalogue_icons(96);
  const SheetLayout L = sheet_layout(icons);
  EXPECT_EQ(L.text_scale, 1);
  EXPECT_EQ(L.rows, 3);
  EXPECT_EQ(L.columns, 6);
  EXPECT_EQ(detail::wrap("director's chair", 96).size(), 1u);
  EXPECT_EQ(L.height, 26 + 3 * 118);
  const int gutter = 8 + detail::text_width("furniture") + 8;
  EXPECT_EQ(L.width, std::max(gutter + 6 * 104, 16 + detail::text_width(
                                                         "dtlab WALKTHROUGH object kinds: 96 px icons, standard method")));
  const render::Image sheet = contact_sheet(icons);
  EXPECT_EQ(sheet.width, L.width);
  EXPECT_EQ(sheet.height, L.height);
  EXPECT_EQ(sheet.rgba.size(), static_cast<std::size_t>(L.width) * L.height * 4);
}

TEST(Sheet, OneRowPerFamilyInCatalogueOrder) {
  const auto icons = catalogue_icons(96);
  const SheetLayout L = sheet_layout(icons);
  std::set<std::pair<int, int>> cells;
  for (std::size_t i = 0; i < icons.size(); ++i) {
    const auto& r = L.icon_rects[i];
    EXPECT_TRUE(cells.insert({r.x, r.y}).second) << "two icons in one cell";
    EXPECT_GE(r.x, 0);
    EXPECT_LE(r.x + r.w, L.width);
    EXPECT_LE(L.label_rects[i].y + L.label_rects[i].h, L.height);
    EXPECT_GE(L.label_rects[i].y, r.y + r.h) << "label under its icon";
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_EQ(icons[i].model->family == icons[j].model->family, L.icon_rects[i].y == L.icon_rects[j].y)
          << icons[i].model->kind << " / " << icons[j].model->kind;
  }
  EXPECT_LT(L.icon_rects[0].y, L.icon_rects[4].y);   // pets above vehicles
  EXPECT_LT(L.icon_rects[4].y, L.icon_rects[8].y);   // vehicles above furniture
}

TEST(Sheet, IconsAreCompositedWhereTheLayoutSaysAndLabelled) {
  const auto icons = catalogue_icons(96);
  const SheetLayout L = sheet_layout(icons);
  const render::Image sheet = contact_sheet(icons);
  for (std::size_t p = 3; p < sheet.rgba.size(); p += 4) ASSERT_EQ(sheet.rgba[p], 255) << "the sheet is opaque";
  for (std::size_t i = 0; i < icons.size(); ++i) {
    const auto& r = L.icon_rects[i];
    const std::uint8_t* centre = sheet.pixel(r.x + 48, r.y + 48);  // opaque part of the icon
    EXPECT_EQ(centre[0], 200);
    EXPECT_EQ(centre[1], 10 * i);
    EXPECT_EQ(centre[2], 20);
    const std::uint8_t* corner = sheet.pixel(r.x + 2, r.y + 2);  // transparent part: the grey cell
    EXPECT_EQ(corner[0], 98);
    EXPECT_EQ(corner[1], 108);
    EXPECT_EQ(corner[2], 128);
    int text_pixels = 0;  // the label's light text inside its area
    const auto& lr = L.label_rects[i];
    for (int y = lr.y; y < lr.y + lr.h; ++y)
      for (int x = lr.x; x < lr.x + lr.w; ++x) text_pixels += sheet.pixel(x, y)[0] == 236;
    EXPECT_GE(text_pixels, 10 * static_cast<int>(icons[i].model->label.size()) / 2) << icons[i].model->kind;
  }
}

TEST(Sheet, LargerIconsScaleTheText) {
  const SheetLayout L = sheet_layout(catalogue_icons(128));
  EXPECT_EQ(L.text_scale, 2);
  EXPECT_EQ(L.icon_rects[0].w, 128);
}

TEST(Sheet, MixedSizesOrNoIconsAreRejected) {
  auto icons = catalogue_icons(96);
  icons[3].image = square_icon(64, {1, 2, 3});
  EXPECT_THROW(sheet_layout(icons), std::invalid_argument);
  EXPECT_THROW(sheet_layout(std::span<const Icon>{}), std::invalid_argument);
}

TEST(Text, WrapAndWidth) {
  EXPECT_GT(detail::text_width("dog"), 0);
  EXPECT_EQ(detail::text_width("dog dog"), 2 * detail::text_width("dog") + detail::text_width(" "));
  EXPECT_EQ(detail::wrap("director's chair", 40), (std::vector<std::string>{"director's", "chair"}));
  EXPECT_EQ(detail::wrap("  a   b ", 1000), (std::vector<std::string>{"a b"}));
  EXPECT_TRUE(detail::wrap("", 10).empty());
}

}  // namespace
}  // namespace dtlab::icons
