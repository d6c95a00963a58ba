// Script parsing and playing (script.h). Lines are `OP ARG...`; arguments
// are numbers, key names, or double-quoted text ("" inside quotes is a
// quote); `#` starts a comment outside quotes; `[screen]` starts a section.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <charconv>
#include <optional>
#include <string>
#include <fstream>
#include <sstream>

#include "app/run/script.h"
#include "study/common/text.h"

namespace dtlab::run {

namespace {

// Splits a line into words; quoted words keep spaces. Error text on a missing close quote.
bool split(const std::string& line, std::vector<std::string>& words, std::string& error) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    const char c = line[i];
    if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
      continue;
    }
    if (c == '#') break;
    std::string w;
    if (c == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            w += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        w += line[i++];
      }
      if (!closed) {
        error = "a quoted text is not closed";
        return false;
      }
    } else {
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != '#') w += line[i++];
    }
    words.push_back(std::move(w));
  }
  return true;
}

bool number(const std::string& s, double& out) {
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size() && std::isfinite(out);
}

struct OpSpec {
  const char* name;
  ScriptStep::Op op;
  int min_args, max_args;
  const char* usage;
};
constexpr OpSpec kOps[] = {
    {"wait", ScriptStep::Op::wait, 1, 1, "wait SECONDS"},
    {"key", ScriptStep::Op::key, 1, 1, "key NAME"},
    {"key_down", ScriptStep::Op::key_down, 1, 1, "key_down NAME"},
    {"key_up", ScriptStep::Op::key_up, 1, 1, "key_up NAME"},
    {"hold", ScriptStep::Op::hold, 2, 2, "hold NAME SECONDS"},
    {"type", ScriptStep::Op::type, 1, 1, "type \"TEXT\""},
    {"move", ScriptStep::Op::move, 2, 2, "move X Y"},
    {"click", ScriptStep::Op::click, 2, 3, "click X Y [left|right|middle]"},
    {"drag", ScriptStep::Op::drag, 5, 5, "drag X0 Y0 X1 Y1 SECONDS"},
    {"turn", ScriptStep::Op::turn, 2, 2, "turn DX SECONDS"},
    {"scroll", ScriptStep::Op::scroll, 2, 2, "scroll DX DY"},
    {"click_item", ScriptStep::Op::click_item, 1, 3, "click_item \"NAME\" [FX FY]"},
    {"window", ScriptStep::Op::window, 1, 1, "window console|participant"},
};

Error at(const std::string& file, int line, std::string field, std::string message) {
  return Error{file, line, 0, std::move(field), std::move(message)};
}

