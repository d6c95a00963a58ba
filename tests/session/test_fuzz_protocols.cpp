// A seeded protocol fuzzer: kMutants mutants of the shipped protocols
// (protocols/*.toml), each made by one to three edits of its lines: a value
// set to a boundary or an extreme (documented min and max, one beyond them,
// 0, -1, 1e6, 1e308, nan, inf, huge integers), a value of another type, a key
// or a whole table deleted or duplicated, a table copied under a new name, a
// scene key added to a task, levels and names shuffled. Each mutant runs in
// its own process under a watchdog (kSecondsPerMutant), and must not crash or
// hang. Every mutant that passes the whole validation (load_protocol and
// session::validate_runnable) must then plan (a few enrollment indexes) and
// generate, for every distinct (scenario, task, rendering) of participant 0's
// plan and for two more trials, the trial's scene and its frame settings at
// every checked viewport, and the depth tests' views: "valid" means runnable.
// Prints how many mutants were accepted and how long the run took; a failing
// mutant is written to a file named in the failure. DTLAB_FUZZ_SEED and
// DTLAB_FUZZ_MUTANTS run other or more mutants (the default is fixed).
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "study/common/random.h"
#include "study/design/design.h"
#include "study/protocol/limits.h"
#include "study/session/mapping.h"
#include "study/session/runnable.h"
#include "tests/common/run_cli.h"

namespace dtlab::session {
namespace {

constexpr int kMutants = 400;
constexpr std::uint64_t kSeed = 20261212;
constexpr int kSecondsPerMutant = 60;

// The mutants' stream: dtlab's own generator (study/common/random.h), unbiased bounded draws.
using Rng = Random<SplitMix64>;

template <class T>
const T& pick(Rng& rng, const std::vector<T>& v) {  // a uniformly chosen element of a non-empty v
  return v[rng.below(v.size())];
}

using dtlab::test::read_text;

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string t;
  for (const auto& l : lines) t += l + "\n";
  return t;
}

// Lines of `key = value` outside multi-line strings; headers `[...]`.
bool is_header(const std::string& l) { return !l.empty() && l[0] == '['; }
std::string key_of(const std::string& l) {
  if (l.empty() || l[0] == '#' || l[0] == '[' || l[0] == ' ') return "";
  const std::size_t eq = l.find(" = ");
  return eq == std::string::npos ? "" : l.substr(0, eq);
}
std::vector<std::size_t> key_lines(const std::vector<std::string>& lines) {
  std::vector<std::size_t> out;
  bool in_string = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!in_string && !key_of(lines[i]).empty()) out.push_back(i);
    for (std::size_t at = lines[i].find("\"\"\""); at != std::string::npos; at = lines[i].find("\"\"\"", at + 3))
      in_string = !in_string;
  }
  return out;
}
std::vector<std::size_t> header_lines(const std::vector<std::string>& lines) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (is_header(lines[i])) out.push_back(i);
  return out;
}

