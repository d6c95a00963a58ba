// The "multiple-choice" screen: one check box per option, showing (and named
// by) its label or the option itself; number keys 1..9 toggle by position;
// Next once the item's own check takes the selection (how many may be chosen).
#include <imgui.h>

#include <algorithm>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"

namespace dtlab::run {
namespace {

class MultipleChoiceScreen final : public ItemScreen {
 public:
  explicit MultipleChoiceScreen(const ItemPage& page) : ItemScreen(page) {
    const auto& labels = item().strings("labels");
    const auto& options = question().options;
    for (std::size_t i = 0; i < options.size(); ++i) shown_.push_back(i < labels.size() ? labels[i] : options[i]);
    checked_.assign(options.size(), false);
  }
  bool frame() override {
    begin_item_panel(page_, "##multiple");
    for (std::size_t i = 0; i < shown_.size(); ++i) {
      bool on = checked_[i];
      if (ImGui::Checkbox(shown_[i].c_str(), &on)) checked_[i] = on;
      ui().name_item(shown_[i]);
      if (i < 9 && digit_pressed(ui(), static_cast<int>(i) + 1)) checked_[i] = !checked_[i];
    }
    const questionnaire::NumberPair select = item().range("select");
    const auto n = static_cast<double>(shown_.size());
    if (select.min > 0 || select.max < n)
      ImGui::TextDisabled("%s", protocol::text(protocol(), "question.choose",
                                               {{"min", number_text(select.min)}, {"max", number_text(std::min(select.max, n))}})
                                    .c_str());
    const bool ok = questionnaire::encode(question(), answer()).ok();
    const bool done = next_button(ui(), protocol(), ok);
    ImGui::End();
    return done;
  }
  session::QuestionAnswer answer() const override {
    std::vector<std::string> chosen;
    for (std::size_t i = 0; i < checked_.size(); ++i)
      if (checked_[i]) chosen.push_back(question().options[i]);
    return chosen;
  }

 private:
  std::vector<std::string> shown_;
  std::vector<bool> checked_;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_multiple_choice_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new MultipleChoiceScreen(page));
}

}  // namespace dtlab::run
