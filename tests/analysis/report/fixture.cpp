// Building test study databases through the Store API; see fixture.h.
#include "tests/analysis/report/fixture.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "study/common/hash.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"

namespace dtlab::report::testing {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& what, const Error& e) {
  ADD_FAILURE() << what << ": " << e.to_string();
  throw std::runtime_error(what);
}

}  // namespace

TempDir::TempDir() {
  static int counter = 0;
  const fs::path base = fs::exists("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
  path_ = base / ("dtlab-report-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(path_);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  // DTLAB_KEEP_TEST_DIRS=1 keeps the databases and reports for a look in a browser.
  if (const char* keep = std::getenv("DTLAB_KEEP_TEST_DIRS"); keep && *keep == '1') {
    std::fprintf(stderr, "kept %s\n", path_.string().c_str());
    return;
  }
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string source_file(const std::string& relative) {
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/" + relative, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + relative);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string level(const design::PlannedTrial& t, const std::string& factor) {
  for (const auto& [f, l] : t.levels)
    if (f == factor) return l;
  return "";
}

void build_study(const std::string& path, const StudySpec& spec) {
  auto proto = protocol::load_protocol_text(spec.protocol_text, "fixture.toml");
  if (!proto) fail("loading the fixture protocol", proto.error());
  store::StudyInfo info;
  info.protocol_id = proto->id;
  info.protocol_text = proto->source_text;
  info.protocol_sha256 = proto->sha256;
  info.design_sha256 = protocol::design_sha256(*proto);
  info.software_version = "dtlab test";
  info.order_rows = design::order_rows(*proto);
  for (const auto& f : proto->factors) info.factors.push_back(f.name);
  store::OpenOptions options;
  options.allow_protocol_change = spec.allow_protocol_change;
  auto opened = store::Store::open(path, info, options);
  if (!opened) fail("opening " + path, opened.error());
  store::Store& s = *opened;
  const auto t0 = std::chrono::system_clock::now();
  for (size_t p = 0; p < spec.participants.size(); ++p) {
    auto e = s.enroll(spec.participants[p], spec.demographics ? spec.demographics(p) : store::Demographics{});
    if (!e) fail("enrolling " + spec.participants[p], e.error());
    const design::Plan plan = design::make_plan(*proto, e->index, e->order_row);
    auto session = s.begin_session(spec.participants[p], plan);
    if (!session) fail("starting a session", session.error());
    if (spec.display)
      if (auto st = s.record_display(*session, *spec.display); !st) fail("recording the display", st.error());
    bool complete = true;
    for (const auto& t : plan.trials) {
      const auto o = spec.trial(p, t);
      if (!o) {
        complete = false;
        break;
      }
      store::TrialRecord r;
      r.position = t.position;
      r.scene_hash = sha256_hex("scene " + std::to_string(t.seed));
      r.answer = o->answer;
      r.truth = o->truth;
      r.completion_s = o->time_s;
      r.started_at = t0 + std::chrono::seconds(100 * t.position);
      r.ended_at = r.started_at + std::chrono::milliseconds(static_cast<long long>(o->time_s * 1000));
      r.frames = store::frame_stats(o->frame_ms, spec.display ? spec.display->refresh_hz : 60.0);  // default: 60 Hz
      for (size_t f = 0; f < o->frame_ms.size(); ++f) {
        store::CameraPose pose;
        pose.t_s = 0.01 * static_cast<double>(f);
        r.poses.push_back(pose);
      }
      if (auto st = s.record_trial(*session, r); !st) fail("recording a trial", st.error());
    }
    if (complete)
      if (auto st = s.finish_session(*session); !st) fail("finishing a session", st.error());
    if (spec.questionnaire) {
      const auto answers = spec.questionnaire(p);
      if (!answers.empty())
        if (auto st = s.record_questionnaire(*session, answers); !st) fail("recording the questionnaire", st.error());
    }
  }
}

}  // namespace dtlab::report::testing
