// `dtlab replay DB --participant ID --trial N --out DIR [--every K] [--size
// WxH] [--json]`: what a participant saw in a recorded trial, rendered again
// headless from the recorded camera poses with the trial's method
// (study/replay): DIR/frame-00001.png ... and, for WALKTHROUGH trials,
// DIR/path.svg, the walked path on the floor plan with the target and the
// answer marked. Never writes the database. Exit 0 done, 1 unknown
// participant or trial or a scene that no longer regenerates, 2 bad command
// line, 3 GL, database or I/O failure.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <regex>

#include "app/commands.h"
#include "app/database_arg.h"
#include "app/platform/gl_context.h"
#include "study/common/file.h"
#include "study/replay/path.h"
#include "study/replay/replay.h"
#include "study/session/mapping.h"

namespace dtlab::app {

namespace {

struct ReplayArgs {
  std::string db, participant, out, size;
  int trial = 0, every = 1;
  bool json = false;
};

void run_replay(const ReplayArgs& a) {
  auto reader = store::StudyReader::open(a.db, session::read_options());
  if (!reader) fail("replay", reader.error());
  auto trial = replay::load_trial(*reader, a.participant, a.trial);
  if (!trial) fail("replay", trial.error());
  int width = trial->display ? trial->display->width : 800, height = trial->display ? trial->display->height : 600;
  if (!a.size.empty()) {
    std::smatch m;
    if (!std::regex_match(a.size, m, std::regex("([0-9]{2,5})x([0-9]{2,5})")))
      fail("replay", kExitUsage, "--size " + a.size + ": expected WIDTHxHEIGHT, e.g. 800x600");
    width = std::stoi(m[1]);
    height = std::stoi(m[2]);
    if (width < 16 || height < 16 || width > 8192 || height > 8192) fail("replay", kExitUsage, "--size: 16x16 up to 8192x8192");
  }
  std::error_code ec;
  std::filesystem::create_directories(a.out, ec);
  if (ec) fail("replay", kExitFailure, a.out + ": cannot create the directory: " + ec.message());
  auto ctx = platform::create_headless(width, height);
  if (!ctx) fail("replay", kExitFailure, ctx.error().to_string());
  std::vector<std::string> files;
  Status st = replay::render_frames(*trial, width, height, a.every, [&](int frame, int, const render::Image& img) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%05d.png", frame + 1);
    files.push_back(name);
    return render::write_png(img, (std::filesystem::path(a.out) / name).string());
  });
  if (!st) fail("replay", st.error());
  const scene::Scene& s = trial->scene;
  if (s.plan) {
    const replay::WalkedPath path = replay::walked_path(
        s, trial->row.answer, trial->poses, "trial " + std::to_string(a.trial) + " (" + trial->row.planned.task + ")");
    const std::string svg = replay::path_svg(*s.plan, s.camera.position, {path}, 640,
                                             a.participant + ", " + path.label);
    Status w = write_file_atomically((std::filesystem::path(a.out) / "path.svg").string(), [&](std::ostream& o) {
      o << svg;
      return Status{};
    });
    if (!w) fail("replay", w.error());
    files.push_back("path.svg");
  }
  if (a.json) {
    nlohmann::json j{{"database", store::display_name(a.db)}, {"participant", a.participant}, {"trial", a.trial},
                     {"task", trial->row.planned.task}, {"method", trial->row.planned.method},
                     {"poses", trial->poses.size()}, {"width", width}, {"height", height},
                     {"out", a.out},               {"files", files}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::cerr << "dtlab replay: " << a.participant << " trial " << a.trial << " (" << trial->row.planned.task << ", "
              << trial->row.planned.method << "): " << files.size() << " files in " << a.out << " from "
              << trial->poses.size() << " recorded poses\n";
  }
}

}  // namespace

void add_replay_command(CLI::App& root) {
  auto a = std::make_shared<ReplayArgs>();
  auto* cmd = root.add_subcommand(
      "replay",
      "Render what a participant saw in a recorded trial: the recorded camera poses drawn again with the trial's "
      "method into PNG frames, and for WALKTHROUGH trials the walked path on the floor plan (path.svg) with the "
      "target and the answer marked");
  cmd->footer("Trials are numbered as in `dtlab plan` and the export's position column (1-based).\n"
              "Exit status: 0 done, 1 unknown participant or trial, or a scene this build no longer generates, "
              "2 bad command line, 3 GL, database or I/O failure.");
  cmd->add_option("database", a->db, kDatabaseHelp)->required();
  cmd->add_option("--participant", a->participant, "Participant ID")->check(participant_id())->required();
  cmd->add_option("--trial", a->trial, "Trial position in the session, 1-based")->required()->check(CLI::PositiveNumber);
  cmd->add_option("--out", a->out, "Output directory (created if missing)")->required();
  cmd->add_option("--every", a->every, "Render every K-th pose (the first and the last always)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--size", a->size, "Frame size WIDTHxHEIGHT (default: the size the session ran at)");
  cmd->add_flag("--json", a->json, "Print {database, participant, trial, task, method, poses, width, height, out, files}");
  cmd->callback([a] { run_replay(*a); });
}

}  // namespace dtlab::app
