// The study data the store tests and benchmarks share: a 2 x 2 study, a
// synthetic plan (the design stage is tested on its own; the store must not
// depend on it) and a deterministic trial record per (seed, participant,
// position). Pure functions; no test framework, no database.
#pragma once
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "study/common/hash.h"
#include "study/design/plan.h"
#include "study/store/store.h"

namespace dtlab::store::testing {

inline StudyInfo study_info(const std::string& text = "id = \"test2x2\"\n# protocol text\n") {
  StudyInfo s;
  s.protocol_id = "test2x2";
  s.protocol_text = text;
  s.protocol_sha256 = sha256_hex(text);
  s.software_version = "dtlab test";
  s.order_rows = 4;
  s.factors = {"transparency", "scenario"};
  return s;
}

// Four conditions in the order of `row` (a cyclic Latin square), `per`
// trials per condition; tasks T1 (count), T2 (letter), T3 (position) cycle
// with the position.
inline design::Plan make_plan(int index, int order_row, int per = 3) {
  static const char* tr[] = {"off", "on", "off", "on"};
  static const char* sc[] = {"ABSTRACT", "ABSTRACT", "WALKTHROUGH", "WALKTHROUGH"};
  static const char* tasks[] = {"T1", "T2", "T3"};
  design::Plan p;
  p.protocol_id = "test2x2";
  p.index = index;
  p.order_row = order_row;
  int pos = 0;
  for (int b = 0; b < 4; ++b) {
    const int c = (order_row + b) % 4;
    for (int k = 0; k < per; ++k) {
      design::PlannedTrial t;
      t.position = ++pos;
      t.block = b + 1;
      t.levels = {{"transparency", tr[c]}, {"scenario", sc[c]}};
      t.task = tasks[(pos - 1) % 3];
      t.trial = k / 3 + 1;
      t.seed = mix64(static_cast<std::uint64_t>(index), static_cast<std::uint64_t>(pos));
      t.method = c % 2 ? "dt-seed" : "standard";
      t.practice = false;
      p.trials.push_back(std::move(t));
    }
  }
  return p;
}

inline bool same_trial(const design::PlannedTrial& a, const design::PlannedTrial& b) {
  return a.position == b.position && a.block == b.block && a.levels == b.levels && a.task == b.task &&
         a.trial == b.trial && a.seed == b.seed && a.method == b.method && a.practice == b.practice;
}

inline std::chrono::system_clock::time_point at_ms(std::int64_t ms) {
  return std::chrono::system_clock::time_point(std::chrono::milliseconds(ms));
}

// The record a simulated participant produces for (seed, trial); `frames`
// poses (default: 200 + a seed-dependent number below 800), on a display of
// `refresh_hz` (nullopt: unknown).
inline TrialRecord make_record(std::uint64_t seed, const design::PlannedTrial& t, std::optional<int> frames = {},
                               std::optional<double> refresh_hz = {}) {
  TrialRecord r;
  const std::uint64_t h = mix64(seed, t.seed);
  r.position = t.position;
  r.scene_hash = sha256_hex("scene " + std::to_string(t.seed));
  if (t.task == "T1") {
    r.truth = Count{20 + static_cast<std::int64_t>(h % 20)};
    r.answer = Count{20 + static_cast<std::int64_t>((h >> 8) % 20)};
  } else if (t.task == "T2") {
    r.truth = Letter{"K"};
    r.answer = Letter{(h >> 3) % 2 ? "K" : "X"};
  } else {
    r.truth = Position{static_cast<double>(h % 97) - 40.25, 12.5};
    r.answer = Position{static_cast<double>((h >> 7) % 97) - 40.25, -3.75};
  }
  r.completion_s = 5.0 + static_cast<double>(h % 6000) / 100.0;
  r.started_at = at_ms(1'700'000'000'000LL + t.position * 100'000LL);
  r.ended_at = r.started_at + std::chrono::milliseconds(static_cast<std::int64_t>(r.completion_s * 1000));
  const int n = frames ? *frames : 200 + static_cast<int>(h % 800);
  std::vector<double> ms;
  for (int i = 0; i < n; ++i) {
    const double fi = i;
    ms.push_back(16.0 + static_cast<double>((h >> (i % 50)) % 7));
    r.poses.push_back(CameraPose{fi / 60.0, fi * 0.5, 1.7, -fi, 0.01 * fi, -0.001 * fi});
  }
  r.frames = frame_stats(ms, refresh_hz);
  for (int i = 0; i < 20; ++i)
    r.events.push_back(InputEvent{i * 0.25, i % 2 ? InputEvent::Kind::key_up : InputEvent::Kind::key_down,
                                  i % 3 ? "Up" : "Left, \"quoted\"", static_cast<double>(i), 2.0 * i});
  return r;
}

}  // namespace dtlab::store::testing
