// The walked-path SVG (study/replay/path.h): the distance walked on the
// floor, the T3 target and a marked answer taken from a recorded trial, a
// panel's size from the plan, several panels laid out in rows under one
// title, and the same bytes for the same input.
#include <gtest/gtest.h>

#include <regex>
#include <string>

#include "study/replay/path.h"

namespace dtlab::replay {
namespace {

// A 4 x 2 plan of two rooms (cells x < 2 and x >= 2) with one doorway between them.
scene::FloorPlan two_rooms() {
  scene::FloorPlan plan;
  plan.width = 4;
  plan.height = 2;
  plan.cell_size = 3.0f;
  plan.room = {0, 0, 1, 1, 0, 0, 1, 1};
  plan.doors = {{1, 0, 2, 0}};
  return plan;
}

store::CameraPose at(double x, double z) { return store::CameraPose{0, x, 1.6, z, 0, 0}; }

std::size_t count(const std::string& s, const std::string& needle) {
  std::size_t n = 0;
  for (auto i = s.find(needle); i != std::string::npos; i = s.find(needle, i + 1)) ++n;
  return n;
}

TEST(WalkedPath, DistanceIsAlongTheFloorOnly) {
  // 3-4-5 on the floor; the eye height changes nowhere, a vertical step would not count.
  std::vector<store::CameraPose> poses = {at(0, 0), at(3, 4), at(3, 4)};
  poses[2].y = 5.0;
  EXPECT_DOUBLE_EQ(walked_distance(poses), 5.0);
  EXPECT_DOUBLE_EQ(walked_distance({}), 0.0);
  EXPECT_DOUBLE_EQ(walked_distance({at(1, 1)}), 0.0);
}

TEST(WalkedPath, TakesTheT3TargetAndAPositionAnswerFromTheTrial) {
  scene::Scene t3;
  t3.task = scene::Task::T3;
  t3.answer.position = {7.5f, 1.5f};
  const std::optional<store::Answer> marked = store::Answer{store::Position{2.0, 4.0}};
  const WalkedPath p = walked_path(t3, marked, {at(1, 1), at(2, 2)}, "trial 3");
  ASSERT_TRUE(p.target && p.answer);
  EXPECT_EQ(*p.target, glm::vec2(7.5f, 1.5f));
  EXPECT_EQ(*p.answer, glm::vec2(2.0f, 4.0f));
  EXPECT_EQ(p.poses.size(), 2u);
  EXPECT_EQ(p.label, "trial 3");

  scene::Scene t4;  // a counting task: no position to find, a count for an answer
  t4.task = scene::Task::T4;
  const WalkedPath q = walked_path(t4, store::Answer{store::Count{3}}, {}, "trial 4");
  EXPECT_FALSE(q.target);
  EXPECT_FALSE(q.answer);
  EXPECT_FALSE(walked_path(t3, std::nullopt, {}, "").answer) << "no answer given";
}

TEST(PathSvg, OnePanelDrawsPlanPathTargetAndAnswer) {
  WalkedPath p{"trial 1", {at(1.5, 1.5), at(4.5, 1.5), at(7.5, 4.5)}, glm::vec2(7.5f, 4.5f), glm::vec2(7.0f, 4.0f)};
  const std::string svg = path_svg(two_rooms(), glm::vec3(1.5f, 1.6f, 1.5f), {p}, 640, "P01");
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_NE(svg.find("walked 7.2 units, o target, x answer"), std::string::npos);  // 3 + sqrt(18) = 7.24
  // Two rooms side by side: one interior wall between x = 2 and 3 cells... split by the doorway in row 0
  // (two pieces) plus the whole edge in row 1: 3 wall lines.
  EXPECT_EQ(count(svg, "<line "), 3u);
  EXPECT_EQ(svg, path_svg(two_rooms(), glm::vec3(1.5f, 1.6f, 1.5f), {p}, 640, "P01")) << "same input, same bytes";
}

TEST(PathSvg, PanelsAreLaidOutInRowsUnderOneTitle) {
  const scene::FloorPlan plan = two_rooms();
  std::vector<PathPanel> panels;
  for (int i = 0; i < 5; ++i)
    panels.push_back(path_panel(plan, glm::vec3(1.5f, 1.6f, 1.5f),
                                {WalkedPath{"trial " + std::to_string(i), {at(1, 1), at(2, 2)}, {}, {}}}, 300));
  // A 4 x 2 plan in a 300 px panel: margin 24, cell (300 - 48) / 4 = 63, legend 22: height 24 + 22 + 126 + 24.
  EXPECT_DOUBLE_EQ(panels[0].width, 300);
  EXPECT_DOUBLE_EQ(panels[0].height, 196);
  EXPECT_EQ(panels[0].markup.find("<svg"), std::string::npos) << "a panel is a fragment";
  const std::string svg = panels_svg(panels, 3, "P01, task T3");
  EXPECT_EQ(count(svg, "<svg"), 1u);
  EXPECT_EQ(count(svg, "<polyline"), 5u);
  EXPECT_NE(svg.find(">P01, task T3</text>"), std::string::npos);
  // 3 columns of 300 px with 8 px gaps; 2 rows of 196 px under a 34 px title.
  EXPECT_NE(svg.find("width=\"916.0\" height=\"434.0\""), std::string::npos) << svg.substr(0, 200);
  EXPECT_NE(svg.find("translate(308.0,34.0)"), std::string::npos);  // row 1, column 2
  EXPECT_NE(svg.find("translate(0.0,238.0)"), std::string::npos);   // row 2, column 1
  EXPECT_NE(svg.find("translate(308.0,238.0)"), std::string::npos);
  EXPECT_EQ(svg.find("translate(616.0,238.0)"), std::string::npos) << "only five panels";
  // Narrow panels leave the marker key to the title.
  EXPECT_EQ(svg.find("o target"), std::string::npos);
}

}  // namespace
}  // namespace dtlab::replay
