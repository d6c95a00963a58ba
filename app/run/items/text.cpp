// The "text" screen: a box of `lines` lines that has the keyboard from the
// start (any script the font covers; Enter starts a new line), a count of
// the characters left, and Next (or Ctrl+Enter) once the item's own check
// takes the text (length, required).
#include <imgui.h>

#include <string>
#include <vector>

#include "app/run/item_screen.h"
#include "study/protocol/wording.h"

namespace dtlab::run {
namespace {

// Code points of UTF-8 text (continuation bytes not counted).
std::size_t characters(const char* s) {
  std::size_t n = 0;
  for (; *s; ++s) n += (static_cast<unsigned char>(*s) & 0xC0) != 0x80;
  return n;
}

class TextScreen final : public ItemScreen {
 public:
  explicit TextScreen(const ItemPage& page) : ItemScreen(page) {
    max_ = static_cast<std::size_t>(item().integer("max_length"));
    buffer_.assign(max_ * 4 + 1, '\0');  // at most 4 bytes a character
  }
  bool frame() override {
    begin_item_panel(page_, "##text");
    if (first_) ImGui::SetKeyboardFocusHere();
    first_ = false;
    const float lines = static_cast<float>(item().integer("lines"));
    ImGui::InputTextMultiline("##answer", buffer_.data(), buffer_.size(),
                              ImVec2(ImGui::GetContentRegionAvail().x, ImGui::GetTextLineHeight() * (lines + 0.6f)));
    ui().name_item("Answer");
    const std::size_t used = characters(buffer_.data());
    ImGui::TextDisabled(
        "%s", protocol::text(protocol(), "question.characters", {{"used", std::to_string(used)}, {"max", std::to_string(max_)}})
                  .c_str());
    const bool ok = questionnaire::encode(question(), std::string(buffer_.data())).ok();
    const bool done = next_button(ui(), protocol(), ok, /*text_box=*/true);
    ImGui::End();
    return done;
  }
  session::QuestionAnswer answer() const override { return std::string(buffer_.data()); }

 private:
  std::size_t max_ = 0;
  std::vector<char> buffer_;
  bool first_ = true;
};

}  // namespace

Result<std::unique_ptr<ItemScreen>> make_text_screen(const ItemPage& page) {
  return std::unique_ptr<ItemScreen>(new TextScreen(page));
}

}  // namespace dtlab::run