Result<ScriptStep> parse_step(const std::vector<std::string>& w, const std::string& file, int line) {
  const OpSpec* spec = nullptr;
  for (const OpSpec& o : kOps)
    if (w[0] == o.name) spec = &o;
  if (!spec) {
    std::string known;
    for (const OpSpec& o : kOps) known += std::string(known.empty() ? "" : ", ") + o.name;
    return at(file, line, w[0], "unknown step; expected one of " + known);
  }
  const int n = static_cast<int>(w.size()) - 1;
  if (n < spec->min_args || n > spec->max_args) return at(file, line, w[0], std::string("expected: ") + spec->usage);
  ScriptStep s;
  s.op = spec->op;
  s.line = line;
  auto num = [&](std::size_t i, double& out) -> Status {
    if (!number(w[i], out)) return at(file, line, w[0], "\"" + w[i] + "\" is not a number; expected: " + spec->usage);
    return {};
  };
  auto key = [&](std::size_t i) -> Status {
    s.key = Input::key_code(w[i]);
    if (s.key < 0) return at(file, line, w[0], "unknown key \"" + w[i] + "\" (names: A-Z, 0-9, F1-F12, Enter, Space, "
                                                                      "Escape, Tab, Backspace, Up, Down, Left, Right, ...)");
    return {};
  };
  Status st;
  switch (s.op) {
    case ScriptStep::Op::wait: st = num(1, s.seconds); break;
    case ScriptStep::Op::key:
    case ScriptStep::Op::key_down:
    case ScriptStep::Op::key_up: st = key(1); break;
    case ScriptStep::Op::hold:
      st = key(1);
      if (st) st = num(2, s.seconds);
      break;
    case ScriptStep::Op::type:
      s.text = w[1];
      if (!utf8_decode(s.text)) st = at(file, line, w[0], "the text is not UTF-8");
      break;
    case ScriptStep::Op::move:
      st = num(1, s.x0);
      if (st) st = num(2, s.y0);
      break;
    case ScriptStep::Op::click:
      st = num(1, s.x0);
      if (st) st = num(2, s.y0);
      if (st && n == 3) {
        s.button = w[3] == "left" ? 0 : w[3] == "right" ? 1 : w[3] == "middle" ? 2 : -1;
        if (s.button < 0) st = at(file, line, w[0], "button \"" + w[3] + "\": expected left, right or middle");
      }
      break;
    case ScriptStep::Op::drag:
      for (std::size_t i = 1; i <= 5 && st; ++i) st = num(i, i == 1 ? s.x0 : i == 2 ? s.y0 : i == 3 ? s.x1 : i == 4 ? s.y1 : s.seconds);
      break;
    case ScriptStep::Op::turn:
      st = num(1, s.x0);
      if (st) st = num(2, s.seconds);
      break;
    case ScriptStep::Op::scroll:
      st = num(1, s.x0);
      if (st) st = num(2, s.y0);
      break;
    case ScriptStep::Op::click_item:
      s.text = w[1];
      s.x0 = s.y0 = 0.5;
      if (n == 3) {
        st = num(2, s.x0);
        if (st) st = num(3, s.y0);
      } else if (n == 2) {
        st = at(file, line, w[0], std::string("give both fractions or none; expected: ") + spec->usage);
      }
      break;
    case ScriptStep::Op::window:
      s.text = w[1];
      if (s.text != "console" && s.text != "participant")
        st = at(file, line, w[0], "\"" + s.text + "\": expected console or participant");
      break;
  }
  if (!st) return st.error();
  if (s.seconds < 0 || s.seconds > 3600) return at(file, line, w[0], "seconds must be within 0..3600");
  return s;
}

}  // namespace

const ScriptSection* Script::for_screen(const std::string& screen) const {
  for (const ScriptSection& s : sections)
    if (s.screen == screen) return &s;
  // "questionnaire tlx.mental" -> "questionnaire tlx": an instrument's items share its section.
  for (std::string prefix = screen; prefix.rfind('.') != std::string::npos && prefix.rfind('.') > prefix.find(' ');) {
    prefix.resize(prefix.rfind('.'));
    for (const ScriptSection& s : sections)
      if (s.screen == prefix) return &s;
  }
  const std::string first = screen.substr(0, screen.find(' '));
  for (const ScriptSection& s : sections)
    if (s.screen == first) return &s;
  return nullptr;
}

Result<Script> parse_script_text(const std::string& text, const std::string& file) {
  Script script;
  script.file = file;
  std::istringstream in(text);
  std::string line_text, error;
  std::vector<std::string> words;
  int line = 0;
  while (std::getline(in, line_text)) {
    ++line;
    if (line_text.find('\0') != std::string::npos) return at(file, line, "", "a NUL byte; a script is text");
    if (!split(line_text, words, error)) return at(file, line, "", error);
    if (words.empty()) continue;
    if (words[0].front() == '[') {
      std::string header;
      for (const auto& w : words) header += (header.empty() ? "" : " ") + w;
      if (header.size() < 3 || header.back() != ']')
        return at(file, line, "section", "expected [SCREEN] or [SCREEN DETAIL], e.g. [trial T1]");
      std::string name = header.substr(1, header.size() - 2);
      for (const ScriptSection& s : script.sections)
        if (s.screen == name)
          return at(file, line, "section", "[" + name + "] is already defined at line " + std::to_string(s.line));
      script.sections.push_back(ScriptSection{std::move(name), line, {}});
      continue;
    }
    if (script.sections.empty())
      return at(file, line, words[0], "a step before any [screen] section; start with e.g. [start]");
    auto step = parse_step(words, file, line);
    if (!step) return step.error();
    script.sections.back().steps.push_back(std::move(step.value()));
  }
  if (script.sections.empty()) return at(file, 0, "", "the script has no [screen] section");
  return script;
}

