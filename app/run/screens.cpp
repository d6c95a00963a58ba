// Shared widgets of the participant window (screens.h).
#include <imgui.h>

#include "app/run/screens.h"
#include "study/protocol/wording.h"
#include "study/scene/models.h"

namespace dtlab::run {

namespace {
constexpr ImGuiWindowFlags kPanel = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                    ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
}

void begin_panel(const char* id, float width_share) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.45f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(io.DisplaySize.x * width_share, 0),
                                      ImVec2(io.DisplaySize.x * width_share, io.DisplaySize.y * 0.95f));
  ImGui::Begin(id, nullptr, kPanel);
}

bool message_panel(Ui& ui, const std::string& title, const std::string& text, const std::string& button) {
  begin_panel("##message");
  ImGui::PushFont(ui.heading_font());
  ImGui::TextUnformatted(title.c_str());
  ImGui::PopFont();
  ImGui::Spacing();
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::Spacing();
  const bool clicked = ui.button(button, ImVec2(ui.text_px() * 8, ui.text_px() * 2));
  ImGui::End();
  return clicked;
}

bool bottom_bar(Ui& ui, const std::string& hint, const std::string& button) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y - ui.text_px() * 0.5f), ImGuiCond_Always,
                          ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##bar", nullptr, kPanel);
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(hint.c_str());
  ImGui::SameLine();
  const bool clicked = ui.button(button);
  ImGui::End();
  return clicked;
}

std::string kind_name(const protocol::Protocol& p, const std::string& kind) {
  const std::string key = "kind." + kind;
  if (protocol::find_text_key(key)) return protocol::text(p, key);
  const scene::ModelInfo* m = scene::find_model(kind);  // a kind the wording table does not list yet
  return m ? std::string(m->label) : kind;
}

void find_this_panel(Ui& ui, const protocol::Protocol& p, const Texture& icon, const std::string& kind) {
  ImGui::SetNextWindowPos(ImVec2(ui.text_px() * 0.5f, ui.text_px() * 0.5f), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::Begin("##find", nullptr, kPanel);
  ImGui::TextUnformatted(protocol::text(p, "trial.find_this").c_str());
  ImGui::Image(icon.id(), ImVec2(static_cast<float>(icon.width()), static_cast<float>(icon.height())));
  ui.name_item("find this");
  ImGui::TextUnformatted(kind_name(p, kind).c_str());
  ImGui::End();
}

void corner_label(Ui& ui, const std::string& text) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - ui.text_px() * 0.5f, ui.text_px() * 0.5f), ImGuiCond_Always,
                          ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::Begin("##corner", nullptr, kPanel);
  ImGui::TextUnformatted(text.c_str());
  ui.name_item("corner label");
  ImGui::End();
}

int choice_buttons(Ui& ui, const std::vector<std::string>& labels) {
  int chosen = -1;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (i) ImGui::SameLine();
    if (ui.button(labels[i], ImVec2(std::max(ui.text_px() * 3, ImGui::CalcTextSize(labels[i].c_str()).x + ui.text_px()),
                                    ui.text_px() * 2.5f)))
      chosen = static_cast<int>(i);
  }
  return chosen;
}

}  // namespace dtlab::run
