// The item screens' registry (from study/questionnaire/item_types.def, in the
// library's order) and what the screens share: the page's panel with its
// prompt, the Next button, and keys that choose only while nothing is typed.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include "app/run/item_screen.h"
#include "app/run/screens.h"
#include "study/protocol/wording.h"

namespace dtlab::run {

#define DTLAB_ITEM_TYPE(id) Result<std::unique_ptr<ItemScreen>> make_##id##_screen(const ItemPage& page);
#include "study/questionnaire/item_types.def"
#undef DTLAB_ITEM_TYPE

namespace {

// One maker per registered item type, in item_types.def order (questionnaire::item_types()'s order).
const std::vector<ItemScreenMaker>& makers() {
  static const std::vector<ItemScreenMaker> all = {
#define DTLAB_ITEM_TYPE(id) &make_##id##_screen,
#include "study/questionnaire/item_types.def"
#undef DTLAB_ITEM_TYPE
  };
  return all;
}

}  // namespace

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string ItemScreen::name() const { return "questionnaire " + item().id; }

Result<std::unique_ptr<ItemScreen>> make_item_screen(const ItemPage& page) {
  const auto types = questionnaire::item_types();
  const questionnaire::ItemType* type = page.question->item->type;
  for (std::size_t i = 0; i < types.size() && i < makers().size(); ++i)
    if (types[i] == type) return makers()[i](page);
  return Error{"", 0, 0, "questionnaire." + page.question->item->id, "its item type has no screen", ErrorKind::internal};
}

void begin_item_panel(const ItemPage& page, const char* id) {
  Ui& ui = *page.ui;
  const session::Question& q = *page.question;
  begin_panel(id);
  ImGui::TextDisabled("%s", page.progress.c_str());
  ImGui::PushTextWrapPos(0.0f);
  ImGui::PushFont(ui.heading_font());
  ImGui::TextUnformatted(q.item->prompt.c_str());
  ImGui::PopFont();
  std::string scope;  // what the question is about, as participants read the levels: "Abstract scenes, X-ray view"
  for (const auto& [factor, level] : q.levels) scope += (scope.empty() ? "" : ", ") + protocol::level_text(*page.spec->protocol, factor, level);
  if (!scope.empty()) ImGui::TextUnformatted(scope.c_str());
  ImGui::PopTextWrapPos();
  ImGui::Spacing();
}

bool typing() { return ImGui::GetIO().WantTextInput; }

bool next_button(Ui& ui, const protocol::Protocol& p, bool enabled, bool text_box) {
  ImGui::Spacing();
  ImGui::BeginDisabled(!enabled);
  const bool clicked = ui.button(protocol::text(p, "question.next"), ImVec2(ui.text_px() * 6, ui.text_px() * 2));
  ImGui::EndDisabled();
  Input& in = ui.input();
  const bool enter = in.key_pressed(GLFW_KEY_ENTER) || in.key_pressed(GLFW_KEY_KP_ENTER);
  const bool key = enter && (!text_box || in.ctrl());
  return enabled && (clicked || key);
}

bool digit_pressed(Ui& ui, int d) { return !typing() && ui.input().key_pressed(GLFW_KEY_0 + d); }

}  // namespace dtlab::run
