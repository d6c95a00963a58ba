// The window's half of the questionnaire item-type seam: one screen per item
// type, make_<identifier>_screen() in app/run/items/<identifier>.cpp, listed
// by study/questionnaire/item_types.def (the library's registration of the
// same type has the same identifier). A screen is one page for one question:
// the runner of the pages (questionnaire.cpp) calls frame() once per window
// frame until it returns true, then takes answer(). Every screen works from
// the keyboard, and names its controls (Ui::name_item) so a script's
// click_item can choose an option by its text, focus a field to type into,
// and press Next. Never: touches the store or GL state (the depth test's
// view draws through SceneView).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "app/run/ui.h"
#include "study/session/session.h"

namespace dtlab::run {

// What a screen is made for.
struct ItemPage {
  Ui* ui = nullptr;
  const session::Question* question = nullptr;
  const session::QuestionnaireSpec* spec = nullptr;
  std::string progress;  // "Question 3 of 12"
};

class ItemScreen {
 public:
  virtual ~ItemScreen() = default;
  // The screen's name: the script section that plays on it. Default "questionnaire <item id>".
  virtual std::string name() const;
  // The 3D view behind the widgets (the depth test's scene); default none.
  virtual bool has_view() const { return false; }
  virtual Status draw3d() { return {}; }
  // One frame of ImGui widgets; true once the participant has answered.
  virtual bool frame() = 0;
  // The answer given (valid after frame() returned true).
  virtual session::QuestionAnswer answer() const = 0;

 protected:
  explicit ItemScreen(ItemPage page) : page_(std::move(page)) {}
  Ui& ui() const { return *page_.ui; }
  const session::Question& question() const { return *page_.question; }
  const questionnaire::Item& item() const { return *page_.question->item; }
  const protocol::Protocol& protocol() const { return *page_.spec->protocol; }
  ItemPage page_;
};

using ItemScreenMaker = Result<std::unique_ptr<ItemScreen>> (*)(const ItemPage& page);

// The screen of the page's question, by its item type; an Error for a type without a screen.
Result<std::unique_ptr<ItemScreen>> make_item_screen(const ItemPage& page);

// --- what the screens share (items/page.cpp) --------------------------------------------------

// Opens the page's panel (end with ImGui::End()): the progress line, the prompt (heading font,
// wrapped, line breaks kept), and the condition it is about (a rating per factors' levels).
void begin_item_panel(const ItemPage& page, const char* id);
// The Next button (the protocol's `question.next`, "Next" in English), greyed out and inert unless `enabled`; true when clicked, or on
// Enter (Ctrl+Enter when a text box has the keyboard) while enabled.
bool next_button(Ui& ui, const protocol::Protocol& p, bool enabled, bool text_box = false);
// A number as a prompt shows it: "%g" (2, 0.5, 1e+06).
std::string number_text(double v);
// Whether a text field has the keyboard (digit and letter keys are then typing, not choosing).
bool typing();
// The key of digit d (0..9) went down this frame, and no text field has the keyboard.
bool digit_pressed(Ui& ui, int d);

}  // namespace dtlab::run
