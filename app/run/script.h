// Scripted input for `dtlab run --script FILE`: a text file of timed input
// events, grouped in sections by the screen they answer. Whenever the app
// shows a screen, the section for it plays from its first line (once the
// screen has been presented twice, so its layout has settled); its events
// enter through Input's entry points, exactly where GLFW's callbacks enter,
// so the app and Dear ImGui cannot tell them from a person. Because sections
// follow screens, not a fixed timeline, the same script finishes a session
// that was interrupted and resumed half-way. docs/run.md, "Scripts", lists
// the syntax. Guarantees: a malformed script is an Error naming file:line
// before anything runs; a step that cannot happen (a UI item that never
// appears on screen within kItemTimeoutS) is an Error naming its line, and a
// screen still up kIdleTimeoutS after its section played out (or with no
// section) is an Error naming the section's last step: a scripted run never
// waits for a person. Never: reads the answer key.
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "app/run/input.h"
#include "study/common/error.h"

namespace dtlab::run {

struct ScriptStep {
  enum class Op {
    wait,        // wait SECONDS
    key,         // key NAME: press and release (two frames)
    key_down,    // key_down NAME
    key_up,      // key_up NAME
    hold,        // hold NAME SECONDS
    type,        // type "TEXT": characters (UTF-8, any script; as a keyboard's text input)
    move,        // move X Y: the cursor to window coordinates
    click,       // click X Y [left|right]
    drag,        // drag X0 Y0 X1 Y1 SECONDS (left button)
    turn,        // turn DX SECONDS: relative cursor motion (a captured cursor turns the view)
    scroll,      // scroll DX DY
    click_item,  // click_item "NAME" [FX FY]: the UI item named NAME (at fractions of its box; default centre)
    window,      // window console|participant: the window the section's next steps act in
  };
  Op op = Op::wait;
  int line = 0;
  double seconds = 0;
  int key = -1;
  int button = 0;
  std::string text;
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct ScriptSection {
  std::string screen;  // "trial T1" (exactly that screen), "questionnaire tlx" (its items), or "trial" (every "trial ...")
  int line = 0;
  std::vector<ScriptStep> steps;
};

struct Script {
  std::string file;
  std::vector<ScriptSection> sections;
  // The section for a screen id: an exact match first, then the id cut at its last '.' (so
  // "questionnaire tlx" serves every "questionnaire tlx.<item>"), then its first word; nullptr if none.
  const ScriptSection* for_screen(const std::string& screen) const;
};

Result<Script> parse_script(const std::string& path);
Result<Script> parse_script_text(const std::string& text, const std::string& file);

// A UI item's box in window coordinates (what click_item aims at).
struct ItemBox {
  float x = 0, y = 0, w = 0, h = 0;
};
using ItemBoxes = std::map<std::string, ItemBox>;

class ScriptPlayer {
 public:
  // `input` is the participant window's; `console` the console's own window's (nullptr on one
  // monitor, where `window console` steps act in the participant's window, which has the console).
  ScriptPlayer(const Script& script, Input& input, Input* console = nullptr);

  // Once per frame, after the frame's real events arrived: a new screen instance restarts its
  // section (in the participant's window); the steps that are due are fed to the input of the
  // window they act in. `items` and `console_items` are the boxes each window drew last.
  Status tick(const std::string& screen, std::uint64_t instance, const ItemBoxes& items,
              const ItemBoxes& console_items, Clock::time_point now);
  // The console's own window drew a frame. Its frames are fewer than the participant's (it draws in
  // their spare time), so steps acting in it wait for one after each of their phases: a click's press
  // and release, or two clicks, must not fall into one console frame.
  void console_drew() { console_fresh_ = true; }
  // The screen is being left: the playing section stops, and every key and button it holds down
  // is released (a release lost with its screen would leave the key down on the next one).
  void leave();
  // The current screen's section has played every step (false without a section for it). The
  // section of a screen that stays up has nothing more to do: only a person could go on.
  bool played_out() const { return section_ != nullptr && next_ >= section_->steps.size(); }
  // The line of the current screen's section (0: none).
  int section_line() const { return section_ ? section_->line : 0; }

 private:
  bool step(const ScriptStep& s, const ItemBoxes& items, Clock::time_point now, Status& error);
  void begin_step(Clock::time_point now);  // the per-step state, fresh for the next step
  void key(int key, bool down);
  void button(int button, bool down);

  const Script& script_;
  Input& participant_;
  Input* console_;
  Input* input_ = nullptr;  // the window the steps act in now
  bool console_fresh_ = true;  // the console window drew a frame since a step last acted there
  const ScriptSection* section_ = nullptr;
  std::uint64_t instance_ = ~0ULL;
  std::size_t next_ = 0;
  int phase_ = 0;
  Clock::time_point step_start_{};
  Clock::time_point idle_since_{};  // since the screen's last step ended (or the screen appeared)
  double moved_ = 0;  // turn/drag: the share of the motion already fed
  std::optional<ItemBox> seen_;  // click_item: its item's box last frame (clicked once it holds still)
  std::vector<std::pair<Input*, int>> held_keys_, held_buttons_;  // with the window they are held in
};

// How long click_item waits for its item (on screen, holding still) before it fails.
inline constexpr double kItemTimeoutS = 60.0;
// How long a screen may stay up once its section has played out (or when the script has no section
// for it) before the run fails, naming the section's last step: only the script acts in a scripted run.
inline constexpr double kIdleTimeoutS = 60.0;

}  // namespace dtlab::run