std::string number_text(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (v == std::floor(v) && std::fabs(v) < 9e15) return std::to_string(static_cast<long long>(v));
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// Values within the documented range of `key` (its ends and middle), or of its kind (enumerations).
std::vector<std::string> documented_values(const std::string& key) {
  std::vector<std::string> v;
  for (const protocol::limits::Documented& d : protocol::limits::documented()) {
    if (d.key != key) continue;
    const bool real = key == "extent" || key == "cell_size" || key == "time_limit_s" || key == "object_radius" ||
                      key == "target_ratio" || key == "a0" || key == "aT";
    const bool pair = key == "object_radius" || key == "target_ratio" || key == "grid" || key == "count_range" ||
                      key == "scale";
    for (double x : {d.min, d.max, real ? (d.min + d.max) / 2 : std::floor((d.min + d.max) / 2)}) {
      std::string t = number_text(x);
      if (real && t.find_first_of(".en") == std::string::npos) t += ".0";
      if (!pair) {
        v.push_back(t);
        continue;
      }
      v.push_back("[" + t + ", " + t + "]");
      v.push_back("[" + number_text(d.min) + (real && d.min == std::floor(d.min) ? ".0" : "") + ", " + t + "]");
    }
  }
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> enums = {
      {{"method"}, {"\"standard\"", "\"dt-seed\"", "\"dt-fast\"", "\"reference\"", "\"vdt\""}},
      {{"kind"}, {"\"abstract\"", "\"walkthrough\""}},
      {{"type"},
       {"\"count-targets\"", "\"identify-letter\"", "\"find-unique\"", "\"count-kind\"", "\"rating\"", "\"choice\"",
        "\"depth-test\""}},
      {{"scheme", "nested_scheme"},
       {"\"latin-square\"", "\"williams\"", "\"full-permutation\"", "\"random\"", "\"fixed\""}},
      {{"unit"}, {"\"conditions\"", "\"blocks\""}},
      {{"mask_shape"}, {"\"outline\"", "\"circle\"", "\"ellipse\""}},
      {{"mode"}, {"\"passive\"", "\"active\""}},
      {{"role"}, {"\"none\"", "\"scenario\"", "\"rendering\""}},
      {{"scenario", "rendering", "factor", "block_factor"},
       {"\"abstract\"", "\"walkthrough\"", "\"on\"", "\"off\"", "\"transparency\"", "\"scenario\""}},
      {{"letters"}, {"[\"C\"]", "[\"Y\", \"X\"]", "[\"C\", \"K\", \"R\", \"X\", \"Y\"]"}},
      {{"object_kinds"},
       {"[\"pet\"]", "[\"vehicle\", \"pet\"]", "[\"furniture\"]", "[\"torus\", \"box\", \"cone\", \"sphere\"]"}},
      {{"levels"}, {"[\"on\", \"off\"]", "[\"walkthrough\", \"abstract\"]", "[\"off\", \"on\", \"half\"]"}},
      {{"per"}, {"[]", "[\"transparency\"]", "[\"scenario\"]"}},
  };
  for (const auto& [keys, values] : enums)
    if (std::find(keys.begin(), keys.end(), key) != keys.end()) v.insert(v.end(), values.begin(), values.end());
  return v;
}

// Values outside the documented range of `key` (one step beyond each end) and extremes of every type.
std::vector<std::string> wild_values(const std::string& key) {
  std::vector<std::string> v;
  for (const protocol::limits::Documented& d : protocol::limits::documented()) {
    if (d.key != key) continue;
    const bool integer = d.min == std::floor(d.min) && d.max == std::floor(d.max);
    const double step = integer ? 1.0 : std::max(1e-9, std::fabs(d.max) * 1e-12);
    for (double x : {d.min - step, d.max + step}) {
      v.push_back(number_text(x));
      v.push_back("[" + number_text(x) + ", " + number_text(d.max) + "]");
    }
  }
  for (const char* x : {"0", "-1", "1", "2", "3", "1e6", "1e308", "-1e308", "nan", "inf", "-inf", "2147483648",
                        "9223372036854775807", "1.5", "0.001", "\"text\"", "\"\"", "true", "[]", "[1]", "[1, 2, 3]",
                        "[0.5, 0.5]", "[2, 2]", "[64, 64]", "{}", "\"x-ray\"", "1979-05-27"})
    v.emplace_back(x);
  return v;
}

// A value for `key`: mostly within its documented range, sometimes anything.
std::string value_for(const std::string& key, Rng& rng) {
  const std::vector<std::string> in = documented_values(key);
  if (!in.empty() && rng.below(4) != 0) return pick(rng, in);
  return pick(rng, wild_values(key));
}

// A key = value line for a key a task or scenario may set, with a boundary value.
std::string scene_key_line(Rng& rng) {
  static const std::vector<std::string> keys = {"objects", "extent", "object_radius", "target_ratio", "letters",
                                                "grid", "cell_size", "count_range", "object_kinds", "trials"};
  const std::string& key = pick(rng, keys);
  return key + " = " + value_for(key, rng);
}

// One edit of `lines`; returns what it did.
std::string edit(std::vector<std::string>& lines, Rng& rng) {
  const auto keys = key_lines(lines);
  const auto headers = header_lines(lines);
  switch (rng.below(12)) {
    case 0:
    case 1:
    case 2:
    case 10:
    case 11: {  // a value to a boundary, an extreme, or another type
      const std::size_t i = pick(rng, keys);
      const std::string key = key_of(lines[i]);
      const std::string old = lines[i];
      lines[i] = key + " = " + value_for(key, rng);
      return "line " + std::to_string(i + 1) + ": '" + old + "' -> '" + lines[i] + "'";
    }
    case 3: {  // delete a key
      const std::size_t i = pick(rng, keys);
      const std::string old = lines[i];
      lines.erase(lines.begin() + static_cast<long>(i));
      return "deleted line " + std::to_string(i + 1) + " '" + old + "'";
    }
    case 4: {  // duplicate a key
      const std::size_t i = pick(rng, keys);
      lines.insert(lines.begin() + static_cast<long>(i), lines[i]);
      return "duplicated line " + std::to_string(i + 1) + " '" + lines[i] + "'";
    }
    case 5: {  // delete a table
      const std::size_t h = rng.below(headers.size());
      const std::size_t end = h + 1 < headers.size() ? headers[h + 1] : lines.size();
      const std::string old = lines[headers[h]];
      lines.erase(lines.begin() + static_cast<long>(headers[h]), lines.begin() + static_cast<long>(end));
      return "deleted table " + old;
    }
    case 6: {  // copy a table under a new name (a new task, item, level...) or the same (duplicate)
      const std::size_t h = rng.below(headers.size());
      const std::size_t end = h + 1 < headers.size() ? headers[h + 1] : lines.size();
      std::vector<std::string> copy(lines.begin() + static_cast<long>(headers[h]), lines.begin() + static_cast<long>(end));
      const std::string old = copy[0];
      if (rng.below(3) != 0) copy[0].insert(copy[0].rfind(']'), "x");
      lines.insert(lines.end(), copy.begin(), copy.end());
      return "copied table " + old + " as " + copy[0];
    }
    case 7: {  // a scene key (or trials) added to a scenario or task, or pairs to a questionnaire item
      std::vector<std::size_t> tables;
      for (std::size_t h : headers)
        if (lines[h].rfind("[scenarios.", 0) == 0 || lines[h].rfind("[questionnaire.", 0) == 0) tables.push_back(h);
      if (tables.empty()) return "nothing";
      const std::size_t h = pick(rng, tables);
      const std::string line =
          lines[h].rfind("[questionnaire.", 0) == 0 ? "pairs = " + value_for("pairs", rng) : scene_key_line(rng);
      lines.insert(lines.begin() + static_cast<long>(h) + 1, line);
      return "added '" + line + "' to " + lines[h];
    }
    case 8: {  // reverse an array of names (levels, letters, kinds...) or swap two adjacent tables' first lines
      for (int tries = 0; tries < 20; ++tries) {
        const std::size_t i = pick(rng, keys);
        const std::size_t open = lines[i].find(" = [\""), close = lines[i].rfind("\"]");
        if (open == std::string::npos || close == std::string::npos) continue;
        std::vector<std::string> items;
        std::stringstream in(lines[i].substr(open + 4, close - open - 3));
        for (std::string item; std::getline(in, item, ',');) items.push_back(item.substr(item.find('"')));
        std::string out = key_of(lines[i]) + " = [";
        for (std::size_t k = items.size(); k-- > 0;) out += items[k] + (k ? ", " : "");
        const std::string old = lines[i];
        lines[i] = out + "]";
        return "reversed '" + old + "' -> '" + lines[i] + "'";
      }
      return "nothing";
    }
    default: {  // move a whole table to the end (file order of factors, tasks, items)
      const std::size_t h = rng.below(headers.size());
      const std::size_t end = h + 1 < headers.size() ? headers[h + 1] : lines.size();
      std::vector<std::string> block(lines.begin() + static_cast<long>(headers[h]), lines.begin() + static_cast<long>(end));
      lines.erase(lines.begin() + static_cast<long>(headers[h]), lines.begin() + static_cast<long>(end));
      lines.insert(lines.end(), block.begin(), block.end());
      return "moved table " + block[0] + " to the end";
    }
  }
}

// What one mutant did; empty `failures` = as it should be.
struct Verdict {
  bool loaded = false, accepted = false;
  std::string failures;
};

void fail(Verdict& v, const std::string& what) { v.failures += what + "\n"; }

// The checks of one mutant (in the child process).
Verdict check(const std::string& text) {
  Verdict v;
  const auto diags = protocol::validate_protocol_text(text, "mutant.toml");
  for (const auto& d : diags)
    if (d.severity == Severity::error && (d.where.line < 1 || d.where.file != "mutant.toml"))
      fail(v, "reader error without a line: " + d.to_string());
  auto p = protocol::load_protocol_text(text, "mutant.toml");
  if (p.ok() == protocol::has_errors(diags)) fail(v, "load_protocol and validate disagree");
  if (!p.ok()) return v;
  v.loaded = true;
  const auto runnable = validate_runnable(*p);
  for (const auto& d : runnable)
    if (d.where.line < 1 || d.where.file != "mutant.toml" || d.where.field.empty())
      fail(v, "runnable error without a line or field: " + d.to_string());
  if (protocol::has_errors(runnable)) return v;
  v.accepted = true;

  // Accepted: it must run. Plans for a few enrollment indexes.
  const int rows = design::order_rows(*p);
  std::set<int> indexes{0, 1, std::max(0, std::min(p->participants, rows) - 1)};
  for (int k : indexes) {
    const design::Plan plan = design::make_plan(*p, k);
    if (plan.trials.empty()) fail(v, "participant " + std::to_string(k) + " has no trials");
  }
  // Participant 0: every distinct (scenario, task, rendering) once, and two more trials.
  const design::Plan plan = design::make_plan(*p, 0);
  std::set<std::tuple<const void*, const void*, const void*>> seen;
  std::vector<const design::PlannedTrial*> sample;
  for (const design::PlannedTrial& t : plan.trials) {
    auto setup = trial_setup(*p, t);
    if (!setup) {
      fail(v, "trial_setup, trial " + std::to_string(t.position) + ": " + setup.error().to_string());
      continue;
    }
    if (seen.emplace(setup->scenario, setup->task, setup->rendering).second) sample.push_back(&t);
  }
  sample.push_back(&plan.trials.back());
  sample.push_back(&plan.trials[plan.trials.size() / 2]);
  for (const design::PlannedTrial* t : sample) {
    auto setup = trial_setup(*p, *t);
    if (!setup) continue;
    auto scene = trial_scene(*setup, *t);
    if (!scene) fail(v, "scene of trial " + std::to_string(t->position) + ": " + scene.error().to_string());
    for (const Viewport& vp : checked_viewports()) {
      auto frame = frame_settings(*p, *setup->rendering, vp.width, vp.height);
      if (!frame) fail(v, "frame settings of trial " + std::to_string(t->position) + ": " + frame.error().to_string());
    }
  }
  // The questionnaire of participant 0 at the simulation's viewport.
  std::vector<Question> questions = expand_questionnaire(*p);
  for (const protocol::QuestionnaireItem& item : p->questionnaire) {
    if (item.type->name != "depth-test") continue;
    auto key = depth_test_view(*p, item, 0, Viewport{160, 120}, questions);
    if (!key) fail(v, "depth test: " + key.error().to_string());
  }
  return v;
}

// Runs check() in a child process; a crash or a hang is a failure of its own.
Verdict check_isolated(const std::string& text) {
  int fds[2];
  if (::pipe(fds) != 0) return {false, false, "pipe failed"};
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    const Verdict v = check(text);
    const std::string out = std::string(1, v.loaded ? 'L' : '-') + (v.accepted ? 'A' : '-') + v.failures;
    std::size_t done = 0;
    while (done < out.size()) {
      const ssize_t w = ::write(fds[1], out.data() + done, out.size() - done);
      if (w <= 0) break;
      done += static_cast<std::size_t>(w);
    }
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string out;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kSecondsPerMutant);
  bool hung = false;
  for (;;) {
    pollfd pfd{fds[0], POLLIN, 0};
    const int ms = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
    if (ms <= 0 || ::poll(&pfd, 1, ms) == 0) {
      hung = true;
      break;
    }
    char buf[4096];
    const ssize_t r = ::read(fds[0], buf, sizeof buf);
    if (r <= 0) break;
    out.append(buf, static_cast<std::size_t>(r));
  }
  ::close(fds[0]);
  if (hung) ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  Verdict v;
  if (hung) return {false, false, "no verdict after " + std::to_string(kSecondsPerMutant) + " s: a hang"};
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || out.size() < 2)
    return {false, false, "the checks crashed (" + (WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                                        : "exit " + std::to_string(WEXITSTATUS(status))) +
                              ")"};
  v.loaded = out[0] == 'L';
  v.accepted = out[1] == 'A';
  v.failures = out.substr(2);
  return v;
}

