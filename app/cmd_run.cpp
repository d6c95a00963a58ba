// `dtlab run PROTOCOL --db DB [--participant ID] [--fullscreen] [--monitor N]
// [--console-monitor N] [--size WxH] [--script FILE] [--screenshots DIR]
// [--experimenter NAME]`, `dtlab run --list-monitors`: a person's session in
// a GLFW window with Dear ImGui (app/run; docs/run.md).
// The experimenter's start screen enrolls (or resumes) a participant, the
// session runner (study/session) drives the participant's screens, the end
// screen thanks them. Every finished trial is committed before the next
// starts, so a crash or a closed window loses at most the trial in progress
// and running the command again resumes at the first unfinished trial.
// Exit 0: the session finished (or the experimenter quit or aborted it);
// 1: invalid protocol, database or script; 2: bad command line; 3: no
// display, GL or database failure (mid-session: said in the window and on
// stderr, and the session resumes); 130: the window was closed mid-session.
#include <CLI/CLI.hpp>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <regex>

#include "app/commands.h"
#include "app/database_arg.h"
#include "app/platform/gl_context.h"
#include "app/run/responder.h"
#include "app/run/script.h"
#include "app/run/start.h"
#include "app/run/ui.h"
#include "study/protocol/protocol.h"
#include "study/protocol/wording.h"
#include "study/session/mapping.h"
#include "study/session/runnable.h"
#include "study/session/session.h"

