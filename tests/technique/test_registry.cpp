// The technique registry (study/technique): one registration per method and
// per key group, every name a user can write unique, and the conversions of
// the protocol's keys to frame settings as docs/render.md states them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "study/technique/technique.h"

namespace dtlab::technique {
namespace {

TEST(Registry, EveryMethodIsRegisteredOnceInEnumOrderAndFoundByItsName) {
  std::set<std::string> names;
  std::size_t i = 0;
  for (const Technique* t : all()) {
    EXPECT_EQ(static_cast<std::size_t>(t->id), i++) << t->name;
    EXPECT_TRUE(names.insert(std::string(t->name)).second) << t->name << " registered twice";
    EXPECT_EQ(find(t->name), t);
    EXPECT_EQ(parse_method(to_string(t->id)), t->id);
    EXPECT_FALSE(t->summary.empty()) << t->name;
    EXPECT_TRUE(t->reads(Group::culling)) << t->name << ": occlusion culling runs under every method";
  }
  EXPECT_EQ(i, kMethodCount);
  EXPECT_EQ(find("xray"), nullptr);
  EXPECT_EQ(technique::names(", ").find("standard, dt-seed, dt-fast"), 0u);
}

// A [rendering.*] table is flat: two groups declaring the same key would read each other's value.
TEST(Registry, EveryKeyNameBelongsToOneGroup) {
  std::set<std::string> keys;
  std::size_t i = 0;
  for (const KeyGroup* g : key_groups()) {
    EXPECT_EQ(static_cast<std::size_t>(g->id), i++) << g->name;
    for (const KeySpec& k : g->keys) {
      EXPECT_TRUE(keys.insert(std::string(k.name)).second) << k.name << " in two groups";
      EXPECT_NE(std::string(k.name), "method");
      if (k.kind == KeySpec::Kind::number || k.kind == KeySpec::Kind::integer) {
        EXPECT_LT(k.min, k.max) << k.name;
      }
      if (k.kind == KeySpec::Kind::choice) {
        EXPECT_FALSE(k.choices.empty()) << k.name;
      }
    }
  }
}

TEST(Registry, TheDynamicTransparencyKeysBecomeTheArticlesUnitsAtTheViewport) {
  Keys keys;  // the protocol's defaults: n = 8 mask pixels of a 128 mask
  keys.dt.mode = "active";
  keys.guard.r1_guard = false;
  MethodSettings s;
  ASSERT_FALSE(frame_settings(of(Method::dt_fast), keys, 800, 600, s));
  EXPECT_EQ(s.method, Method::dt_fast);
  // 8 texels of 800/128 x 600/128 pixels: 8 sqrt(800 x 600) / 128 = 43.30 output pixels.
  EXPECT_NEAR(s.dt.gradient_px, 43.30127, 1e-4);
  EXPECT_EQ(s.dt.mode, DtMode::active);
  EXPECT_EQ(s.dt.searchlight_center, glm::vec2(400.0f, 300.0f));
  EXPECT_FLOAT_EQ(s.dt.searchlight_radius, 0.2f * 600.0f);
  EXPECT_FALSE(s.dt.r1_guard);
  // A mask finer than the view can show becomes the view's own resolution (0).
  keys.dt.mask_resolution = 256;
  ASSERT_FALSE(frame_settings(of(Method::dt_seed), keys, 160, 120, s));
  EXPECT_EQ(s.dt.mask_resolution, 0);
}

TEST(Registry, AKeyTheFrameCannotTakeIsNamedAsTheAuthorWroteIt) {
  Keys keys;
  keys.lens.radius = 2.0;
  keys.lens.distance = 10.0;
  keys.dt.mode = "passive";  // a lens is active or fixed
  MethodSettings s;
  const auto problem = frame_settings(of(Method::lens), keys, 800, 600, s);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "mode");
  keys.dt.mode = "fixed";
  keys.lens.shape = "torus";
  const auto shape = frame_settings(of(Method::lens), keys, 800, 600, s);
  ASSERT_TRUE(shape);
  EXPECT_EQ(shape->key, "shape");
}

TEST(Registry, TheAidFollowsThePointerOnlyWhereTheMethodHasOne) {
  MethodSettings s;
  s.method = Method::lens;
  s.lens.follows_cursor = true;
  aim(s, {10.0f, 20.0f});
  EXPECT_EQ(s.lens.center, glm::vec2(10.0f, 20.0f));
  EXPECT_EQ(s.dt.searchlight_center, glm::vec2(0.0f)) << "passive: no searchlight to move";
  s.method = Method::standard;
  s.lens.center = {};
  aim(s, {5.0f, 6.0f});
  EXPECT_EQ(s.lens.center, glm::vec2(0.0f)) << "a lens setting under another method is not the aid";
}

}  // namespace
}  // namespace dtlab::technique
