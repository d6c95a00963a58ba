// `dtlab run` through the real app in a real window (this program runs under
// xvfb-run): the shipped pilot script takes a new participant through the
// whole pilot protocol (every planned trial and the questionnaire stored,
// the answers the script's); every screen's screenshot is non-blank and
// differs from the others; kill -9 at several moments and a rerun with the
// same script give the trial sequence and answers of an uninterrupted run,
// with PRAGMA integrity_check ok after each kill, and so does a rerun after a
// render failure (which the window and stderr report); replay reproduces the
// logged poses and its first frame equals `dtlab render` of that pose; and
// real X events (xdotool) reach the app the way a person's do.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "study/render/image.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/common/must.h"

using dtlab::test::must;

namespace dtlab::run {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string kPilot = std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml";
const std::string kScript = std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot-session.script";
constexpr const char* kSize = "640x480";  // small: llvmpipe renders every frame of the session

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("dtlab_run_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Starts `dtlab run` with `protocol`; stdout and stderr to `log`.
pid_t start_protocol(const std::string& protocol, const fs::path& db, const fs::path& log,
                     const std::vector<std::string>& extra = {},
                     const std::vector<std::pair<std::string, std::string>>& env = {}) {
  std::vector<std::string> args{DTLAB_BINARY, "run", protocol, "--db", db.string(), "--size", kSize};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    for (const auto& [k, v] : env) ::setenv(k.c_str(), v.c_str(), 1);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(DTLAB_BINARY, argv.data());
    ::_exit(127);
  }
  return pid;
}

// Starts `dtlab run` with the pilot; stdout and stderr to `log`.
pid_t start_run(const fs::path& db, const fs::path& log, const std::vector<std::string>& extra = {},
                const std::vector<std::pair<std::string, std::string>>& env = {}) {
  return start_protocol(kPilot, db, log, extra, env);
}

// A waitpid status as a shell reports it: the exit code, or 128 + the signal.
int exit_code(int status) { return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status); }

int wait_exit(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return exit_code(status);
}

// The exit code, or -1 if it ran past `seconds` (it is killed then: a hang fails the test, it
// does not stall the suite).
int wait_exit_within(pid_t pid, double seconds) {
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (Clock::now() < until) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return exit_code(status);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  return -1;
}

std::string slurp(const fs::path& p) { return dtlab::test::read_text(p); }

store::StudyReader reader(const fs::path& db) {
  auto r = store::StudyReader::open(db.string());
  if (!r) {
    ADD_FAILURE() << r.error().to_string();
    std::abort();
  }
  return std::move(*r);
}

// What must not depend on when the session was interrupted: the planned sequence, the scenes
// and the answers, and the questionnaire.
std::string outcome(const fs::path& db) {
  auto r = reader(db);
  std::string s;
  const auto trials = r.trials();
  for (const auto& t : *trials) {
    s += t.participant + " " + std::to_string(t.planned.position) + " " + t.planned.task + " " +
         std::to_string(t.planned.seed) + " " + t.scene_hash.substr(0, 16) + " ";
    if (t.answer) {
      if (const auto* c = std::get_if<store::Count>(&*t.answer)) s += "count " + std::to_string(c->n);
      if (const auto* l = std::get_if<store::Letter>(&*t.answer)) s += "letter " + l->letter;
      if (const auto* p = std::get_if<store::Position>(&*t.answer)) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "position %.2f %.2f", p->x, p->z);
        s += buf;
      }
    } else {
      s += "none";
    }
    s += "\n";
  }
  const auto answers = r.questionnaire();
  for (const auto& q : *answers) {
    s += q.item + "[" + q.scope + "]=";
    if (const double* v = std::get_if<double>(&q.value)) s += std::to_string(*v);
    else s += std::get<std::string>(q.value);
    s += "\n";
  }
  return s;
}

