// `dtlab copy` and store::copy_study into an empty database: a whole study
// from one engine to the other and back, every row of every table as it was
// (compared through the engines' own C APIs) and the exports byte-identical;
// the same database, a missing one and one that is not a study are refused,
// and a failed copy into a new file leaves no file. Merging is
// test_merge.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "study/store/copy.h"
#include "study/store/read.h"
#include "tests/common/run_cli.h"
#include "tests/store/copy_fixtures.h"

namespace dtlab::store {
namespace {

using namespace dtlab::store::testing;

class Copy : public OnBothBackends {
 protected:
  void SetUp() override {
    OnBothBackends::SetUp();
    DTLAB_SKIP_WITHOUT_SERVER(Backend::postgresql);  // a copy between engines needs both
  }
  std::string other(const std::string& name) const {
    return new_study(pg() ? Backend::sqlite : Backend::postgresql, dir_.path(), name);
  }
};
DTLAB_ON_BOTH_BACKENDS(Copy);

TEST_P(Copy, EveryRowOfEveryTableToTheOtherEngineAndBack) {
  const std::string src = study("src"), there = other("there"), back = study("back");
  write_rich_study(src);
  auto first = copy_study(src, there);
  ASSERT_TRUE(first) << first.error().to_string();
  EXPECT_FALSE(first->merged);
  EXPECT_EQ(first->participants, 6);
  EXPECT_EQ(first->trials, 4 + 3 + 1 + 4);
  EXPECT_EQ(first->consents, 2);
  EXPECT_EQ(first->withdrawals, 2);
  EXPECT_EQ(first->screens, 4 + 2);  // every session's instructions, the finished ones' debriefs
  auto second = copy_study(there, back);
  ASSERT_TRUE(second) << second.error().to_string();

  RawDb a(src), b(there), c(back);
  for (const auto& [name, order] : kTables) {
    const auto want = table(a, name, order);
    EXPECT_FALSE(want.empty()) << name << ": the study should exercise every table";
    EXPECT_EQ(table(b, name, order), want) << name << " differs after the copy to the other engine";
    EXPECT_EQ(table(c, name, order), want) << name << " differs after the copy back";
  }
  EXPECT_EQ(b.integrity(), "ok");
  EXPECT_EQ(c.integrity(), "ok");
  // The export is the same bytes from all three, and the copies behave as studies: a reader sees
  // the resumed session, the interruption, the pause and the decisions.
  const std::string csv = exported(src);
  EXPECT_EQ(exported(there), csv);
  EXPECT_EQ(exported(back), csv);
  auto r = StudyReader::open(there);
  ASSERT_TRUE(r);
  auto sessions = r->sessions();
  ASSERT_EQ(sessions->size(), 4u);
  EXPECT_EQ((*sessions)[1].resumes.size(), 1u);
  EXPECT_EQ((*sessions)[0].interruptions.size(), 1u);
  EXPECT_DOUBLE_EQ((*sessions)[0].paused_s(), 7.25);
  EXPECT_EQ((*sessions)[2].status, SessionStatus::abandoned);
  ASSERT_EQ((*sessions)[1].displays.size(), 2u);  // the start and the resume
  EXPECT_EQ((*sessions)[1].displays[0].info.monitor, kWindow.monitor);
  EXPECT_EQ((*sessions)[1].displays[0].info.refresh_hz, kWindow.refresh_hz);
  EXPECT_EQ((*sessions)[1].displays[1].info.kind, "headless");
  EXPECT_FALSE((*sessions)[1].displays[1].info.refresh_hz);
  auto trials = r->trials("P1");
  ASSERT_EQ(trials->size(), 4u);
  EXPECT_EQ((*trials)[0].frames.refresh_hz, kWindow.refresh_hz);
  EXPECT_FALSE((*trials)[1].frames.refresh_hz);
  EXPECT_TRUE((*trials)[1].frames.first_ms && (*trials)[1].frames.late);
  EXPECT_TRUE((*sessions)[3].withdrawn);  // P4
  EXPECT_EQ((*sessions)[3].status, SessionStatus::finished);
  EXPECT_EQ(r->withdrawals()->size(), 2u);
  EXPECT_EQ(r->screens("P1")->size(), 2u);
  // And the copy is a study one can go on writing to: P5 starts there.
  Store s = open_ok(there, study_info("id = \"test2x2\"\n# second wording\n"));
  auto e = s.lookup("P5");
  ASSERT_TRUE(e);
  EXPECT_TRUE(s.begin_session("P5", make_plan(e->index, e->order_row, 1)));
}

TEST_P(Copy, RefusesTheSameDatabaseAndWhatIsNotAStudy) {
  const std::string src = study("src");
  write_rich_study(src);
  auto same = copy_study(src, src);
  ASSERT_FALSE(same);
  EXPECT_EQ(same.error().kind, ErrorKind::invalid_input);
  EXPECT_NE(same.error().message.find("same database"), std::string::npos) << same.error().to_string();
  auto missing = copy_study(dir_.file("missing.sqlite"), other("x"));
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().kind, ErrorKind::not_found);
  const std::string junk = dir_.file("junk.sqlite");
  std::ofstream(junk) << std::string(4096, 'j');
  auto into_junk = copy_study(src, junk);
  ASSERT_FALSE(into_junk);
  EXPECT_EQ(dtlab::test::read_text(junk), std::string(4096, 'j'));  // untouched
  // A failed copy into a new file leaves no file behind.
  const std::string fresh = dir_.file("fresh.sqlite");
  auto from_junk = copy_study(junk, fresh);
  ASSERT_FALSE(from_junk);
  EXPECT_FALSE(std::filesystem::exists(fresh));
}

}  // namespace
}  // namespace dtlab::store
