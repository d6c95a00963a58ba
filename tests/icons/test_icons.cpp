// Icons of the WALKTHROUGH kinds, rendered once per program through the real
// renderer (OSMesa): every kind framed (coverage, transparent border, exact
// fit along the longer side, centred), its dominant colour the catalogue's
// main colour, the same bytes twice, and every pair of kinds distinguishable
// (the claim of issue 3: silhouettes or colours differ enough to tell apart).
// The keying step is also checked alone on hand-made images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "app/platform/gl_context.h"
#include "study/icons/detail/keying.h"
#include "study/icons/icons.h"

namespace dtlab::icons {
namespace {

// The process's headless context, current on return (ctest runs every test in its own process).
void use_context() {
  static std::unique_ptr<platform::GlContext> ctx = [] {
    auto c = platform::create_headless(16, 16);
    if (!c) {
      std::fprintf(stderr, "no headless GL context: %s\n", c.error().to_string().c_str());
      std::abort();
    }
    return std::move(c.value());
  }();
  ctx->make_current();
}

// Catalogue kind i's default icon, rendered on first use only (a test of one kind renders one).
const Icon& icon_at(std::size_t i) {
  static std::vector<std::unique_ptr<Icon>> cache(scene::model_catalogue().size());
  use_context();
  if (!cache[i]) {
    const scene::ModelInfo& m = scene::model_catalogue()[i];
    auto r = render_icon(m);
    if (!r) {
      std::fprintf(stderr, "render_icon(%s) failed: %s\n", std::string(m.kind).c_str(), r.error().to_string().c_str());
      std::abort();
    }
    cache[i] = std::make_unique<Icon>(Icon{&m, std::move(r.value())});
  }
  return *cache[i];
}

const std::vector<Icon>& all_icons() {
  static std::vector<Icon> icons = [] {
    std::vector<Icon> v;
    for (std::size_t i = 0; i < scene::model_catalogue().size(); ++i) v.push_back(icon_at(i));
    return v;
  }();
  use_context();
  return icons;
}

int alpha(const render::Image& img, int x, int y) { return img.pixel(x, y)[3]; }

struct Box {
  int x0 = std::numeric_limits<int>::max(), y0 = x0, x1 = -1, y1 = -1;  // inclusive pixel bounds of alpha > 0
};
Box alpha_box(const render::Image& img) {
  Box b;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (alpha(img, x, y) > 0) {
        b.x0 = std::min(b.x0, x);
        b.x1 = std::max(b.x1, x);
        b.y0 = std::min(b.y0, y);
        b.y1 = std::max(b.y1, y);
      }
  return b;
}

std::string kind_name(const testing::TestParamInfo<std::size_t>& info) {
  return std::string(scene::model_catalogue()[info.param].kind);
}

class EveryKind : public testing::TestWithParam<std::size_t> {
 protected:
  const Icon& icon() const { return icon_at(GetParam()); }
};
INSTANTIATE_TEST_SUITE_P(Icons, EveryKind, testing::Range<std::size_t>(0, scene::model_catalogue().size()), kind_name);

TEST_P(EveryKind, IsTheDefaultSizeWithATransparentBackground) {
  const render::Image& img = icon().image;
  ASSERT_EQ(img.width, 96);
  ASSERT_EQ(img.height, 96);
  ASSERT_EQ(img.rgba.size(), 96u * 96u * 4u);
  for (int x : {0, 95})
    for (int y : {0, 95}) EXPECT_EQ(alpha(img, x, y), 0) << "corner " << x << "," << y;
  for (std::size_t p = 0; p < img.rgba.size(); p += 4)  // background pixels carry no colour
    if (img.rgba[p + 3] == 0) {
      ASSERT_EQ(img.rgba[p] + img.rgba[p + 1] + img.rgba[p + 2], 0);
    }
}

// Measured: 17% to 52%, except the two tall thin models that fill the icon's height but little
// of its width: bird on its perch stand 8.7%, floor lamp 10.5%. The exact fit is tested below.
TEST_P(EveryKind, CoverageSaysTheModelIsFramed) {
  const double c = coverage(icon().image);
  EXPECT_GE(c, 0.08) << icon().model->kind << " is too small in its icon";
  EXPECT_LE(c, 0.85) << icon().model->kind << " fills its icon";
}

TEST_P(EveryKind, FitsTheFrameExactlyInsideTheMargin) {
  // Default margin 5% of 96 = 4.8 px on each side: the model spans 86.4 px along its longer side.
  const render::Image& img = icon().image;
  const Box b = alpha_box(img);
  ASSERT_GE(b.x1, 0) << "empty icon";
  for (int border = 0; border < 4; ++border)  // no object pixel in the 4-pixel border ring
    for (int i = 0; i < 96; ++i) {
      EXPECT_EQ(alpha(img, i, border), 0);
      EXPECT_EQ(alpha(img, i, 95 - border), 0);
      EXPECT_EQ(alpha(img, border, i), 0);
      EXPECT_EQ(alpha(img, 95 - border, i), 0);
    }
  const int w = b.x1 - b.x0 + 1, h = b.y1 - b.y0 + 1;
  EXPECT_NEAR(std::max(w, h), 86.4, 2.0) << "the longer side spans the frame minus the margins";
  EXPECT_NEAR(0.5 * (b.x0 + b.x1 + 1), 48.0, 1.5) << "centred horizontally";
  EXPECT_NEAR(0.5 * (b.y0 + b.y1 + 1), 48.0, 1.5) << "centred vertically";
}

// Each opaque pixel is a shade k * c (k in the headlight's 0.3..1 range) of one of the
// model's vertex colours c; the colour that explains most pixels is the dominant one. It is
// the catalogue's main colour for 9 kinds. For 5 kinds another part covers more of the 3/4
// view (measured at 96 px, shares of opaque pixels): the bird's grey perch stand (64%, the
// yellow bird 22% + 10% wings), the fish tank's sand (35%, orange fish 31%), the bike's tyres
// (51%, blue frame 35%), the motorbike's chrome (36%, its near-black paint 12% + tyres 32%),
// the bed's darker pink headboard (50%, blanket 31%). Those are pinned here as measured, and
// the main colour must still be a large part of every icon (>= 10%).
struct DominantCase {
  std::string_view kind;
  glm::vec3 other;  // the measured dominant part's colour where it is not the main colour
};
const DominantCase kNotMainColour[] = {
    {"bird", {0.35f, 0.35f, 0.38f}},       {"fish", {0.85f, 0.80f, 0.62f}},
    {"bike", {0.06f, 0.06f, 0.06f}},       {"motorbike", {0.72f, 0.72f, 0.75f}},
    {"bed", {0.75f, 0.30f, 0.50f}},
};

TEST_P(EveryKind, DominantColourIsTheCatalogueColour) {
  const scene::ModelInfo& m = *icon().model;
  const scene::Mesh mesh = m.build();
  std::vector<glm::vec3> palette;
  for (const scene::Vertex& v : mesh.vertices)
    if (std::none_of(palette.begin(), palette.end(), [&](glm::vec3 c) { return glm::length(c - v.color) < 1e-4f; }))
      palette.push_back(v.color);
  std::vector<int> votes(palette.size(), 0);
  int opaque = 0;
  const render::Image& img = icon().image;
  for (std::size_t p = 0; p < img.rgba.size(); p += 4) {
    if (img.rgba[p + 3] < 255) continue;  // edges mix colours
    ++opaque;
    const glm::vec3 px(img.rgba[p] / 255.0f, img.rgba[p + 1] / 255.0f, img.rgba[p + 2] / 255.0f);
    std::size_t best = 0;
    float best_err = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < palette.size(); ++i) {
      const glm::vec3 c = palette[i];
      const float cc = glm::dot(c, c);
      const float k = cc > 0.0f ? std::clamp(glm::dot(px, c) / cc, 0.3f, 1.0f) : 1.0f;
      const float err = glm::length(px - k * c);
      if (err < best_err) best_err = err, best = i;
    }
    ++votes[best];
  }
  const auto top = std::max_element(votes.begin(), votes.end()) - votes.begin();
  glm::vec3 expected = m.main_color;
  for (const DominantCase& c : kNotMainColour)
    if (c.kind == m.kind) expected = c.other;
  EXPECT_LT(glm::length(palette[top] - expected), 1e-4f)
      << m.kind << ": dominant colour (" << palette[top].r << ", " << palette[top].g << ", " << palette[top].b
      << "), expected (" << expected.r << ", " << expected.g << ", " << expected.b << ")";
  int main_votes = 0;
  for (std::size_t i = 0; i < palette.size(); ++i)
    if (glm::length(palette[i] - m.main_color) < 1e-4f) main_votes += votes[i];
  EXPECT_GE(main_votes, opaque / 10) << m.kind << ": the catalogue colour covers " << main_votes << " of " << opaque
                                     << " opaque pixels";
}

TEST(Icons, SameBytesTwiceInOneProcess) {
  const auto& first = all_icons();
  auto again = render_all();
  ASSERT_TRUE(again.ok()) << again.error().to_string();
  ASSERT_EQ(again.value().size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i)
    EXPECT_EQ(again.value()[i].image.rgba, first[i].image.rgba) << first[i].model->kind;
}

TEST(Icons, OneIconPerCatalogueKindInOrder) {
  const auto& icons = all_icons();
  ASSERT_EQ(icons.size(), scene::model_catalogue().size());
  for (std::size_t i = 0; i < icons.size(); ++i) EXPECT_EQ(icons[i].model, &scene::model_catalogue()[i]);
}

TEST(Icons, OtherSizesKeepTheFraming) {
  use_context();
  IconOptions o;
  o.size = 40;
  auto icon = render_icon(*scene::find_model("truck"), o);
  ASSERT_TRUE(icon.ok());
  EXPECT_EQ(icon.value().width, 40);
  const Box b = alpha_box(icon.value());
  EXPECT_NEAR(std::max(b.x1 - b.x0 + 1, b.y1 - b.y0 + 1), 36.0, 1.5);
}

TEST(Icons, OptionsOutOfRangeAreRejected) {
  IconOptions o;
  o.size = 8;
  EXPECT_THROW(validate(o), std::invalid_argument);
  o = {};
  o.margin = 0.5f;
  EXPECT_THROW(validate(o), std::invalid_argument);
  o = {};
  o.supersample = 0;
  EXPECT_THROW(validate(o), std::invalid_argument);
  EXPECT_NO_THROW(validate(IconOptions{}));
}

// --- distinguishability --------------------------------------------------------------------
// Shape: silhouette IoU, intersection over union of the pixels the two models cover (alpha >=
// 128) in their own icons. Colour: histogram intersection of the opaque pixels' colours in
// 8 x 8 x 8 RGB bins (1 = the same colour distribution, 0 = no colour in common). A pair is told
// apart when its shapes or its colours differ: IoU < kMaxIou or colour overlap < kMaxColourOverlap.
// Measured at 96 px over the 91 pairs: IoU reaches 0.82 (car/sofa, boxy side views) but every
// pair above 0.6 overlaps at most 0.27 in colour (car/truck: red/green); overlap reaches 0.58
// (bike/motorbike: black tyres) but every pair above 0.35 has IoU at most 0.36. This test checks
// issue 3's claim that the kinds are distinguishable in their icons; it prints both maxima.
constexpr double kMaxIou = 0.6;
constexpr double kMaxColourOverlap = 0.35;

double iou(const render::Image& a, const render::Image& b) {
  long inter = 0, uni = 0;
  for (std::size_t p = 3; p < a.rgba.size(); p += 4) {
    const bool ia = a.rgba[p] >= 128, ib = b.rgba[p] >= 128;
    inter += ia && ib;
    uni += ia || ib;
  }
  return uni ? static_cast<double>(inter) / static_cast<double>(uni) : 1.0;
}

std::vector<double> colour_histogram(const render::Image& img) {
  std::vector<double> h(512, 0.0);
  double n = 0.0;
  for (std::size_t p = 0; p < img.rgba.size(); p += 4) {
    if (img.rgba[p + 3] < 255) continue;
    ++h[(img.rgba[p] / 32) * 64 + (img.rgba[p + 1] / 32) * 8 + img.rgba[p + 2] / 32];
    ++n;
  }
  for (double& v : h) v /= std::max(n, 1.0);
  return h;
}

double colour_overlap(const render::Image& a, const render::Image& b) {
  const auto ha = colour_histogram(a), hb = colour_histogram(b);
  double s = 0.0;
  for (std::size_t i = 0; i < ha.size(); ++i) s += std::min(ha[i], hb[i]);
  return s;
}

TEST(Icons, EveryPairOfKindsIsDistinguishable) {
  const auto& icons = all_icons();
  int pairs = 0, within_family = 0;
  double max_iou = 0.0, max_overlap = 0.0;
  for (std::size_t i = 0; i < icons.size(); ++i)
    for (std::size_t j = i + 1; j < icons.size(); ++j) {
      const double s = iou(icons[i].image, icons[j].image);
      const double c = colour_overlap(icons[i].image, icons[j].image);
      ++pairs;
      within_family += icons[i].model->family == icons[j].model->family;
      max_iou = std::max(max_iou, s);
      max_overlap = std::max(max_overlap, c);
      EXPECT_TRUE(s < kMaxIou || c < kMaxColourOverlap)
          << icons[i].model->kind << " vs " << icons[j].model->kind << ": silhouette IoU " << s
          << " and colour overlap " << c << " (hard to tell apart)";
    }
  EXPECT_EQ(pairs, 91);
  EXPECT_EQ(within_family, 6 + 6 + 15);
  std::printf("%d pairs: largest silhouette IoU %.3f, largest colour overlap %.3f\n", pairs, max_iou, max_overlap);
}

// The measures themselves: an icon is identical to itself, and two made-up icons of the same
// silhouette but different colours separate by colour alone.
TEST(Icons, TheMeasuresSeparateWhatTheyShould) {
  const render::Image& dog = icon_at(0).image;
  EXPECT_DOUBLE_EQ(iou(dog, dog), 1.0);
  EXPECT_NEAR(colour_overlap(dog, dog), 1.0, 1e-12);
  render::Image blue = dog;
  for (std::size_t p = 0; p < blue.rgba.size(); p += 4)
    if (blue.rgba[p + 3] > 0) blue.rgba[p] = 0, blue.rgba[p + 1] = 0, blue.rgba[p + 2] = 200;
  EXPECT_DOUBLE_EQ(iou(dog, blue), 1.0);
  EXPECT_LT(colour_overlap(dog, blue), 0.05);
}

// A renderer-free check of the keying: known samples over black and white backgrounds.
TEST(Keying, AlphaIsTheCoveredShareAndColourTheCoveredMean) {
  render::Image black, white;
  black.width = white.width = 2;
  black.height = white.height = 2;
  black.rgba = {10, 20, 30, 255, 0, 0, 0, 255, 50, 60, 70, 255, 0, 0, 0, 255};
  white.rgba = {10, 20, 30, 255, 255, 255, 255, 255, 50, 60, 70, 255, 255, 255, 255, 255};
  const render::Image out = detail::key_and_downsample(black, white, 2);
  ASSERT_EQ(out.width, 1);
  EXPECT_EQ(out.rgba, (std::vector<std::uint8_t>{30, 40, 50, 128}));  // 2 of 4 covered, mean of the two
  // A black object sample stays black over white: it is object, not background.
  black.rgba = {0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255};
  white.rgba = {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255};
  EXPECT_EQ(detail::key_and_downsample(black, white, 2).rgba, (std::vector<std::uint8_t>{0, 0, 0, 64}));
  render::Image odd = black;
  odd.width = 1;
  odd.height = 4;
  EXPECT_THROW(detail::key_and_downsample(odd, white, 2), std::invalid_argument);
}

}  // namespace
}  // namespace dtlab::icons