class RunPilot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir = new fs::path(temp_dir("reference"));
    db = new fs::path(*dir / "pilot.sqlite");
    const auto t0 = Clock::now();
    const pid_t pid = start_run(*db, *dir / "log.txt", {"--script", kScript, "--screenshots", (*dir / "shots").string()});
    rc = wait_exit(pid);
    seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  }
  static void TearDownTestSuite() {
    if (!::testing::Test::HasFailure() && !std::getenv("DTLAB_KEEP_TEST_DIRS")) fs::remove_all(*dir);
    delete db;
    delete dir;
  }
  static fs::path* dir;
  static fs::path* db;
  static int rc;
  static double seconds;
};
fs::path* RunPilot::dir = nullptr;
fs::path* RunPilot::db = nullptr;
int RunPilot::rc = -1;
double RunPilot::seconds = 0;

TEST_F(RunPilot, TheScriptedSessionFinishesWithEveryTrialAndTheQuestionnaire) {
  ASSERT_EQ(rc, 0) << slurp(*dir / "log.txt");
  RecordProperty("session_seconds", std::to_string(seconds));
  auto r = reader(*db);
  auto sessions = r.sessions();
  ASSERT_EQ(sessions->size(), 1u);
  const auto& s = (*sessions)[0];
  EXPECT_EQ(s.participant, "pilot-01");
  EXPECT_EQ(s.status, store::SessionStatus::finished);
  EXPECT_EQ(s.planned, 8);
  EXPECT_EQ(s.recorded, 8);
  ASSERT_EQ(s.displays.size(), 1u);
  EXPECT_EQ(s.displays[0].info.kind, "window");
  EXPECT_EQ(s.displays[0].info.width, 640);
  EXPECT_EQ(s.displays[0].info.height, 480);
  // Demographics as the script entered them on the start screen.
  const auto ledger = r.ledger();
  EXPECT_EQ((*ledger)[0].demographics,
            (store::Demographics{{"age", "27"}, {"gender", "female"}, {"handedness", "right"}, {"games", "sometimes"}}));
  // The answers are the script's: T1 23, T2 K, T4 5, T3 a point of the plan.
  auto trials = r.trials();
  ASSERT_EQ(trials->size(), 8u);
  for (const auto& t : *trials) {
    SCOPED_TRACE(t.planned.task + " at " + std::to_string(t.planned.position));
    ASSERT_TRUE(t.answer.has_value());
    if (t.planned.task == "T1") {
      EXPECT_EQ(std::get<store::Count>(*t.answer).n, 23);
    } else if (t.planned.task == "T2") {
      EXPECT_EQ(std::get<store::Letter>(*t.answer).letter, "K");
    } else if (t.planned.task == "T4") {
      EXPECT_EQ(std::get<store::Count>(*t.answer).n, 5);
    }
    if (t.planned.task == "T3") {
      const auto& p = std::get<store::Position>(*t.answer);
      EXPECT_GT(p.x, 0);
      EXPECT_GT(p.z, 0);
    }
    EXPECT_GT(t.completion_s, 0);
    EXPECT_GT(t.frames.frames, 1);
    EXPECT_GT(t.event_count, 0);  // keys, cursor, buttons and the answer
    EXPECT_TRUE(t.frames.first_ms.has_value());
    EXPECT_TRUE(t.frames.late.has_value());
    EXPECT_EQ(r.poses(t.participant, t.planned.position)->size(), static_cast<std::size_t>(t.frames.frames));
  }
  // The questionnaire: 4 ratings (3), the preference (on), self-reported depth (2), 3 depth-test pairs.
  auto q = r.questionnaire();
  std::map<std::string, std::string> answers;
  for (const auto& a : *q)
    answers[a.item + "[" + a.scope + "]"] = std::holds_alternative<double>(a.value)
                                                ? std::to_string(static_cast<int>(std::get<double>(a.value)))
                                                : std::get<std::string>(a.value);
  EXPECT_EQ(answers.size(), 4u + 1 + 1 + 3);
  EXPECT_EQ(answers["rating[scenario=abstract;transparency=off]"], "3");
  EXPECT_EQ(answers["preference[]"], "on");
  EXPECT_EQ(answers["depth_self[]"], "2");
  for (const char* pair : {"pair=1", "pair=2", "pair=3"}) {
    const std::string v = answers[std::string("depth_test[") + pair + "]"];
    EXPECT_TRUE(v == "0" || v == "1") << pair << ": " << v;  // scored against the geometry
  }
  EXPECT_EQ(*r.integrity_check(), "ok");
}

