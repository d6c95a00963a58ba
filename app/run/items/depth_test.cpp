// The "depth-test" screen ("depth_test"): the item's static WALKTHROUGH view
// drawn by the real renderer, the pair's two objects marked A and B at their
// projected centres, the prompt above; click A or B (named "A" and "B") or
// press the key.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"
#include "app/run/view.h"

namespace dtlab::run {
namespace {

class DepthTestScreen final : public ItemScreen {
 public:
  DepthTestScreen(const ItemPage& page, const session::DepthTestView& view, std::unique_ptr<SceneView> scene)
      : ItemScreen(page), view_(view), scene_(std::move(scene)) {}
  std::string name() const override { return "depth_test"; }
  bool has_view() const override { return true; }
  Status draw3d() override { return scene_->draw(ui().width(), ui().height(), glm::vec2(0)); }
  bool frame() override {
    const ImGuiIO& io = ImGui::GetIO();
    const session::Viewport window{static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y)};
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, ui().text_px() * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0));
    ImGui::SetNextWindowBgAlpha(0.9f);
    ImGui::Begin("##depth", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::TextUnformatted(protocol::text(protocol(), "depth_test.pair",
                                          {{"progress", page_.progress},
                                           {"pair", std::to_string(question().pair)},
                                           {"pairs", std::to_string(item().integer("pairs"))}})
                               .c_str());
    ImGui::TextUnformatted(item().prompt.c_str());
    ImGui::TextDisabled("%s", protocol::text(protocol(), "depth_test.click").c_str());
    ImGui::End();
    const std::uint32_t ids[2] = {question().object_a, question().object_b};
    const char* names[2] = {"A", "B"};
    for (int k = 0; k < 2; ++k) {
      const auto at = session::depth_test_marker(view_, ids[k], window);
      if (!at) continue;
      ImGui::SetNextWindowPos(ImVec2(at->x, at->y), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
      ImGui::SetNextWindowBgAlpha(0.0f);
      ImGui::Begin(names[k], nullptr,
                   ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoBackground);
      ImGui::PushFont(ui().heading_font());
      if (ui().button(names[k]) || ui().input().key_pressed(k == 0 ? GLFW_KEY_A : GLFW_KEY_B)) chosen_ = ids[k];
      ImGui::PopFont();
      ImGui::End();
    }
    return chosen_.has_value();
  }
  session::QuestionAnswer answer() const override { return static_cast<double>(*chosen_); }

 private:
  const session::DepthTestView& view_;
  std::unique_ptr<SceneView> scene_;
  std::optional<std::uint32_t> chosen_;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_depth_test_screen(const ItemPage& page) {
  const session::DepthTestView* dv = nullptr;
  for (const auto& v : page.spec->depth_tests)
    if (v.item == page.question->item->id) dv = &v;
  if (!dv)
    return Error{"", 0, 0, "questionnaire." + page.question->item->id, "no depth-test view was prepared", ErrorKind::internal};
  auto scene = SceneView::create(dv->scene, dv->frame, dv->camera);
  if (!scene) return scene.error();
  return std::unique_ptr<ItemScreen>(new DepthTestScreen(page, *dv, std::move(scene.value())));
}

}  // namespace dtlab::run