namespace dtlab::app {

namespace {

struct RunArgs {
  std::string protocol, db, participant, size = "1280x800", script, screenshots, experimenter, font;
  bool fullscreen = false, allow_protocol_change = false;
  int monitor = 0;
  int console_monitor = -1;  // -1: the console is an overlay on the participant's window
};

std::string experimenter_name(const std::string& given) {
  if (!given.empty()) return given;
  for (const char* var : {"DTLAB_EXPERIMENTER", "USER", "LOGNAME"})
    if (const char* v = std::getenv(var); v && *v) return v;
  return "experimenter";
}

// --console-monitor, checked before anything is opened: a wrong monitor is a command-line mistake.
void check_console_monitor(const RunArgs& a) {
  if (a.console_monitor < 0) return;
  const auto monitors = platform::monitors();
  if (monitors.empty()) fail("run", kExitFailure, "--console-monitor: no monitor found (a participant session needs a display)");
  if (a.console_monitor >= static_cast<int>(monitors.size()))
    fail("run", kExitUsage, "--console-monitor " + std::to_string(a.console_monitor) + ": there is no such monitor; the "
                         "monitors are " + platform::describe(monitors) + " (dtlab run --list-monitors)");
  if (a.console_monitor == a.monitor)
    fail("run", kExitUsage, "--console-monitor " + std::to_string(a.console_monitor) +
                         ": the participant's window is on that monitor (--monitor " + std::to_string(a.monitor) +
                         "); the console goes on another one, or leave the option out for the overlay");
}

// --list-monitors: the monitors with the numbers --monitor and --console-monitor take.
void list_monitors() {
  const auto monitors = platform::monitors();
  if (monitors.empty()) std::cout << "no monitor (is there a display?)\n";
  for (std::size_t i = 0; i < monitors.size(); ++i) {
    const auto& m = monitors[i];
    std::cout << i << "  " << m.name << "  " << m.width << "x" << m.height << " at " << m.x << "," << m.y;
    if (m.refresh_hz > 0) std::cout << "  " << m.refresh_hz << " Hz";
    std::cout << (i == 0 ? "  (primary)" : "") << "\n";
  }
}

// The environment failed mid-session (the renderer, the GL, the disk): the participant's window
// says the session stopped and shows the experimenter the error until Close, then stderr says it
// and the command ends with exit 3. The session stays running in the file: every finished trial is
// kept, the trial in progress is recorded as interrupted, and the same command resumes it.
[[noreturn]] void report_failure(run::Ui& ui, const protocol::Protocol& p, const std::string& participant,
                                 const Error& e) {
  const std::string error = e.to_string();
  // A window that cannot draw any more (a lost context) still ends with the message on stderr.
  (void)run::end_screen(ui, "end", protocol::text(p, "end.failed_title"),
                        protocol::text(p, "end.failed_text") + "\n\n" +
                            protocol::text(p, "end.failed_experimenter", {{"error", error}}),
                        protocol::text(p, "end.close"));
  fail("run", exit_code(e),
       error + "; " + participant + "'s session stopped here: every finished trial is saved and running the same "
                                    "command again resumes it");
}

void run_person(const RunArgs& a) {
  auto p = protocol::load_protocol(a.protocol);
  if (!p) fail("run", kExitInvalid, p.error().to_string() + "\n(run `dtlab validate " + a.protocol + "` for every problem)");
  std::optional<run::Script> script;
  if (!a.script.empty()) {
    auto s = run::parse_script(a.script);
    if (!s) fail("run", s.error());
    script = std::move(s.value());
  }
  int width = 0, height = 0;
  std::smatch m;
  if (!std::regex_match(a.size, m, std::regex("([0-9]{2,5})x([0-9]{2,5})")))
    fail("run", kExitUsage, "--size " + a.size + ": expected WIDTHxHEIGHT, e.g. 1280x800");
  width = std::stoi(m[1]);
  height = std::stoi(m[2]);
  // Up to the largest view `dtlab validate` checks a protocol at (session::kMaxViewportSide).
  if (width < 320 || height < 240 || width > session::kMaxViewportSide || height > session::kMaxViewportSide)
    fail("run", kExitUsage, "--size " + a.size + ": expected 320x240 up to " + std::to_string(session::kMaxViewportSide) + "x" +
                         std::to_string(session::kMaxViewportSide));

  check_console_monitor(a);

  auto store = store::Store::open(a.db, session::study_info(p.value()), session::open_options(a.allow_protocol_change));
  if (!store) fail("run", store.error());

  platform::WindowOptions wo;
  wo.title = "dtlab - " + p->title;
  wo.width = width;
  wo.height = height;
  wo.fullscreen = a.fullscreen;
  wo.monitor = a.monitor;
  wo.resizable = false;  // the trial views keep one size for the whole session
  auto window = platform::create_window(wo);
  if (!window) fail("run", kExitFailure, window.error().to_string() + " (a participant session needs a display; for headless "
                                                              "runs use dtlab simulate)");
  run::UiOptions uo;
  uo.screenshots = a.screenshots;
  uo.font = !a.font.empty() ? a.font : std::getenv("DTLAB_FONT") ? std::getenv("DTLAB_FONT") : "";
  uo.glyph_text = protocol::participant_text(p.value());
  uo.script = script ? &*script : nullptr;
  uo.console_monitor = a.console_monitor;
  auto ui = run::Ui::create(**window, uo);
  if (!ui) fail("run", ui.error());
  if (!(*ui)->missing_glyphs().empty()) {
    std::string list;
    for (const std::string& g : (*ui)->missing_glyphs()) list += (list.empty() ? "" : " ") + g;
    std::cerr << "dtlab run: warning: the font has no glyph for " << list
              << " in the protocol's wording; participants would see '?' there. Give a font that has them with "
                 "--font FILE (or DTLAB_FONT), e.g. one of Debian's fonts-noto-* packages\n";
  }

  auto chosen = run::start_screen(**ui, *store, p.value(), a.participant);
  if (!chosen) fail("run", chosen.error().kind == ErrorKind::conflict ? kExitInterrupted : exit_code(chosen.error()),
                    chosen.error().to_string());
  if (!chosen->has_value()) {
    std::cerr << "dtlab run: quit from the start screen; nothing was run\n";
    return;
  }
  const std::string participant = (*chosen)->participant;
  run::WindowResponder responder(**ui, *store, p.value(), participant, experimenter_name(a.experimenter));
  session::Hooks hooks;
  hooks.on_session_start = [&](const store::Session& s, const design::Plan& plan) { responder.on_session_start(s, plan); };
  hooks.on_trial_recorded = [&](const session::TrialSpec& t, const store::TrialRecord& r) {
    responder.on_trial_recorded(t, r);
    std::cerr << "dtlab run: " << participant << " trial " << r.position << " of " << t.planned_trials
              << " recorded (" << t.planned.task << ", " << r.completion_s << " s)\n";
  };
  auto result = session::run_session(*store, p.value(), participant, responder, hooks, (*chosen)->demographics);
  if (!result) {
    if (responder.aborted()) {
      run::end_screen(**ui, "end", protocol::text(p.value(), "end.aborted_title"),
                      protocol::text(p.value(), "end.aborted_text"), protocol::text(p.value(), "end.close"));
      std::cerr << "dtlab run: " << participant << "'s session was aborted from the console (abandoned); every "
                << "recorded trial is kept\n";
      return;
    }
    if (result.error().field == "window")
      fail("run", kExitInterrupted, result.error().to_string() + "; run the same command again to resume " + participant);
    if (result.error().kind == ErrorKind::busy && result.error().field == store::kClaimField)
      fail("run", kExitFailure, result.error().to_string());
    if (result.error().kind == ErrorKind::environment) report_failure(**ui, p.value(), participant, result.error());
    fail("run", result.error());
  }
  if (result->declined) {
    Status st = run::end_screen(**ui, "end", protocol::text(p.value(), "consent.title"),
                                protocol::text(p.value(), "consent.declined"), protocol::text(p.value(), "end.close"));
    std::cerr << "dtlab run: " << participant << " declined consent; only the refusal is stored in "
              << store::display_name(a.db) << "\n";
    if (!st && st.error().field != "window") fail("run", st.error());
    return;
  }
  if (result->already_finished)
    std::cerr << "dtlab run: " << participant << " had already finished; nothing to run\n";
  Status st = run::end_screen(**ui, "end", protocol::text(p.value(), "end.title"),
                              protocol::text(p.value(), "end.text") + "\n\n" +
                                  protocol::text(p.value(), "end.experimenter"),
                              protocol::text(p.value(), "end.close"));
  std::cerr << "dtlab run: " << participant << "'s session is finished: " << result->trials_recorded
            << " trials recorded in " << store::display_name(a.db) << "\n";
  if (!st && st.error().field != "window") fail("run", st.error());
}

}  // namespace

void add_run_command(CLI::App& root) {
  auto a = std::make_shared<RunArgs>();
  auto* cmd = root.add_subcommand(
      "run",
      "Run a person through a protocol in a window: the experimenter's start screen (enroll with demographics, "
      "resume, release), then instructions, training, the trials, breaks between blocks, the post-test "
      "questionnaire with the depth test, and an end screen. The experimenter console (its own window with "
      "--console-monitor N, else Ctrl+Shift+E over the participant's screen, answer key on Ctrl+Shift+K held) pauses, "
      "marks trials invalid, takes notes and aborts, all stored. Every finished trial is saved at once; run the same "
      "command again to resume an interrupted session");
  cmd->footer(
      "Keys: Enter answers a trial; in WALKTHROUGH the arrow keys move and turn, the mouse turns; in ABSTRACT "
      "left-drag turns the scene. docs/run.md describes every screen, the console, scripts and replay.\n"
      "Exit status: 0 finished (or quit, or aborted from the console), 1 invalid protocol, database or script, 2 bad "
      "command line, 3 no display, GL or database failure (mid-session: rerun to resume), 130 window closed mid-session "
      "(rerun to resume).");
  // Before the required arguments are checked: --list-monitors alone is a whole command.
  cmd->add_flag_callback(
         "--list-monitors",
         [] {
           list_monitors();
           throw CLI::Success();
         },
         "Print the connected monitors with the numbers --monitor and --console-monitor take, and exit")
      ->trigger_on_parse();
  cmd->add_option("protocol", a->protocol, "Protocol file (TOML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--db", a->db, std::string(kDatabaseHelp) + "; a file is created if missing")->required();
  cmd->add_option("--participant", a->participant, "Participant ID to fill in on the start screen")
      ->check(participant_id());
  cmd->add_flag("--fullscreen", a->fullscreen, "Full screen on the monitor (at its current resolution)");
  cmd->add_option("--monitor", a->monitor, "Monitor to use, 0-based (0 = primary)")->check(CLI::Range(0, 16));
  cmd->add_option("--console-monitor", a->console_monitor,
                  "Open the experimenter console as its own window on this monitor (0-based, as --list-monitors "
                  "numbers them; not the participant's); without it the console is an overlay (Ctrl+Shift+E) that "
                  "hides the answer key unless Ctrl+Shift+K is held")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--size", a->size, "Window size WIDTHxHEIGHT in pixels (windowed)")->capture_default_str();
  cmd->add_option("--script", a->script,
                  "Scripted input: a text file of timed events per screen (docs/run.md, \"Scripts\"), fed in where "
                  "GLFW's callbacks enter; protocols/pilot-session.script runs the pilot end to end")
      ->check(CLI::ExistingFile);
  cmd->add_option("--screenshots", a->screenshots, "Directory for one PNG per distinct screen");
  cmd->add_option("--font", a->font,
                  "TrueType/OpenType font for the window's text (default: DejaVu Sans, which covers Latin, Greek "
                  "and Cyrillic; $DTLAB_FONT too); for a script it lacks, e.g. a Noto font of that script");
  cmd->add_option("--experimenter", a->experimenter,
                  "Who runs the session (recorded with console actions; default $DTLAB_EXPERIMENTER, else $USER)");
  cmd->add_flag("--allow-protocol-change", a->allow_protocol_change,
                "Accept a protocol whose design differs from the one the database was created with (recorded as a "
                "new design revision; a reworded protocol needs no flag)");
  cmd->callback([a] { run_person(*a); });
}

}  // namespace dtlab::app