TEST(ProtocolFuzz, AcceptedMutantsRunAndNoneCrashesOrHangs) {
  const std::vector<std::pair<std::string, std::string>> bases = {
      {"elmqvist2008.toml", read_text(DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml")},
      {"pilot.toml", read_text(DTLAB_SOURCE_DIR "/protocols/pilot.toml")},
  };
  // DTLAB_FUZZ_SEED and DTLAB_FUZZ_MUTANTS explore further (a failure names its mutant's file).
  const char* seed_env = std::getenv("DTLAB_FUZZ_SEED");
  const char* count_env = std::getenv("DTLAB_FUZZ_MUTANTS");
  const std::uint64_t seed = seed_env ? std::strtoull(seed_env, nullptr, 10) : kSeed;
  const int mutants = count_env ? std::atoi(count_env) : kMutants;
  Rng rng(seed);
  int loaded = 0, accepted = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int m = 0; m < mutants; ++m) {
    const auto& [name, text] = bases[rng.below(bases.size())];
    std::vector<std::string> lines = split_lines(text);
    std::string how;
    const int first = static_cast<int>(rng.below(2));  // one draw per statement: argument order is unspecified
    const int edits = 1 + first * static_cast<int>(1 + rng.below(2));  // 1, 1, 2, 3
    for (int e = 0; e < edits; ++e) how += (e ? "; " : "") + edit(lines, rng);
    const std::string mutant = joined(lines);
    const Verdict v = check_isolated(mutant);
    loaded += v.loaded;
    accepted += v.accepted;
    if (!v.failures.empty()) {
      const std::string file = ::testing::TempDir() + "dtlab_mutant_" + std::to_string(m) + ".toml";
      std::ofstream(file, std::ios::binary) << mutant;
      ADD_FAILURE() << "mutant " << m << " of " << name << " (" << how << "; written to " << file << "):\n"
                    << v.failures;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("protocol fuzzer: %d mutants (seed %llu), %d read without error, %d accepted as runnable, %.1f s\n",
              mutants, static_cast<unsigned long long>(seed), loaded, accepted, seconds);
  // The mutants must exercise both sides: many accepted (they are the ones that must run), many not.
  EXPECT_GT(accepted, mutants / 5);
  EXPECT_LT(accepted, mutants * 4 / 5);
}

}  // namespace
}  // namespace dtlab::session