// Decodes a PNG; empty on failure.
render::Image decode(const fs::path& png) {
  render::Image img;
  int n = 0;
  unsigned char* data = stbi_load(png.c_str(), &img.width, &img.height, &n, 4);
  if (!data) return img;
  img.rgba.assign(data, data + static_cast<std::size_t>(img.width) * img.height * 4);
  stbi_image_free(data);
  return img;
}

TEST_F(RunPilot, EveryScreenHasANonBlankScreenshotDistinctFromTheOthers) {
  ASSERT_EQ(rc, 0);
  std::vector<fs::path> shots;
  for (const auto& e : fs::directory_iterator(*dir / "shots")) shots.push_back(e.path());
  std::sort(shots.begin(), shots.end());
  std::vector<std::string> names;
  for (const auto& p : shots) names.push_back(p.filename().string().substr(3));
  for (const char* want : {"start.png", "instructions-T1.png", "training-T1.png", "trial-T1.png", "answer-T1.png",
                           "answer-T2.png", "trial-T3.png", "answer-T3.png", "trial-T4.png", "break.png",
                           "questionnaire-rating.png", "questionnaire-preference.png", "questionnaire-depth-self.png",
                           "depth-test.png", "end.png"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  std::vector<render::Image> images;
  for (const auto& p : shots) {
    images.push_back(decode(p));
    const render::Image& img = images.back();
    ASSERT_EQ(img.width, 640) << p;
    ASSERT_EQ(img.height, 480) << p;
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i < img.rgba.size(); i += 4 * 7)
      colours.insert(img.rgba[i] | img.rgba[i + 1] << 8 | img.rgba[i + 2] << 16);
    EXPECT_GT(colours.size(), 8u) << p << " is blank (" << colours.size() << " colours)";
  }
  for (std::size_t a = 0; a < images.size(); ++a)
    for (std::size_t b = a + 1; b < images.size(); ++b)
      EXPECT_GT(must(render::compare(images[a], images[b])).pixels_off_pct, 0.5) << shots[a] << " and " << shots[b];
}

TEST_F(RunPilot, ReplayReproducesTheLoggedPosesAndRendersWhatDtlabRenderDraws) {
  ASSERT_EQ(rc, 0);
  auto r = reader(*db);
  const auto trials = r.trials();
  int position = 0;
  for (const auto& t : *trials)
    if (t.planned.task == "T3" && position == 0) position = t.planned.position;
  ASSERT_GT(position, 0);
  const auto poses = *r.poses("pilot-01", position);
  const fs::path out = *dir / "replay";
  const auto rep = dtlab::test::run_dtlab("replay '" + db->string() + "' --participant pilot-01 --trial " +
                                          std::to_string(position) + " --out '" + out.string() + "' --json");
  ASSERT_EQ(rep.rc, 0) << rep.err;
  const auto j = nlohmann::json::parse(rep.out);
  EXPECT_EQ(j["poses"].get<std::size_t>(), poses.size());
  std::size_t frames = 0;
  for (const auto& e : fs::directory_iterator(out)) frames += e.path().extension() == ".png";
  EXPECT_EQ(frames, poses.size()) << "one frame per recorded pose (--every 1)";
  const std::string svg = slurp(out / "path.svg");
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("x answer"), std::string::npos);  // the T3 answer is marked
  // Its first frame is `dtlab render` of the first pose (yaw in degrees, the eye position).
  char camera[256];
  std::snprintf(camera, sizeof camera, "yaw=%.17g,pitch=%.17g,x=%.17g,y=%.17g,z=%.17g", poses[0].yaw * 180 / M_PI,
                poses[0].pitch * 180 / M_PI, poses[0].x, poses[0].y, poses[0].z);
  const fs::path rendered = *dir / "render.png";
  const auto ren = dtlab::test::run_dtlab("render --protocol '" + kPilot + "' --db '" + db->string() +
                                          "' --participant pilot-01 --trial " + std::to_string(position) +
                                          " --width 640 --height 480 --camera " + camera + " --out '" +
                                          rendered.string() + "'");
  ASSERT_EQ(ren.rc, 0) << ren.err;
  const auto diff = must(render::compare(decode(out / "frame-00001.png"), decode(rendered)));
  EXPECT_LT(diff.mae, 0.5);
  EXPECT_LT(diff.pixels_off_pct, 0.5);
}