Result<Script> parse_script(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{path, 0, 0, "", "cannot read the script file", ErrorKind::not_found};
  std::ostringstream text;
  text << in.rdbuf();
  if (text.str().size() > (1 << 20)) return Error{path, 0, 0, "", "larger than 1 MiB; a script is a short text file"};
  return parse_script_text(text.str(), path);
}

ScriptPlayer::ScriptPlayer(const Script& script, Input& input, Input* console)
    : script_(script), participant_(input), console_(console), input_(&input) {}

void ScriptPlayer::key(int k, bool down) {
  input_->on_key(k, down ? GLFW_PRESS : GLFW_RELEASE, 0);
  std::erase(held_keys_, std::pair(input_, k));
  if (down) held_keys_.emplace_back(input_, k);
}

void ScriptPlayer::button(int b, bool down) {
  input_->on_mouse_button(b, down ? GLFW_PRESS : GLFW_RELEASE, 0);
  std::erase(held_buttons_, std::pair(input_, b));
  if (down) held_buttons_.emplace_back(input_, b);
}

void ScriptPlayer::leave() {
  for (const auto& [in, k] : std::vector(held_keys_)) {
    input_ = in;
    key(k, false);
  }
  for (const auto& [in, b] : std::vector(held_buttons_)) {
    input_ = in;
    button(b, false);
  }
  input_ = &participant_;
  section_ = nullptr;
  instance_ = ~0ULL;
}

void ScriptPlayer::begin_step(Clock::time_point now) {
  phase_ = 0;
  step_start_ = now;
  moved_ = 0;
  seen_.reset();
}

Status ScriptPlayer::tick(const std::string& screen, std::uint64_t instance, const ItemBoxes& items,
                          const ItemBoxes& console_items, Clock::time_point now) {
  if (instance != instance_) {
    instance_ = instance;
    input_ = &participant_;  // every section starts in the participant's window
    section_ = script_.for_screen(screen);
    next_ = 0;
    begin_step(now);
    idle_since_ = now;
  }
  Status error;
  while (section_ && next_ < section_->steps.size()) {
    const bool in_console = console_ && input_ == console_;
    if (in_console && !console_fresh_) return {};  // the console window has not seen the last phase yet
    const bool done = step(section_->steps[next_], in_console ? console_items : items, now, error);
    if (in_console) console_fresh_ = false;
    if (!done) return error;  // waiting (or failed)
    ++next_;
    begin_step(now);
    idle_since_ = now;
  }
  // Only the script acts in a scripted run: a screen it has nothing more for would wait forever.
  if (std::chrono::duration<double>(now - idle_since_).count() <= kIdleTimeoutS) return {};
  const std::string wait = " and the screen was still up " + std::to_string(int(kIdleTimeoutS)) + " s later";
  if (!section_)
    return Error{script_.file, 0, 0, "script", "the script has no section for the screen \"" + screen + "\"" + wait};
  const ScriptStep& last = section_->steps.back();
  return Error{script_.file, last.line, 0, "script",
               "section [" + section_->screen + "] played out at this step" + wait +
                   " (a click that missed, or a key the screen does not take)"};
}

