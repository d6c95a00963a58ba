// Content hashes: pinned values (a changed value means scenes changed: bump
// kSceneFormatVersion and update the pins on purpose), equal across two
// processes of the dtlab binary, and sensitive to what a participant sees.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "study/scene/generate.h"
#include "study/scene/hash.h"

namespace dtlab::scene {
namespace {

struct Pinned {
  Kind kind;
  Task task;
  std::uint64_t seed;
  const char* hash;
};

// Generated once by this code on x86-64 (g++ 12, glibc); any machine must agree.
const Pinned kPinned[] = {
    {Kind::abstract, Task::T1, 1, "9fa9eeabdb9115f278e7742e8bb4fa5b80eba9c5e1fee333f66199714483fafe"},
    {Kind::abstract, Task::T2, 2, "fa786c5bd80ab528680211baf0088a21c8117d8fea98f36075faae65a8c3abf1"},
    {Kind::walkthrough, Task::T3, 3, "d843f54631c0323e07d09484b6816ade5ea2a4a1551b08ee39e2fffb6051d742"},
    {Kind::walkthrough, Task::T4, 18446744073709551615ULL, "0bb5aaaad026edf8d2e7f3e953a8a1089ef09124bb4169f7ff2414203d019214"},
};

TEST(SceneHash, MatchesPinnedValues) {
  for (const Pinned& p : kPinned) {
    const auto s = generate(p.kind, p.task, p.seed);
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->hash, p.hash) << kind_name(p.kind) << " " << task_name(p.task) << " seed " << p.seed;
    EXPECT_EQ(s->hash, scene_hash(*s));
  }
}

TEST(SceneHash, SameInputsSameHashDifferentSeedsDiffer) {
  for (auto [kind, task] : {std::pair{Kind::abstract, Task::T1}, std::pair{Kind::abstract, Task::T2},
                            std::pair{Kind::walkthrough, Task::T3}, std::pair{Kind::walkthrough, Task::T4}}) {
    const auto a = generate(kind, task, 9), b = generate(kind, task, 9), c = generate(kind, task, 10);
    EXPECT_EQ(a->hash, b->hash);
    EXPECT_EQ(canonical_serialization(*a), canonical_serialization(*b));
    EXPECT_NE(a->hash, c->hash);
  }
  EXPECT_NE(generate(Kind::abstract, Task::T1, 9)->hash, generate(Kind::abstract, Task::T2, 9)->hash);
}

TEST(SceneHash, ChangesWithWhatTheParticipantSees) {
  const Scene base = *generate(Kind::walkthrough, Task::T3, 4);
  auto changed = [&](auto edit) {
    Scene s = base;
    edit(s);
    return scene_hash(s) != base.hash;
  };
  EXPECT_TRUE(changed([](Scene& s) { s.objects[5].transform[3].x += 0.001f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.objects[5].color.g *= 0.5f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.objects[5].target = !s.objects[5].target; }));
  EXPECT_TRUE(changed([](Scene& s) { s.objects[5].impenetrable = !s.objects[5].impenetrable; }));
  EXPECT_TRUE(changed([](Scene& s) { s.objects.pop_back(); }));
  EXPECT_TRUE(changed([](Scene& s) { s.answer.position.x += 1.0f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.plan->doors.pop_back(); }));
  EXPECT_TRUE(changed([](Scene& s) { s.camera.position.y += 0.1f; }));
  EXPECT_TRUE(changed([](Scene& s) { s.meshes.back().indices.resize(s.meshes.back().indices.size() - 3); }));
  // Below the 1e-4 quantum, and in values computed with sin/cos, the hash does not look.
  EXPECT_FALSE(changed([](Scene& s) { s.meshes.back().vertices[0].position.x += 1e-6f; }));
  EXPECT_FALSE(changed([](Scene& s) { s.camera.far_plane *= 1.5f; }));
}

TEST(SceneHash, SerializationIsLineOrientedAsciiWithoutVertices) {
  const Scene s = *generate(Kind::abstract, Task::T1, 1);
  const std::string text = canonical_serialization(s);
  EXPECT_EQ(text.rfind("dtlab-scene " + std::to_string(kSceneFormatVersion) + "\nscene abstract T1 1\n", 0), 0u);
  EXPECT_NE(text.find("\nmesh sphere 91 120\n"), std::string::npos) << "meshes appear as name and counts";
  for (char c : text) ASSERT_TRUE(c == '\n' || (c >= 32 && c < 127));
}

// Runs the dtlab binary, returning stdout and setting the exit status.
std::string run(const std::string& args, int* status) {
  const std::string cmd = std::string(DTLAB_BINARY) + " " + args + " 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int rc = pipe ? pclose(pipe) : -1;
  *status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return out;
}

TEST(SceneHash, TwoProcessesAgreeWithEachOtherAndThisOne) {
  for (const Pinned& p : kPinned) {
    const std::string args = "scene --scene " + std::string(kind_name(p.kind)) + " --task " +
                             std::string(task_name(p.task)) + " --seed " + std::to_string(p.seed) + " --json";
    int s1 = -1, s2 = -1;
    const auto j1 = nlohmann::json::parse(run(args, &s1)), j2 = nlohmann::json::parse(run(args, &s2));
    ASSERT_EQ(s1, 0);
    ASSERT_EQ(s2, 0);
    EXPECT_EQ(j1.at("hash"), j2.at("hash"));
    EXPECT_EQ(j1.at("hash").get<std::string>(), generate(p.kind, p.task, p.seed)->hash);
    EXPECT_EQ(j1.at("seed").get<std::uint64_t>(), p.seed);
  }
}

}  // namespace
}  // namespace dtlab::scene
