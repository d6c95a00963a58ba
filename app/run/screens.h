// The widgets every screen of the participant window shares, in one look:
// a centred message panel with a title, a text and one button; the bar at
// the bottom of a 3D view with its hint and button; the "find this" panel in
// the upper left corner; a row of big choice buttons. Each registers its
// buttons as named items (scripts click them by their labels). Call inside
// an ImGui frame of Ui::frame(). Never: touches the store or GL.
#pragma once
#include <string>
#include <vector>

#include "app/run/ui.h"
#include "app/run/view.h"
#include "study/protocol/protocol.h"

namespace dtlab::run {

// A centred panel: `title` (heading font), `text` (wrapped), one button; true when it was clicked.
bool message_panel(Ui& ui, const std::string& title, const std::string& text, const std::string& button);
// The bar at the bottom of a 3D view: a hint and a button; true when the button was clicked.
bool bottom_bar(Ui& ui, const std::string& hint, const std::string& button);
// "Find this": the object kind's icon and name (in the protocol's wording), upper left.
void find_this_panel(Ui& ui, const protocol::Protocol& p, const Texture& icon, const std::string& kind);
// The name of a WALKTHROUGH object kind as participants read it (the protocol's kind.<kind> wording).
std::string kind_name(const protocol::Protocol& p, const std::string& kind);
// A small label in the upper right corner ("Practice", "Trial 3 of 24").
void corner_label(Ui& ui, const std::string& text);
// Big buttons in a row; the index clicked this frame, or -1.
int choice_buttons(Ui& ui, const std::vector<std::string>& labels);
// Begins a centred panel window of `width_share` of the window (end with ImGui::End()).
void begin_panel(const char* id, float width_share = 0.7f);

}  // namespace dtlab::run
