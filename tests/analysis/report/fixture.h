// Test databases for the report, written through the Store API exactly as a
// session would write them: enroll (the ledger picks the order row), the plan
// from design::make_plan, one record_trial per planned trial, questionnaire
// answers, finish. The caller decides every trial's time and answer from the
// participant and the planned trial, so published data sets can be placed as
// participant x condition means. Databases live in a fresh temporary folder
// (on tmpfs when there is one: the store's fsync per trial costs nothing there).
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "study/design/plan.h"
#include "study/store/store.h"

namespace dtlab::report::testing {

// A fresh folder, removed when the object goes away (kept when DTLAB_KEEP_TEST_DIRS=1).
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

struct Outcome {
  double time_s = 1;
  std::optional<store::Answer> answer;  // nullopt: no answer given
  store::Answer truth = store::Count{10};
  std::vector<double> frame_ms;         // per-frame times (one camera pose each); empty = not rendered
};

struct StudySpec {
  std::string protocol_text;
  std::vector<std::string> participants;  // ids, in enrollment order
  std::function<store::Demographics(size_t p)> demographics;  // optional
  // The outcome of participant p's planned trial t; nullopt stops the session there (it stays running).
  std::function<std::optional<Outcome>(size_t p, const design::PlannedTrial& t)> trial;
  std::function<std::vector<store::QuestionnaireAnswer>(size_t p)> questionnaire;  // optional
  bool allow_protocol_change = false;  // the database exists under another design: record this one beside it
  std::optional<store::DisplayInfo> display;  // recorded for every session; its rate counts late frames (else 60 Hz)
};

// Writes the study into the database at `path` (new, or of the same design, or any design when
// allowed); fails the test (and throws) on any store error.
void build_study(const std::string& path, const StudySpec& spec);

// The text of a file of the repository (DTLAB_SOURCE_DIR-relative path).
std::string source_file(const std::string& relative);

// The level of `factor` in a planned trial ("" if absent).
std::string level(const design::PlannedTrial& t, const std::string& factor);

}  // namespace dtlab::report::testing
