// protocol::design_sha256: the hash the store uses to tell a reworded
// protocol (sessions continue, analyses pool) from a changed design. Every
// edit that changes what a session runs must change it; comments, white
// space, key order, the title, the description and prompt texts must not.
// Each case is one textual edit of the shipped pilot protocol.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "study/protocol/protocol.h"

namespace dtlab::protocol {
namespace {

std::string pilot_text() {
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Edit {
  const char* name;
  const char* from;  // text to find (first occurrence)
  const char* to;    // its replacement
};

std::string apply(const Edit& e) {
  std::string t = pilot_text();
  const auto at = t.find(e.from);
  EXPECT_NE(at, std::string::npos) << e.name << ": \"" << e.from << "\" is not in pilot.toml";
  if (at != std::string::npos) t.replace(at, std::string(e.from).size(), e.to);
  return t;
}

std::string hash_of(const std::string& text, const char* name) {
  auto p = load_protocol_text(text, name);
  EXPECT_TRUE(p.ok()) << name << ": " << (p.ok() ? "" : p.error().to_string());
  return p.ok() ? design_sha256(p.value()) : std::string();
}

class SameDesign : public ::testing::TestWithParam<Edit> {};
class OtherDesign : public ::testing::TestWithParam<Edit> {};

TEST_P(SameDesign, WordingLeavesTheHash) {
  const std::string base = hash_of(pilot_text(), "pilot");
  ASSERT_EQ(base.size(), 64u);
  EXPECT_EQ(hash_of(apply(GetParam()), GetParam().name), base);
}

TEST_P(OtherDesign, WhatRunsChangesTheHash) {
  EXPECT_NE(hash_of(apply(GetParam()), GetParam().name), hash_of(pilot_text(), "pilot"));
}

INSTANTIATE_TEST_SUITE_P(
    Wording, SameDesign,
    ::testing::Values(Edit{"comment", "# Pilot:", "# A typo fixed. Pilot:"},
                      Edit{"trailing_comment", "master_seed = 1", "master_seed = 1  # the seed"},
                      Edit{"whitespace", "participants = 4", "participants    =    4"},
                      Edit{"title", "title = \"Pilot", "title = \"Pilot study"},
                      Edit{"description", "description = \"A quick", "description = \"A very quick"},
                      Edit{"prompt", "prompt = \"Overall", "prompt = \"All in all"},
                      Edit{"target_participants", "participants = 4", "participants = 8"},
                      Edit{"key_order", "a0 = 0.1\naT = 0.3", "aT = 0.3\na0 = 0.1"},
                      Edit{"published_results", "[demographics.age]",
                           "[reference_results]\nsource = \"A & B (2020)\"\n[[reference_results.results]]\n"
                           "measure = \"time\"\nmean = { off = 60, on = 30 }\nsd = { off = 9, on = 8 }\n"
                           "F = \"12.1\"\np = \"< .01\"\n[demographics.age]"},
                      // The session's wording: labels, instructions, consent and page texts.
                      Edit{"labels", "levels = [\"off\", \"on\"]",
                           "levels = [\"off\", \"on\"]\nlabels = [\"Normal\", \"X-ray view\"]"},
                      Edit{"level_instructions", "levels = [\"off\", \"on\"]",
                           "levels = [\"off\", \"on\"]\ninstructions = [\"\", \"Walls turn see-through.\"]"},
                      Edit{"no_breaks_table", "[training]", "[breaks]\nafter_blocks = true\n\n[training]"}),
    [](const auto& info) { return std::string(info.param.name); });

INSTANTIATE_TEST_SUITE_P(
    Design, OtherDesign,
    ::testing::Values(Edit{"master_seed", "master_seed = 1", "master_seed = 2"},
                      Edit{"session_limit", "time_limit_s = 1200", "time_limit_s = 1300"},
                      Edit{"training_limit", "time_limit_s = 60", "time_limit_s = 90"},
                      Edit{"practice", "practice_trials = 0", "practice_trials = 1"},
                      Edit{"levels", "levels = [\"off\", \"on\"]", "levels = [\"on\", \"off\"]"},
                      Edit{"scheme", "scheme = \"latin-square\"", "scheme = \"williams\""},
                      Edit{"objects", "objects = 200", "objects = 150"},
                      Edit{"extent", "extent = 100.0", "extent = 120.0"},
                      Edit{"object_kinds", "[\"sphere\", \"cone\", \"box\", \"torus\"]", "[\"sphere\", \"cone\", \"box\"]"},
                      Edit{"radius", "object_radius = [3.0, 6.0]", "object_radius = [3.0, 6.5]"},
                      Edit{"target_ratio", "target_ratio = [0.10, 0.20]", "target_ratio = [0.10, 0.25]"},
                      Edit{"trials", "trials = 1", "trials = 2"},
                      Edit{"letters", "[\"C\", \"K\", \"R\", \"X\", \"Y\"]", "[\"C\", \"K\", \"R\", \"X\"]"},
                      Edit{"grid", "grid = [16, 16]", "grid = [16, 12]"},
                      Edit{"cell_size", "cell_size = 4.0", "cell_size = 5.0"},
                      Edit{"count_range", "count_range = [3, 8]", "count_range = [3, 7]"},
                      Edit{"method", "method = \"dt-seed\"", "method = \"dt-fast\""},
                      Edit{"a0", "a0 = 0.1", "a0 = 0.15"},
                      Edit{"aT", "aT = 0.3", "aT = 0.35"},
                      Edit{"gradient", "gradient_width = 8", "gradient_width = 9"},
                      Edit{"mask_resolution", "mask_resolution = 128", "mask_resolution = 64"},
                      Edit{"mask_shape", "mask_shape = \"outline\"", "mask_shape = \"circle\""},
                      Edit{"mode", "mode = \"passive\"", "mode = \"active\""},
                      Edit{"layer_limit", "layer_limit = 0", "layer_limit = 2"},
                      Edit{"searchlight_radius", "layer_limit = 0", "layer_limit = 0\nsearchlight_radius = 0.3"},
                      Edit{"scale", "scale = [0, 4]", "scale = [1, 5]"},
                      Edit{"per", "per = [\"scenario\", \"transparency\"]", "per = [\"scenario\"]"},
                      Edit{"id", "id = \"pilot\"", "id = \"pilot2\""},
                      Edit{"occlusion_culling", "method = \"dt-seed\"", "method = \"dt-seed\"\nocclusion_culling = true"},
                      Edit{"r1_guard", "method = \"dt-seed\"", "method = \"dt-seed\"\nr1_guard = false"},
                      // The session's sequence around the trials.
                      Edit{"consent", "[training]", "[consent]\ntext = \"I agree.\"\n\n[training]"},
                      Edit{"page", "[training]", "[pages.debrief]\nwhen = \"end\"\ntext = \"Thanks.\"\n\n[training]"},
                      Edit{"breaks", "[training]", "[breaks]\nevery_trials = 4\n\n[training]"},
                      Edit{"break_length", "[training]", "[breaks]\nmin_s = 30\n\n[training]"},
                      Edit{"feedback", "practice_trials = 0", "practice_trials = 0\nfeedback = true"},
                      Edit{"counter", "time_limit_s = 1200", "time_limit_s = 1200\ntrial_counter = true"},
                      Edit{"announce", "time_limit_s = 1200", "time_limit_s = 1200\nannounce_blocks = true"}),
    [](const auto& info) { return std::string(info.param.name); });

// A protocol that does not set occlusion_culling hashes as before the key existed; setting it false is
// the default, so the same design.
TEST(DesignHash, OcclusionCullingOffIsTheDefault) {
  const std::string text = pilot_text();
  std::string off = text;
  off.replace(off.find("method = \"dt-seed\""), 18, "method = \"dt-seed\"\nocclusion_culling = false");
  EXPECT_EQ(hash_of(off, "off"), hash_of(text, "pilot"));
}

// The R1 guard is on unless a protocol says false (issue 26): writing the default keeps the hash of
// every protocol written before the key, which sessions rendered with the guard on.
TEST(DesignHash, R1GuardOnIsTheDefault) {
  const std::string text = pilot_text();
  std::string on = text;
  on.replace(on.find("method = \"dt-seed\""), 18, "method = \"dt-seed\"\nr1_guard = true");
  EXPECT_EQ(hash_of(on, "on"), hash_of(text, "pilot"));
}

// Regression (issue 24): the item-type seam must not change the design hash of a protocol with the
// three types older than it, or every study recorded before would need --allow-protocol-change.
// The values were recorded from the databases the build before the seam wrote (study_designs).
TEST(DesignHash, TheQuestionnaireSeamKeepsTheHashesOfExistingStudies) {
  EXPECT_EQ(hash_of(pilot_text(), "pilot"), "5fe8b466c3c82e3d336e98e437c831733778073f779d2f9aac3392a02bb1046b");
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/elmqvist2008.toml");
  std::stringstream ref;
  ref << in.rdbuf();
  EXPECT_EQ(hash_of(ref.str(), "elmqvist2008"), "6997f652ac35e1f7e095f8423f6794617743baff6cc921e103769c456e612ee4");
}

// Regression (issue 26): moving every method's keys into the technique registry (key groups that
// hash their own keys) must not change the design hash of any shipped protocol. The values were
// recorded from the databases `dtlab simulate` of the build before the registry wrote
// (study_designs.design_sha256), one protocol per method family.
TEST(DesignHash, TheTechniqueRegistryKeepsTheHashesOfExistingStudies) {
  const auto text = [](const char* name) {
    std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/" + name + ".toml");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  EXPECT_EQ(hash_of(text("lens-vs-dt"), "lens"), "1412478f1d8fb33d8ba96d110a05c553966f884c11e8f634cf03977589acfaad");
  EXPECT_EQ(hash_of(text("screen-door-vs-dt"), "screen-door"),
            "c498af129a03f1df5f3f3307a7c0b639fc58bb6284ff638618ee0cc801a80b14");
  EXPECT_EQ(hash_of(text("vdt-vs-dt"), "vdt"), "569b55539d499864262ffca5b2a462b9be5fa7c6e11fa2e6d2d3c397f9544f88");
  EXPECT_EQ(hash_of(text("technik-de"), "technik-de"), "88cf50bab8ba53e0035f41978cae0e18652880e99f78459ecd9599289580a806");
}

// Questionnaire items of the seam: what changes what is asked or stored changes the hash (`when`,
// a type's keys, an instrument and its keys); what is only read (labels, anchors, units) does not.
TEST(DesignHash, QuestionnaireStructureCountsItsWordingDoesNot) {
  const std::string items = "\n[questionnaire.ease]\ntype = \"likert\"\nprompt = \"Easy?\"\npoints = 5\n"
                            "labels = [\"no\", \"yes\"]\nwhen = \"block\"\n"
                            "[questionnaire.vas]\ntype = \"slider\"\nprompt = \"Effort?\"\nanchors = [\"low\", \"high\"]\n"
                            "[questionnaire.tlx]\ninstrument = \"nasa-tlx\"\nwhen = \"level:transparency\"\n";
  const std::string base = pilot_text() + items;
  const std::string h = hash_of(base, "items");
  EXPECT_NE(h, hash_of(pilot_text(), "pilot"));
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    t.replace(t.find(from), from.size(), to);
    return hash_of(t, from.c_str());
  };
  EXPECT_EQ(edit("labels = [\"no\", \"yes\"]", "labels = [\"nein\", \"ja\"]"), h);
  EXPECT_EQ(edit("anchors = [\"low\", \"high\"]", "anchors = [\"niedrig\", \"hoch\"]"), h);
  EXPECT_EQ(edit("prompt = \"Easy?\"", "prompt = \"Leicht?\""), h);
  EXPECT_NE(edit("when = \"block\"", "when = \"task\""), h);
  EXPECT_NE(edit("points = 5", "points = 7"), h);
  EXPECT_NE(edit("anchors = [\"low\", \"high\"]", "anchors = [\"low\", \"high\"]\nstep = 5"), h);
  EXPECT_NE(edit("instrument = \"nasa-tlx\"", "instrument = \"nasa-tlx\"\nweights = true"), h);
  EXPECT_NE(edit("instrument = \"nasa-tlx\"", "instrument = \"sus\""), h);
  // A `when` written as its default is the default.
  EXPECT_EQ(edit("[questionnaire.vas]", "[questionnaire.vas]\nwhen = \"end\""), h);
}

TEST(DesignHash, OfTextEqualsOfTheParsedProtocolAndRefusesBrokenText) {
  const std::string text = pilot_text();
  EXPECT_EQ(design_sha256_of_text(text), std::optional<std::string>(hash_of(text, "pilot")));
  EXPECT_EQ(design_sha256_of_text("this is not a protocol"), std::nullopt);
}

}  // namespace
}  // namespace dtlab::protocol