// One step; true when it is done. A step that presses and releases spends one frame pressed and
// one frame released before the next step: a frame that held a release and the next press would
// read to the UI as one long press (no click), as with a real mouse and a real frame.
bool ScriptPlayer::step(const ScriptStep& s, const ItemBoxes& items, Clock::time_point now, Status& error) {
  using Op = ScriptStep::Op;
  const double elapsed = std::chrono::duration<double>(now - step_start_).count();
  auto press_release = [&](int button, double x, double y) {
    if (phase_ == 0) {
      input_->on_cursor(x, y);
      this->button(button, true);
      phase_ = 1;
      return false;
    }
    if (phase_ == 1) {
      this->button(button, false);
      phase_ = 2;
      return false;
    }
    return true;
  };
  switch (s.op) {
    case Op::wait: return elapsed >= s.seconds;
    case Op::window: input_ = s.text == "console" && console_ ? console_ : &participant_; return true;
    case Op::key:
      if (phase_ == 0) {
        key(s.key, true);
        phase_ = 1;
        return false;
      }
      if (phase_ == 1) {
        key(s.key, false);
        phase_ = 2;
        return false;
      }
      return true;
    case Op::key_down: key(s.key, true); return true;
    case Op::key_up: key(s.key, false); return true;
    case Op::hold:
      if (phase_ == 0) {
        key(s.key, true);
        phase_ = 1;
      }
      if (phase_ == 2) return true;
      if (elapsed < s.seconds) return false;
      key(s.key, false);
      phase_ = 2;
      return false;
    case Op::type:  // code points, as a keyboard's text input delivers them (UTF-8 decoded)
      for (const char32_t c : utf8_codepoints(s.text)) input_->on_char(static_cast<unsigned>(c));
      return true;
    case Op::move: input_->on_cursor(s.x0, s.y0); return true;
    case Op::click: return press_release(s.button, s.x0, s.y0);
    case Op::scroll: input_->on_scroll(s.x0, s.y0); return true;
    case Op::drag: {
      if (phase_ == 0) {
        input_->on_cursor(s.x0, s.y0);
        this->button(0, true);
        phase_ = 1;
        return false;
      }
      if (phase_ == 2) return true;
      const double f = s.seconds > 0 ? std::min(1.0, elapsed / s.seconds) : 1.0;
      input_->on_cursor(s.x0 + (s.x1 - s.x0) * f, s.y0 + (s.y1 - s.y0) * f);
      if (f < 1.0) return false;
      this->button(0, false);
      phase_ = 2;
      return false;
    }
    case Op::turn: {
      const double f = s.seconds > 0 ? std::min(1.0, elapsed / s.seconds) : 1.0;
      const glm::dvec2 c = input_->cursor();
      input_->on_cursor(c.x + s.x0 * (f - moved_), c.y);
      moved_ = f;
      return f >= 1.0;
    }
    case Op::click_item: {
      const auto it = items.find(s.text);
      if (phase_ == 0 && elapsed > kItemTimeoutS) {
        std::string shown;
        for (const auto& [name, box] : items) shown += (shown.empty() ? "" : ", ") + ("\"" + name + "\"");
        error = Error{script_.file, s.line, 0, "click_item",
                      it == items.end()
                          ? "no UI item \"" + s.text + "\" appeared on screen within " +
                                std::to_string(int(kItemTimeoutS)) + " s (items on screen: " +
                                (shown.empty() ? "none" : shown) + ")"
                          : "the UI item \"" + s.text + "\" did not hold still for a frame within " +
                                std::to_string(int(kItemTimeoutS)) + " s"};
        return false;
      }
      if (phase_ == 0 && it == items.end()) return false;
      if (phase_ == 0) {
        // A new popup's items are laid out on its first frame and placed on its second: click
        // only a box that held still for one frame, as a person's eye would wait for it.
        const ItemBox& b = it->second;
        const bool still = seen_ && seen_->x == b.x && seen_->y == b.y && seen_->w == b.w && seen_->h == b.h;
        seen_ = b;
        if (!still) return false;
        return press_release(0, b.x + b.w * s.x0, b.y + b.h * s.y0);
      }
      return press_release(0, 0, 0);  // later phases ignore the position
    }
  }
  return true;
}

}  // namespace dtlab::run