// The report of the scripted session links one walked-path figure per WALKTHROUGH task, drawn from
// the recorded poses on each trial's regenerated building: a line per trial, T3's target and answer.
TEST_F(RunPilot, TheReportLinksTheWalkedPathsOfEachWalkthroughTask) {
  ASSERT_EQ(rc, 0);
  const fs::path out = *dir / "report";
  const auto rep = dtlab::test::run_dtlab("analyze '" + db->string() + "' --out '" + out.string() + "' --quiet");
  ASSERT_EQ(rep.rc, 0) << rep.err;
  auto r = reader(*db);
  const auto recorded = r.trials();
  ASSERT_TRUE(recorded);
  std::map<std::string, std::size_t> trials;  // per task
  for (const auto& t : *recorded) ++trials[t.planned.task];
  const std::string html = slurp(out / "index.html");
  for (const char* task : {"T3", "T4"}) {
    SCOPED_TRACE(task);
    const std::string file = std::string("paths/01-pilot-01-") + task + ".svg";
    const std::string svg = slurp(out / file);
    ASSERT_FALSE(svg.empty());
    std::size_t lines = 0, crosses = 0;
    for (auto i = svg.find("<polyline"); i != std::string::npos; i = svg.find("<polyline", i + 1)) ++lines;
    for (auto i = svg.find("<path d="); i != std::string::npos; i = svg.find("<path d=", i + 1)) ++crosses;
    EXPECT_EQ(lines, trials[task]) << "one walked line per trial";
    EXPECT_EQ(crosses, std::string(task) == "T3" ? trials[task] : 0u) << "T3's marked answers";
    EXPECT_NE(html.find("<a href=\"" + file + "\">"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(out / "paths/01-pilot-01-T1.svg")) << "ABSTRACT tasks have no floor plan";
}

// Rerunning the script for a participant whose session finished: the start screen refuses, and
// with no step left in its section the run ends with that reason (it used to wait forever for a
// person to type another ID). Exit code 1: the input (the script) is at fault.
TEST_F(RunPilot, FinishedParticipantScriptRefusedAtOnce) {
  ASSERT_EQ(rc, 0);
  const fs::path d = temp_dir("finished");
  fs::copy_file(*db, d / "pilot.sqlite");
  const std::string before = outcome(d / "pilot.sqlite");
  const int again = wait_exit_within(start_run(d / "pilot.sqlite", d / "log.txt", {"--script", kScript}), 120);
  EXPECT_EQ(again, 1) << slurp(d / "log.txt");
  const std::string log = slurp(d / "log.txt");
  EXPECT_NE(log.find("has finished their session"), std::string::npos) << log;
  EXPECT_NE(log.find(kScript), std::string::npos) << "the error names the script: " << log;
  EXPECT_EQ(outcome(d / "pilot.sqlite"), before) << "nothing saved is changed";
  fs::remove_all(d);
}

// The second participant of the same study (enrollment index 1) through the same script with
// their own ID, choosing the neutral option of the preference question. Regression: the depth
// test's markers were projected with the scene's start camera instead of the test's fixed view,
// so for this participant they lay off the window, click_item "A" clicked nothing, and the
// session waited forever; the neutral option was not shown at all.
TEST_F(RunPilot, SecondParticipantFinishesTheDepthTestAndCanChooseNoPreference) {
  ASSERT_EQ(rc, 0);
  const fs::path d = temp_dir("second");
  fs::copy_file(*db, d / "pilot.sqlite");
  std::string script = slurp(kScript);
  for (auto [from, to] : {std::pair<std::string, std::string>{"type \"pilot-01\"", "type \"pilot-02\""},
                          {"[questionnaire preference]\nclick_item \"on\"",
                           "[questionnaire preference]\nclick_item \"no preference\""}}) {
    const auto at = script.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    script.replace(at, from.size(), to);
  }
  { std::ofstream(d / "second.script") << script; }
  const int second = wait_exit_within(
      start_run(d / "pilot.sqlite", d / "log.txt", {"--script", (d / "second.script").string()}), 300);
  ASSERT_EQ(second, 0) << slurp(d / "log.txt");
  auto r = reader(d / "pilot.sqlite");
  const auto ledger = r.ledger();
  ASSERT_EQ(ledger->size(), 2u);
  EXPECT_EQ((*ledger)[1].participant, "pilot-02");
  EXPECT_EQ((*ledger)[1].index, 1);
  std::map<std::string, std::string> answers;
  const auto stored = r.questionnaire("pilot-02");
  ASSERT_TRUE(stored);
  for (const auto& q : *stored) {
    if (const auto* t = std::get_if<std::string>(&q.value)) answers[q.item + "[" + q.scope + "]"] = *t;
    else answers[q.item + "[" + q.scope + "]"] = std::to_string(std::get<double>(q.value));
  }
  EXPECT_EQ(answers["preference[]"], "no preference");
  for (const char* pair : {"depth_test[pair=1]", "depth_test[pair=2]", "depth_test[pair=3]"})
    EXPECT_EQ(answers.count(pair), 1u) << pair;
  fs::remove_all(d);
}

// The shipped German study (protocols/technik-de.toml) with its script: consent agreed, every page
// of the sequence in the screen log in its place, the NASA-TLX after each technique clicked by its
// German wording, SUS by number keys, the preference by a level's label, the comment in UTF-8 as typed.
TEST(RunGerman, TheShippedGermanStudyRunsToTheEndInGerman) {
  const fs::path d = temp_dir("german");
  const std::string protocol = std::string(DTLAB_SOURCE_DIR) + "/protocols/technik-de.toml";
  const int rc = wait_exit_within(
      start_protocol(protocol, d / "de.sqlite", d / "log.txt",
                     {"--script", std::string(DTLAB_SOURCE_DIR) + "/protocols/technik-de.script"}),
      400);
  ASSERT_EQ(rc, 0) << slurp(d / "log.txt");
  auto r = reader(d / "de.sqlite");
  const auto consents = r.consents();
  ASSERT_TRUE(consents);
  ASSERT_EQ(consents->size(), 1u);
  EXPECT_TRUE(consents->front().agreed);
  const auto screens = r.screens("de-01");
  ASSERT_TRUE(screens);
  std::vector<std::string> names;
  for (const auto& s : *screens) names.push_back(s.screen);
  ASSERT_GE(names.size(), 4u);
  EXPECT_EQ(names[0], "consent");
  EXPECT_EQ(names[1], "page willkommen");
  EXPECT_EQ(names.back(), "page abschluss");
  for (const char* level : {"level technique=standard", "level technique=xray", "level technique=lens"})
    EXPECT_EQ(std::count(names.begin(), names.end(), level), 1) << level;
  EXPECT_EQ(std::count(names.begin(), names.end(), "break"), 2);
  for (const char* task : {"instructions T1", "training T1", "instructions T2", "training T2"})
    EXPECT_EQ(std::count(names.begin(), names.end(), task), 3) << task;  // once per technique's block
  for (const auto& s : *screens) {
    if (s.screen == "break") EXPECT_GE(s.duration_s, 5.0);  // min_s = 5, not skippable
  }
  std::map<std::string, std::string> answers;
  const auto stored = r.questionnaire("de-01");
  ASSERT_TRUE(stored);
  for (const auto& q : *stored) {
    if (const auto* t = std::get_if<std::string>(&q.value)) answers[q.item + "[" + q.scope + "]"] = *t;
    else answers[q.item + "[" + q.scope + "]"] = std::to_string(std::get<double>(q.value));
  }
  for (const char* technique : {"standard", "xray", "lens"})
    EXPECT_EQ(answers["tlx.mental[technique=" + std::string(technique) + "]"], std::to_string(40.0)) << technique;
  for (int q = 1; q <= 10; ++q) EXPECT_EQ(answers["sus.q" + std::to_string(q) + "[]"], std::to_string(3.0)) << q;
  EXPECT_EQ(answers["vorliebe[]"], "xray");
  EXPECT_EQ(answers["kommentar[]"], "Der Röntgenblick war angenehm; die Lupe verdeckte manchmal zu viel.");
  fs::remove_all(d);
}

// A participant ID longer than the store keeps (64 bytes) is refused on the start screen, whole,
// with the reason; it used to be cut to 64 characters without a word.
TEST_F(RunPilot, TooLongAParticipantIdIsRefusedNotCut) {
  ASSERT_EQ(rc, 0);
  const fs::path d = temp_dir("long_id");
  const std::string id(70, 'p');
  std::string script = slurp(kScript);
  const std::string from = "type \"pilot-01\"";
  script.replace(script.find(from), from.size(), "type \"" + id + "\"");
  { std::ofstream(d / "long.script") << script; }
  const int code =
      wait_exit_within(start_run(d / "pilot.sqlite", d / "log.txt", {"--script", (d / "long.script").string()}), 120);
  EXPECT_EQ(code, 1) << slurp(d / "log.txt");
  const std::string log = slurp(d / "log.txt");
  EXPECT_NE(log.find("is 70 bytes long; a participant ID has at most 64"), std::string::npos) << log;
  if (auto r = store::StudyReader::open((d / "pilot.sqlite").string())) {
    const auto ledger = r->ledger();
    EXPECT_TRUE(!ledger || ledger->empty()) << "nobody was enrolled";
  }
  fs::remove_all(d);
}

// kill -9 at several moments of a scripted session; each rerun with the same script continues.
// The file stays intact after every kill, and the end result equals the uninterrupted run's.
TEST_F(RunPilot, KilledAtSeveralMomentsAndResumedEqualsTheUninterruptedRun) {
  ASSERT_EQ(rc, 0);
  const fs::path d = temp_dir("killed");
  const fs::path killed = d / "pilot.sqlite", log = d / "log.txt";
  int kills = 0, final_rc = -1;
  // A kill that lands after the session's last commit (on the end screen) leaves it finished: the
  // next run's start screen refuses the participant, and the scripted run says so and stops with
  // exit 1 (FinishedParticipantScriptRefusedAtOnce). That counts as the session's end wherever in
  // the loop it happens (regression: it was handled after the last kill only, and a fresh clone's
  // suite failed when an earlier kill landed there).
  auto finished = [&] {
    if (!fs::exists(killed)) return false;
    auto r = store::StudyReader::open(killed.string());
    if (!r) return false;
    const auto sessions = r->sessions();
    return sessions && sessions->size() == 1 && (*sessions)[0].status == store::SessionStatus::finished;
  };
  auto rerun_finished = [&] {
    const int rc = wait_exit_within(start_run(killed, log, {"--script", kScript}), 300);
    EXPECT_EQ(rc, 1) << slurp(log);
    return rc == 1 ? 0 : rc;
  };
  for (double delay : {4.0, 9.0, 14.0, 19.0, 24.0, 29.0}) {
    if (finished()) {
      final_rc = rerun_finished();
      break;
    }
    const pid_t pid = start_run(killed, log, {"--script", kScript});
    const auto until = Clock::now() + std::chrono::duration<double>(delay);
    int status = 0;
    bool ended = false;
    while (Clock::now() < until)
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        ended = true;
        break;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    if (ended) {
      final_rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      break;
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    ++kills;
    // Killed before the schema's transaction committed, the file holds no table yet (nothing was
    // saved; the rerun creates the schema). Anything else must be a sound study.
    if (fs::exists(killed)) {
      auto r = store::StudyReader::open(killed.string());
      if (r) {
        EXPECT_EQ(*r->integrity_check(), "ok") << "after kill " << kills;
      } else {
        EXPECT_NE(r.error().message.find("no session was ever started"), std::string::npos)
            << "after kill " << kills << ": " << r.error().to_string();
      }
    }
  }
  if (final_rc < 0)
    final_rc = finished() ? rerun_finished() : wait_exit_within(start_run(killed, log, {"--script", kScript}), 300);
  ASSERT_EQ(final_rc, 0) << slurp(log);
  EXPECT_GE(kills, 2) << "the session should have been interrupted more than once";
  EXPECT_EQ(outcome(killed), outcome(*db));
  auto sessions = reader(killed).sessions();
  ASSERT_EQ(sessions->size(), 1u);
  EXPECT_EQ((*sessions)[0].status, store::SessionStatus::finished);
  EXPECT_EQ(*reader(killed).integrity_check(), "ok");
  fs::remove_all(d);
}

// A render failure mid-session (the test builds' injected GL_OUT_OF_MEMORY: render.h's renderer
// fails every frame while $DTLAB_TEST_RENDER_FAIL_FILE exists) once two trials are recorded: the
// participant's window turns to the end screen, stderr names the error and says the session can
// resume, the exit status is 3 (environment); the recorded trials stay, the session stays running
// with the trial in progress recorded as interrupted, and the same command without the failure
// resumes it to the uninterrupted run's outcome. (Before, the renderer threw std::runtime_error
// through the session: the process died and nothing was said.)
TEST_F(RunPilot, ARenderFailureShowsTheErrorKeepsTheTrialsAndTheSameCommandResumes) {
  ASSERT_EQ(rc, 0);
  const fs::path d = temp_dir("render_failure");
  const fs::path db = d / "pilot.sqlite", log = d / "log.txt", items = d / "items.jsonl", flag = d / "fail-now";
  const pid_t pid = start_run(db, log, {"--script", kScript},
                              {{"DTLAB_TEST_RENDER_FAIL_FILE", flag.string()}, {"DTLAB_RUN_ITEMS_LOG", items.string()}});
  auto count = [](const fs::path& file, const std::string& what) {
    const std::string text = fs::exists(file) ? slurp(file) : "";
    int n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  // The third trial's screen is up (the pilot's first participant does T1, T2, T3, T4 with
  // instructions and training before each; trial 3 is T3): the failure lands inside a trial, not
  // in training, which renders too (a failure there also stops the session, with no attempt).
  const auto until = Clock::now() + std::chrono::seconds(240);
  while ((count(log, " recorded (") < 2 || count(items, "\"screen\":\"trial T3\"") < 1) && Clock::now() < until &&
         ::waitpid(pid, nullptr, WNOHANG) == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  { std::ofstream(flag) << "fail\n"; }
  const int at_failure = count(log, " recorded (");
  ASSERT_EQ(at_failure, 2) << slurp(log);
  EXPECT_EQ(wait_exit_within(pid, 240), 3) << slurp(log);
  const std::string text = slurp(log);
  EXPECT_NE(text.find("dtlab run: error: "), std::string::npos) << text;
  EXPECT_NE(text.find("the GL ran out of memory"), std::string::npos) << text;
  EXPECT_NE(text.find("GL_OUT_OF_MEMORY (injected"), std::string::npos) << text;
  EXPECT_NE(text.find("session stopped here: every finished trial is saved and running the same command again "
                      "resumes it"),
            std::string::npos)
      << text;
  EXPECT_NE(slurp(items).find("\"screen\":\"end\""), std::string::npos)
      << "the participant's window did not turn to the end screen";
  {
    auto r = reader(db);
    EXPECT_EQ(*r.integrity_check(), "ok");
    const auto sessions = r.sessions();
    ASSERT_EQ(sessions->size(), 1u);
    EXPECT_EQ((*sessions)[0].status, store::SessionStatus::running) << "neither finished nor abandoned";
    EXPECT_GE(r.trials()->size(), static_cast<std::size_t>(at_failure)) << "a recorded trial was lost";
  }
  fs::remove(flag);
  ASSERT_EQ(wait_exit_within(start_run(db, log, {"--script", kScript}), 300), 0) << slurp(log);
  EXPECT_EQ(outcome(db), outcome(*RunPilot::db));
  auto sessions = reader(db).sessions();
  ASSERT_EQ(sessions->size(), 1u);
  EXPECT_EQ((*sessions)[0].status, store::SessionStatus::finished);
  ASSERT_EQ((*sessions)[0].interruptions.size(), 1u) << "the failed trial's attempt is recorded";
  EXPECT_EQ((*sessions)[0].interruptions[0].position, 3);
  if (!HasFailure()) fs::remove_all(d);
}

// Real X events: xdotool types the participant's ID and age into the start screen and clicks
// "Start session" by the boxes the app reports ($DTLAB_RUN_ITEMS); the enrollment is stored.
TEST(RunWindow, RealXEventsReachTheAppLikeAPersons) {
  if (std::system("command -v xdotool >/dev/null 2>&1") != 0) GTEST_SKIP() << "xdotool is not installed";
  const fs::path d = temp_dir("xdotool");
  const fs::path db = d / "x.sqlite", log = d / "log.txt", items = d / "items.json";
  const pid_t pid = start_run(db, log, {}, {{"DTLAB_RUN_ITEMS", items.string()}});
  auto wait_for_screen = [&](const std::string& screen) -> nlohmann::json {
    const auto until = Clock::now() + std::chrono::seconds(60);
    while (Clock::now() < until) {
      const std::string text = slurp(items);
      if (!text.empty()) {
        const auto j = nlohmann::json::parse(text, nullptr, false);
        if (!j.is_discarded() && j["screen"] == screen) return j;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return {};
  };
  const auto start = wait_for_screen("start");
  ASSERT_FALSE(start.is_null()) << slurp(log);
  auto click = [&](const std::string& item) {
    const auto& b = start["items"][item];
    char cmd[256];
    std::snprintf(cmd, sizeof cmd,
                  "xdotool search --sync --name 'dtlab - Pilot' mousemove --window %%1 %d %d "
                  "click 1",
                  static_cast<int>(b[0].get<double>() + b[2].get<double>() / 2),
                  static_cast<int>(b[1].get<double>() + b[3].get<double>() / 2));
    return std::system(cmd);
  };
  ASSERT_EQ(click("Participant ID"), 0);
  ASSERT_EQ(std::system("xdotool type --delay 50 'xdo-01'"), 0);
  ASSERT_EQ(click("age"), 0);
  ASSERT_EQ(std::system("xdotool type --delay 50 '33'"), 0);
  ASSERT_EQ(click("Start session"), 0);
  EXPECT_FALSE(wait_for_screen("instructions T1").is_null()) << slurp(log);
  ::kill(pid, SIGTERM);
  wait_exit(pid);
  auto ledger = reader(db).ledger();
  ASSERT_EQ(ledger->size(), 1u);
  EXPECT_EQ((*ledger)[0].participant, "xdo-01");
  EXPECT_EQ((*ledger)[0].demographics, (store::Demographics{{"age", "33"}}));
  fs::remove_all(d);
}

}  // namespace
}  // namespace dtlab::run
