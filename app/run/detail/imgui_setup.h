// Internal to dtlab_run: a Dear ImGui context as every window of `dtlab run`
// has one (the participant's, and the experimenter console's own window):
// fonts sized for the window from one font file with the glyphs of Latin,
// Greek, Cyrillic and every character of the protocol's wording, the light
// style, keyboard navigation off, no .ini or log files, and an instance of the
// OpenGL3 backend made in the GL context current at creation. Debian's imgui
// 1.86 keeps a backend's state in its context's IO (BackendRendererUserData),
// so each window's context has its own backend, shaders and font texture in
// its own GL context; nothing GL is shared between windows. Never: feeds
// input (run::Input does); leaves a half-made context behind on an error.
#pragma once
#include <string>
#include <vector>

#include <imgui.h>

#include "study/common/error.h"

namespace dtlab::run::detail {

// The window's text: a TrueType/OpenType file ("" = DejaVu Sans, kDefaultFont) and the text whose
// every character the atlas must hold (the protocol's participant-facing wording).
struct FontSpec {
  std::string file;
  std::string glyph_text;
};

inline constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct ImGuiSetup {
  ImGuiContext* context = nullptr;
  ImFont* heading = nullptr;  // 1.5 x text
  ImFont* small = nullptr;    // 0.7 x text, at least 14 px: the experimenter's screens (read at a desk)
  // Characters of FontSpec::glyph_text the font has no glyph for (ImGui would draw '?'), as
  // "U+XXXX" entries; empty when the font covers the wording (or ImGui's own font stands in).
  std::vector<std::string> missing_glyphs;
};

// Creates a context sized for text of `text_px` pixels and makes it current; the window's GL
// context must be current (the backend's objects are made in it). `glyph_ranges` receives the
// atlas's ranges and must outlive the context. Errors (the context is destroyed again): a given
// font file that does not exist (not_found) or does not load (invalid_input); the backend did not
// start (environment). Without a given file and without DejaVu Sans, ImGui's own font.
Result<ImGuiSetup> create_imgui(float text_px, const FontSpec& font, ImVector<ImWchar>& glyph_ranges);
// Shuts its backend down and destroys `context`; the GL context it was created in must be current.
// The current ImGui context is the caller's again afterwards (null if it was `context`).
void destroy_imgui(ImGuiContext* context);

}  // namespace dtlab::run::detail
