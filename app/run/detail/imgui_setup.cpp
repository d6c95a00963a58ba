// One Dear ImGui context per window (detail/imgui_setup.h).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <stb/stb_truetype.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <vector>

#include "app/run/detail/imgui_setup.h"
#include "study/common/text.h"

namespace dtlab::run::detail {

namespace {

void map_keys(ImGuiIO& io) {
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
  io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
  io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
  io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
}

// ImGui asserts (aborts the program) when a font file is not one: read it first as ImGui's
// stb_truetype will (Debian's libstb), with the table directory inside the file.
Status check_font_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<unsigned char> data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  auto bad = [&](const std::string& why) {
    return Error{file, 0, 0, "font", "not a TrueType or OpenType font (" + why + "); give a .ttf or .otf file, e.g. " +
                                         std::string(kDefaultFont), ErrorKind::invalid_input};
  };
  if (!in.eof() && in.fail()) return bad("it could not be read");
  if (data.size() < 12) return bad("shorter than a font's header");
  const int offset = stbtt_GetFontOffsetForIndex(data.data(), 0);
  if (offset < 0 || static_cast<std::size_t>(offset) + 12 > data.size()) return bad("no font signature");
  const std::size_t tables = (std::size_t{data[offset + 4]} << 8) | data[offset + 5];
  if (static_cast<std::size_t>(offset) + 12 + 16 * tables > data.size()) return bad("its table directory is cut off");
  auto u32 = [&](std::size_t at) {
    return (std::size_t{data[at]} << 24) | (std::size_t{data[at + 1]} << 16) | (std::size_t{data[at + 2]} << 8) |
           data[at + 3];
  };
  for (std::size_t t = 0; t < tables; ++t) {  // stb_truetype reads the tables unchecked
    const std::size_t entry = static_cast<std::size_t>(offset) + 12 + 16 * t;
    if (u32(entry + 8) > data.size() || u32(entry + 12) > data.size() - u32(entry + 8))
      return bad("a table lies past the end of the file: is it cut off?");
  }
  stbtt_fontinfo info;
  if (!stbtt_InitFont(&info, data.data(), offset)) return bad("its glyph tables are missing");
  return {};
}

// The three sizes from `file`, with the scripts participants are written in: Latin (with
// Extended-A and -B: Polish, Czech, Turkish, ...), Greek, Cyrillic, typographic punctuation, and
// every character of the wording (so a script outside these ranges still shows where the font has
// it). Then what the font lacks, which would read as '?'.
Status add_font_file(ImGuiSetup& s, float text_px, const std::string& file, const std::string& glyph_text,
                     ImVector<ImWchar>& glyph_ranges) {
  static const ImWchar kScripts[] = {0x0020, 0x024F, 0x0370, 0x03FF, 0x0400, 0x052F, 0x1E00, 0x1EFF,
                                     0x2000, 0x206F, 0x20A0, 0x20BF, 0x2100, 0x214F, 0};
  if (Status st = check_font_file(file); !st) return st;
  ImGuiIO& io = ImGui::GetIO();
  ImFontConfig cfg;
  cfg.OversampleH = 2;
  ImFontGlyphRangesBuilder builder;
  builder.AddRanges(kScripts);
  builder.AddText(glyph_text.c_str());
  glyph_ranges.clear();
  builder.BuildRanges(&glyph_ranges);
  const ImWchar* ranges = glyph_ranges.Data;
  ImFont* text = io.Fonts->AddFontFromFileTTF(file.c_str(), text_px, &cfg, ranges);
  s.heading = io.Fonts->AddFontFromFileTTF(file.c_str(), text_px * 1.5f, &cfg, ranges);
  s.small = io.Fonts->AddFontFromFileTTF(file.c_str(), std::max(14.0f, text_px * 0.7f), &cfg, ranges);
  if (!text || !s.heading || !s.small)
    return Error{file, 0, 0, "font", "the font could not be loaded (not a TrueType or OpenType file?)",
                 ErrorKind::invalid_input};
  io.Fonts->Build();
  std::set<char32_t> reported;
  for (const char32_t c : utf8_codepoints(glyph_text)) {
    if (c < 0x20 || reported.count(c)) continue;
    if (c <= 0xFFFF && text->FindGlyphNoFallback(static_cast<ImWchar>(c))) continue;  // ImWchar: 16 bits here
    reported.insert(c);
    char entry[32];
    std::snprintf(entry, sizeof entry, "U+%04X", static_cast<unsigned>(c));
    s.missing_glyphs.push_back(entry);
  }
  return {};
}

// ImGui's own font, scaled (pixel-like but legible; Latin-1 only).
void add_default_font(ImGuiSetup& s, float text_px) {
  ImGuiIO& io = ImGui::GetIO();
  ImFontConfig cfg;
  cfg.OversampleH = 2;
  cfg.SizePixels = text_px;
  io.Fonts->AddFontDefault(&cfg);
  cfg.SizePixels = text_px * 1.5f;
  s.heading = io.Fonts->AddFontDefault(&cfg);
  cfg.SizePixels = std::max(14.0f, text_px * 0.7f);
  s.small = io.Fonts->AddFontDefault(&cfg);
}

}  // namespace

Result<ImGuiSetup> create_imgui(float text_px, const FontSpec& font, ImVector<ImWchar>& glyph_ranges) {
  if (!font.file.empty() && !std::filesystem::is_regular_file(font.file))
    return Error{font.file, 0, 0, "font", "no such font file (a TrueType or OpenType file, e.g. " +
                                              std::string(kDefaultFont) + ")", ErrorKind::not_found};
  IMGUI_CHECKVERSION();
  ImGuiSetup s;
  s.context = ImGui::CreateContext();
  ImGui::SetCurrentContext(s.context);
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini beside the study
  io.LogFilename = nullptr;
  // No keyboard navigation: it would highlight (pre-select) the first button of every page; every
  // screen has its own keys (digits for ratings, letters for T2, Enter, Escape, Space).
  io.ConfigFlags &= ~ImGuiConfigFlags_NavEnableKeyboard;
  io.BackendPlatformName = "dtlab-run";
  map_keys(io);
  const std::string file = font.file.empty() ? kDefaultFont : font.file;
  if (std::filesystem::exists(file)) {
    if (Status st = add_font_file(s, text_px, file, font.glyph_text, glyph_ranges); !st) {
      ImGui::DestroyContext(s.context);
      return st.error();
    }
  } else {
    add_default_font(s, text_px);
  }
  ImGui::StyleColorsLight();
  ImGuiStyle& style = ImGui::GetStyle();
  style.ScaleAllSizes(text_px / 16.0f);
  style.FrameRounding = 4;
  style.WindowRounding = 6;
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext(s.context);
    return Error{"", 0, 0, "window", "Dear ImGui's OpenGL 3 backend did not start", ErrorKind::environment};
  }
  return s;
}

void destroy_imgui(ImGuiContext* context) {
  ImGuiContext* caller = ImGui::GetCurrentContext();
  ImGui::SetCurrentContext(context);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext(context);  // leaves no current context when it was the current one
  if (caller != context) ImGui::SetCurrentContext(caller);
}

}  // namespace dtlab::run::detail
