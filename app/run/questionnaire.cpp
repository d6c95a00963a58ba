// WindowResponder::answer_questionnaire (responder.h): one page per
// question, in the protocol's order. Ratings are buttons from scale_min to
// scale_max (digit keys too), choices one button per option (the neutral
// one included; number keys 1..n too), and the static depth test one
// WALKTHROUGH view per item with each pair's two objects marked A and B:
// click the closer one (or press A or B). Answers are returned to the
// runner, which scores the depth test and stores everything in one
// transaction.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>

#include "app/run/console.h"
#include "app/run/responder.h"
#include "app/run/screens.h"
#include "app/run/view.h"

namespace dtlab::run {

namespace {

std::string scope_text(const session::Question& q) {
  std::string s;
  for (const auto& [factor, level] : q.levels) s += (s.empty() ? "" : ", ") + factor + ": " + level;
  return s;
}

}  // namespace

Result<std::vector<session::QuestionAnswer>> WindowResponder::answer_questionnaire(
    const session::QuestionnaireSpec& spec) {
  console_->set_trial(nullptr);
  std::vector<session::QuestionAnswer> answers;
  Input& in = ui_.input();
  for (std::size_t i = 0; i < spec.questions.size(); ++i) {
    const session::Question& q = spec.questions[i];
    const protocol::QuestionnaireItem& item = *q.item;
    const std::string progress = "Question " + std::to_string(i + 1) + " of " + std::to_string(spec.questions.size());
    std::optional<session::QuestionAnswer> answer;
    ui_.new_instance();  // every question restarts its script section, even with the same screen name
    if (item.type == protocol::ItemType::depth_test) {
      const session::DepthTestView* dv = nullptr;
      for (const auto& v : spec.depth_tests)
        if (v.item == item.id) dv = &v;
      if (!dv) return Error{"", 0, 0, "questionnaire." + item.id, "no depth-test view was prepared", ErrorKind::internal};
      auto view = SceneView::create(dv->scene, dv->frame, dv->camera);
      if (!view) return view.error();
      Status st = loop("depth_test", [&] { (*view)->draw(ui_.width(), ui_.height(), glm::vec2(0)); }, [&] {
        const ImGuiIO& io = ImGui::GetIO();
        const session::Viewport window{static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y)};
        ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, ui_.text_px() * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0));
        ImGui::SetNextWindowBgAlpha(0.9f);
        ImGui::Begin("##depth", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::Text("%s. Pair %d of %d", progress.c_str(), q.pair, item.pairs);
        ImGui::TextUnformatted(item.prompt.c_str());
        ImGui::TextDisabled("Click A or B (or press the key).");
        ImGui::End();
        const std::uint32_t ids[2] = {q.object_a, q.object_b};
        const char* names[2] = {"A", "B"};
        for (int k = 0; k < 2; ++k) {
          const auto at = session::depth_test_marker(*dv, ids[k], window);
          if (!at) continue;
          ImGui::SetNextWindowPos(ImVec2(at->x, at->y), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
          ImGui::SetNextWindowBgAlpha(0.0f);
          ImGui::Begin(names[k], nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                              ImGuiWindowFlags_NoBackground);
          ImGui::PushFont(ui_.heading_font());
          if (ui_.button(names[k]) || in.key_pressed(k == 0 ? GLFW_KEY_A : GLFW_KEY_B))
            answer = static_cast<double>(ids[k]);
          ImGui::PopFont();
          ImGui::End();
        }
        return answer.has_value();
      });
      if (!st) return st.error();
    } else if (item.type == protocol::ItemType::rating) {
      std::vector<std::string> labels;
      for (int v = item.scale_min; v <= item.scale_max; ++v) labels.push_back(std::to_string(v));
      Status st = loop("questionnaire " + item.id, {}, [&] {
        begin_panel("##rating");
        ImGui::TextDisabled("%s", progress.c_str());
        ImGui::PushTextWrapPos(0.0f);
        ImGui::PushFont(ui_.heading_font());
        ImGui::TextUnformatted(item.prompt.c_str());
        ImGui::PopFont();
        if (!q.levels.empty()) ImGui::Text("%s", scope_text(q).c_str());
        ImGui::PopTextWrapPos();
        ImGui::Spacing();
        int chosen = choice_buttons(ui_, labels);
        for (int v = item.scale_min; v <= item.scale_max; ++v)
          if (v >= 0 && v <= 9 && in.key_pressed(GLFW_KEY_0 + v)) chosen = v - item.scale_min;
        if (chosen >= 0) answer = static_cast<double>(item.scale_min + chosen);
        ImGui::End();
        return answer.has_value();
      });
      if (!st) return st.error();
    } else {
      Status st = loop("questionnaire " + item.id, {}, [&] {
        begin_panel("##choice");
        ImGui::TextDisabled("%s", progress.c_str());
        ImGui::PushTextWrapPos(0.0f);
        ImGui::PushFont(ui_.heading_font());
        ImGui::TextUnformatted(item.prompt.c_str());
        ImGui::PopFont();
        ImGui::PopTextWrapPos();
        ImGui::Spacing();
        int chosen = choice_buttons(ui_, q.options);
        for (std::size_t k = 0; k < q.options.size() && k < 9; ++k)
          if (in.key_pressed(GLFW_KEY_1 + static_cast<int>(k))) chosen = static_cast<int>(k);
        if (chosen >= 0) answer = q.options[static_cast<std::size_t>(chosen)];
        ImGui::End();
        return answer.has_value();
      });
      if (!st) return st.error();
    }
    answers.push_back(std::move(*answer));
  }
  return answers;
}

}  // namespace dtlab::run
