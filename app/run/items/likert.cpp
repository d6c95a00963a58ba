// The "likert" screen: a row of buttons, one per point; a point labelled on
// its own shows (and is named by) its label, otherwise its value, with the
// end labels written beside the row; number keys 1..9 choose by position.
#include <imgui.h>

#include "app/run/item_screen.h"
#include "app/run/screens.h"

namespace dtlab::run {
namespace {

class LikertScreen final : public ItemScreen {
 public:
  explicit LikertScreen(const ItemPage& page) : ItemScreen(page) {
    const auto& labels = item().strings("labels");
    first_ = static_cast<int>(item().integer("first"));
    const int points = static_cast<int>(item().integer("points"));
    each_ = static_cast<int>(labels.size()) == points;
    for (int k = 0; k < points; ++k) shown_.push_back(each_ ? labels[static_cast<std::size_t>(k)] : std::to_string(first_ + k));
    if (!each_ && labels.size() == 2) ends_ = {labels[0], labels[1]};
  }
  bool frame() override {
    begin_item_panel(page_, "##likert");
    if (!each_) {
      ImGui::AlignTextToFramePadding();
      ImGui::TextUnformatted(ends_.first.c_str());
      ImGui::SameLine();
    }
    int chosen = choice_buttons(ui(), shown_);
    if (!each_) {
      ImGui::SameLine();
      ImGui::TextUnformatted(ends_.second.c_str());
    }
    for (std::size_t k = 0; k < shown_.size() && k < 9; ++k)
      if (digit_pressed(ui(), static_cast<int>(k) + 1)) chosen = static_cast<int>(k);
    if (chosen >= 0) chosen_ = chosen;
    ImGui::End();
    return chosen_.has_value();
  }
  session::QuestionAnswer answer() const override { return static_cast<double>(first_ + *chosen_); }

 private:
  int first_ = 1;
  bool each_ = false;
  std::vector<std::string> shown_;
  std::pair<std::string, std::string> ends_;
  std::optional<int> chosen_;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_likert_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new LikertScreen(page));
}

}  // namespace dtlab::run
