// The "choice" screen: one button per option, the neutral one last, each
// showing (and named by) its label, or the option itself where it has none;
// number keys 1..9 choose by position.
#include <imgui.h>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"
#include "app/run/screens.h"

namespace dtlab::run {
namespace {

class ChoiceScreen final : public ItemScreen {
 public:
  explicit ChoiceScreen(const ItemPage& page) : ItemScreen(page) {
    const auto& labels = item().strings("labels");
    const auto& options = question().options;
    const auto f = item().keys.find("factor");  // a factor's levels read as their labels
    const std::string* factor = f == item().keys.end() ? nullptr : std::get_if<std::string>(&f->second);
    for (std::size_t i = 0; i < options.size(); ++i)
      shown_.push_back(i < labels.size()              ? labels[i]
                       : !factor || factor->empty() ? options[i]
                                                     : protocol::level_text(protocol(), *factor, options[i]));
  }
  bool frame() override {
    begin_item_panel(page_, "##choice");
    int chosen = choice_buttons(ui(), shown_);
    for (std::size_t k = 0; k < shown_.size() && k < 9; ++k)
      if (digit_pressed(ui(), static_cast<int>(k) + 1)) chosen = static_cast<int>(k);
    if (chosen >= 0) chosen_ = chosen;
    ImGui::End();
    return chosen_.has_value();
  }
  session::QuestionAnswer answer() const override { return question().options[static_cast<std::size_t>(*chosen_)]; }

 private:
  std::vector<std::string> shown_;
  std::optional<int> chosen_;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_choice_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new ChoiceScreen(page));
}

}  // namespace dtlab::run
