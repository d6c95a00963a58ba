// The "rating" screen: one button per integer from the scale's min to max
// (named by the number), digit keys for the values 0..9 on the scale.
#include <imgui.h>

#include "app/run/item_screen.h"
#include "app/run/screens.h"

namespace dtlab::run {
namespace {

class RatingScreen final : public ItemScreen {
 public:
  explicit RatingScreen(const ItemPage& page) : ItemScreen(page) {
    const questionnaire::NumberPair s = item().range("scale");
    lo_ = static_cast<int>(s.min);
    hi_ = static_cast<int>(s.max);
    for (int v = lo_; v <= hi_; ++v) labels_.push_back(std::to_string(v));
  }
  bool frame() override {
    begin_item_panel(page_, "##rating");
    int chosen = choice_buttons(ui(), labels_);
    for (int v = lo_; v <= hi_; ++v)
      if (v >= 0 && v <= 9 && digit_pressed(ui(), v)) chosen = v - lo_;
    if (chosen >= 0) value_ = lo_ + chosen;
    ImGui::End();
    return value_.has_value();
  }
  session::QuestionAnswer answer() const override { return static_cast<double>(*value_); }

 private:
  int lo_ = 0, hi_ = 0;
  std::vector<std::string> labels_;
  std::optional<int> value_;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_rating_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new RatingScreen(page));
}

}  // namespace dtlab::run
