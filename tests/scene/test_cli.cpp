// `dtlab scene`: the JSON contract, the text summary, OBJ output, and exit
// codes for a task of the wrong scene kind (1), a bad command line (2) and an
// unwritable OBJ path (3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct Outcome {
  int status;
  std::string out;  // stdout and stderr together
};

Outcome dtlab(const std::string& args) {
  const std::string cmd = std::string(DTLAB_BINARY) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int rc = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, out};
}

TEST(SceneCommand, JsonHasTheDocumentedNames) {
  const Outcome r = dtlab("scene --scene abstract --task T1 --seed 42 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"scene", "task", "seed", "hash", "objects", "targets", "triangles", "answer"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["scene"], "abstract");
  EXPECT_EQ(j["task"], "T1");
  EXPECT_EQ(j["seed"], 42);
  int total = 0;
  for (const auto& [kind, n] : j["objects"].items()) total += n.get<int>();
  EXPECT_EQ(total, 200);
  EXPECT_EQ(j["answer"]["count"], j["targets"]);
  EXPECT_GE(j["triangles"].get<int>(), 10000);
}

// The start camera, which a protocol's lens `distance` is measured against (docs/protocol.md). The
// orbit distance is docs/scene.md's D = margin R / sin(fov_y / 2) with margin 1.05, fov_y 45 deg
// and R = 100 sqrt(3) / 2 the radius of the 100-unit cube's circumscribed sphere: 237.617...
TEST(SceneCommand, PrintsTheStartCamera) {
  const auto a = nlohmann::json::parse(dtlab("scene --scene abstract --task T1 --seed 42 --json").out);
  ASSERT_TRUE(a.contains("camera"));
  EXPECT_EQ(a["camera"]["mode"], "orbit");
  const double d = 1.05 * (100 * std::sqrt(3.0) / 2) / std::sin(22.5 * M_PI / 180);
  EXPECT_NEAR(a["camera"]["distance"].get<double>(), d, 1e-3 * d);
  EXPECT_NEAR(a["camera"]["fov_y_deg"].get<double>(), 45.0, 1e-4);
  EXPECT_EQ(a["camera"]["target"].size(), 3u);
  const auto w = nlohmann::json::parse(dtlab("scene --scene walkthrough --task T3 --seed 1 --json").out);
  EXPECT_EQ(w["camera"]["mode"], "walk");
  EXPECT_EQ(w["camera"]["position"].size(), 3u);
  EXPECT_FALSE(w["camera"].contains("distance"));
  EXPECT_NEAR(w["camera"]["fov_y_deg"].get<double>(), 60.0, 1e-4);
  const Outcome text = dtlab("scene --scene abstract --task T1 --seed 42");
  char want[64];
  std::snprintf(want, sizeof want, "at distance %.4g", d);
  EXPECT_NE(text.out.find(std::string("camera     orbit around")), std::string::npos) << text.out;
  EXPECT_NE(text.out.find(want), std::string::npos) << want << " in:\n" << text.out;
}

TEST(SceneCommand, AnswersPerTask) {
  const auto t2 = nlohmann::json::parse(dtlab("scene --scene abstract --task T2 --seed 1 --json").out);
  EXPECT_NE(std::string("CKRXY").find(t2["answer"]["letter"].get<std::string>()), std::string::npos);
  const auto t3 = nlohmann::json::parse(dtlab("scene --scene walkthrough --task T3 --seed 1 --json").out);
  EXPECT_EQ(t3["objects"][t3["answer"]["kind"].get<std::string>()], 1);
  EXPECT_TRUE(t3["answer"].contains("x") && t3["answer"].contains("z"));
  EXPECT_EQ(t3["targets"], 50);
  const auto t4 = nlohmann::json::parse(dtlab("scene --scene walkthrough --task T4 --seed 1 --json").out);
  EXPECT_EQ(t4["objects"][t4["answer"]["kind"].get<std::string>()], t4["answer"]["count"]);
}

TEST(SceneCommand, TextSummaryAndObjFiles) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Outcome r = dtlab("scene --scene walkthrough --task T4 --seed 7 --obj " + (dir / "w.obj").string());
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* line : {"hash ", "objects ", "targets ", "triangles ", "answer ", "count "})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << " missing in:\n" << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "w.obj"));
  EXPECT_TRUE(std::filesystem::exists(dir / "w.mtl"));
  std::filesystem::remove_all(dir);
}

struct Failure {
  const char* name;
  const char* args;
  int status;
  const char* says;
};

void PrintTo(const Failure& f, std::ostream* os) { *os << f.name; }  // readable ctest names

class SceneCommandFails : public ::testing::TestWithParam<Failure> {};

TEST_P(SceneCommandFails, WithTheDocumentedStatus) {
  const Outcome r = dtlab(GetParam().args);
  EXPECT_EQ(r.status, GetParam().status) << r.out;
  EXPECT_NE(r.out.find(GetParam().says), std::string::npos) << r.out;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SceneCommandFails,
    ::testing::Values(Failure{"AbstractWithT3", "scene --scene abstract --task T3 --seed 1", 1, "T3 belongs to walkthrough scenes, not abstract"},
                      Failure{"WalkthroughWithT1", "scene --scene walkthrough --task T1 --seed 1 --json", 1, "task"},
                      Failure{"UnknownScene", "scene --scene city --task T1 --seed 1", 2, "--scene"},
                      Failure{"UnknownTask", "scene --scene abstract --task T9 --seed 1", 2, "--task"},
                      Failure{"NegativeSeed", "scene --scene abstract --task T1 --seed -4", 2, "--seed"},
                      Failure{"SeedOverflow", "scene --scene abstract --task T1 --seed 18446744073709551616", 2, "--seed"},
                      Failure{"SeedNotInteger", "scene --scene abstract --task T1 --seed 1e3", 2, "--seed"},
                      Failure{"MissingSeed", "scene --scene abstract --task T1", 2, "--seed"},
                      Failure{"UnwritableObj", "scene --scene abstract --task T1 --seed 1 --obj /nonexistent/dir/x.obj", 3,
                              "/nonexistent/dir/x.obj"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
