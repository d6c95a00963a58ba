// The "numeric" screen: a "Value" field that has the keyboard from the
// start, the unit beside it, what is expected under it; Next (or Enter) once
// the number is one the item takes (its type's own check decides).
#include <imgui.h>

#include <array>
#include <cstdlib>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"

namespace dtlab::run {
namespace {

class NumericScreen final : public ItemScreen {
 public:
  explicit NumericScreen(const ItemPage& page) : ItemScreen(page) {}
  bool frame() override {
    begin_item_panel(page_, "##numeric");
    if (first_) ImGui::SetKeyboardFocusHere();
    first_ = false;
    ImGui::SetNextItemWidth(ui().text_px() * 8);
    ImGui::InputText("##value", text_.data(), text_.size(), ImGuiInputTextFlags_CharsScientific);
    ui().name_item("Value");
    const std::string& unit = item().text("unit");
    if (!unit.empty()) {
      ImGui::SameLine();
      ImGui::TextUnformatted(unit.c_str());
    }
    char* end = nullptr;
    const double v = std::strtod(text_.data(), &end);
    const bool parsed = end != text_.data() && *end == '\0';
    auto checked = parsed ? questionnaire::encode(question(), v) : Result<questionnaire::StoredValue>(Error{});
    if (text_[0] != '\0' && !checked.ok()) {
      const questionnaire::NumberPair range = item().range("range");
      ImGui::TextDisabled("%s", protocol::text(protocol(), "question.number",
                                               {{"min", number_text(range.min)}, {"max", number_text(range.max)}})
                                    .c_str());
    }
    if (checked.ok()) value_ = v;
    const bool done = next_button(ui(), protocol(), checked.ok());
    ImGui::End();
    return done;
  }
  session::QuestionAnswer answer() const override { return value_; }

 private:
  std::array<char, 64> text_{};
  bool first_ = true;
  double value_ = 0;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_numeric_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new NumericScreen(page));
}

}  // namespace dtlab::run
