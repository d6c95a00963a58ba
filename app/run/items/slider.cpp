// The "slider" screen: a visual analogue scale across the panel with its
// end labels under its ends, and a "Value" field (empty until a value is
// set) to type the number into; a typed value snaps to the slider's steps.
// The handle starts in the middle with no value shown, and Next stays off
// until the participant moves it (drag, Left/Right arrows by one step, or
// typing), so nobody answers the middle by default.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"

namespace dtlab::run {
namespace {

class SliderScreen final : public ItemScreen {
 public:
  explicit SliderScreen(const ItemPage& page) : ItemScreen(page) {
    range_ = item().range("range");
    step_ = item().number("step");
    value_ = snap(0.5 * (range_.min + range_.max));
  }
  bool frame() override {
    begin_item_panel(page_, "##slider");
    const float width = ImGui::GetContentRegionAvail().x;
    ImGui::SetNextItemWidth(width);
    double v = value_;
    if (ImGui::SliderScalar("##scale", ImGuiDataType_Double, &v, &range_.min, &range_.max, touched_ ? "%g" : " ",
                            ImGuiSliderFlags_AlwaysClamp))
      set(v);
    ui().name_item("slider");
    const auto& anchors = item().strings("anchors");
    if (anchors.size() == 2) {
      ImGui::TextUnformatted(anchors[0].c_str());
      ImGui::SameLine(std::max(0.0f, width - ImGui::CalcTextSize(anchors[1].c_str()).x));
      ImGui::TextUnformatted(anchors[1].c_str());
    }
    Input& in = ui().input();
    if (!typing() && in.key_pressed(GLFW_KEY_LEFT)) set(value_ - step_);
    if (!typing() && in.key_pressed(GLFW_KEY_RIGHT)) set(value_ + step_);
    ImGui::Spacing();
    ImGui::AlignTextToFramePadding();
    ImGui::TextUnformatted(protocol::text(protocol(), "question.value").c_str());
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ui().text_px() * 6);
    if (!editing_ && touched_) std::snprintf(text_.data(), text_.size(), "%g", value_);
    if (ImGui::InputText("##value", text_.data(), text_.size(), ImGuiInputTextFlags_CharsScientific)) {
      char* end = nullptr;
      const double v = std::strtod(text_.data(), &end);
      if (end != text_.data() && *end == '\0') set(v, /*from_field=*/true);
    }
    editing_ = ImGui::IsItemActive();
    ui().name_item("Value");
    const bool done = next_button(ui(), protocol(), touched_);
    ImGui::End();
    return done;
  }
  session::QuestionAnswer answer() const override { return value_; }

 private:
  double snap(double v) const {
    const double k = std::round((v - range_.min) / step_);
    return std::clamp(range_.min + k * step_, range_.min, range_.max);
  }
  void set(double v, bool from_field = false) {
    value_ = snap(v);
    if (!from_field) editing_ = false;  // the field shows the value again
    touched_ = true;
  }
  questionnaire::NumberPair range_;
  double step_ = 1, value_ = 0;
  std::array<char, 32> text_{};  // the Value field: empty until the participant sets a value
  bool touched_ = false, editing_ = false;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_slider_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new SliderScreen(page));
}

}  // namespace dtlab::run
