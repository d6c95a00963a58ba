// The participants' wording (study/protocol/wording.h): docs/protocol.md lists
// exactly the keys the code has, with their defaults and placeholders; a
// protocol's [text] replaces a default, fills its placeholders, and may use
// no key and no placeholder the table does not have; wording never changes
// the design hash.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "study/protocol/wording.h"
#include "study/scene/models.h"

namespace dtlab::protocol {
namespace {

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string pilot() { return read(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml"); }

TEST(Wording, DocsListExactlyTheKeysWithTheirDefaults) {
  const std::string docs = read(std::string(DTLAB_SOURCE_DIR) + "/docs/protocol.md");
  const auto at = docs.find("## `[text]`");
  ASSERT_NE(at, std::string::npos);
  const std::string section = docs.substr(at, docs.find("\n## ", at + 1) - at);
  const std::regex row(R"(\| `([a-z_.]+)` \| ([^|]*) \| ([^|]*) \|)");
  std::vector<std::pair<std::string, std::string>> documented;
  for (auto it = std::sregex_iterator(section.begin(), section.end(), row); it != std::sregex_iterator(); ++it)
    documented.emplace_back((*it)[1].str(), (*it)[2].str());
  ASSERT_EQ(documented.size(), text_keys().size());
  for (std::size_t i = 0; i < documented.size(); ++i) {
    EXPECT_EQ(documented[i].first, text_keys()[i].key);
    EXPECT_EQ(documented[i].second, text_keys()[i].english) << documented[i].first;
  }
}

// Participants read WALKTHROUGH kinds by name ("Find this: dog"): every kind of the scene
// generator has its key, defaulting to the model's own label.
TEST(Wording, EveryObjectKindHasItsKeyWithTheModelsLabel) {
  for (const scene::ModelInfo& m : scene::model_catalogue()) {
    const TextKey* k = find_text_key("kind." + std::string(m.kind));
    ASSERT_NE(k, nullptr) << m.kind;
    EXPECT_EQ(k->english, m.label) << m.kind;
  }
}

TEST(Wording, ATextTableReplacesDefaultsAndFillsPlaceholders) {
  const auto english = load_protocol_text(pilot(), "pilot.toml");
  ASSERT_TRUE(english) << english.error().to_string();
  EXPECT_EQ(text(*english, "break.after_block", {{"done", "1"}, {"blocks", "4"}}),
            "Block 1 of 4 is done. Take a short break.");
  const auto german = load_protocol_text(
      pilot() + "\n[text]\n\"break.after_block\" = \"Block {done} von {blocks} ist geschafft. Kurze Pause.\"\n"
                "\"button.continue\" = \"Weiter\"\n\"announce.title\" = \"Ελληνικά: επόμενο\"\n",
      "pilot-de.toml");
  ASSERT_TRUE(german) << german.error().to_string();
  EXPECT_EQ(text(*german, "break.after_block", {{"done", "1"}, {"blocks", "4"}}),
            "Block 1 von 4 ist geschafft. Kurze Pause.");
  EXPECT_EQ(text(*german, "button.continue"), "Weiter");
  EXPECT_EQ(text(*german, "announce.title"), "Ελληνικά: επόμενο");
  EXPECT_EQ(text(*german, "consent.title"), "Consent") << "a key the table does not set keeps its default";
  EXPECT_EQ(design_sha256(*german), design_sha256(*english)) << "wording is not design";
}

// An instrument worded in another language: prompts and anchors replaced, the pairwise comparisons
// named by the reworded titles, the published scoring and the design hash unchanged.
TEST(Wording, AnInstrumentTakesItsItemsWordingInAnotherLanguage) {
  const std::string tlx = "\n[questionnaire.tlx]\ninstrument = \"nasa-tlx\"\nweights = true\n";
  const auto english = load_protocol_text(pilot() + tlx, "pilot.toml");
  ASSERT_TRUE(english) << english.error().to_string();
  const auto german = load_protocol_text(
      pilot() + tlx +
          "[questionnaire.tlx.wording.mental]\nprompt = \"Geistige Anforderung\\nWie viel geistige Anstrengung?\"\n"
          "anchors = [\"Sehr gering\", \"Sehr hoch\"]\n"
          "[questionnaire.tlx.wording.w]\nprompt = \"Was trug mehr zur Beanspruchung bei?\"\n",
      "pilot-de.toml");
  ASSERT_TRUE(german) << german.error().to_string();
  const auto item = [](const Protocol& p, const std::string& id) -> const QuestionnaireItem& {
    for (const QuestionnaireItem& q : p.questionnaire)
      if (q.id == id) return q;
    throw std::runtime_error("no item " + id);
  };
  EXPECT_EQ(item(*german, "tlx.mental").prompt, "Geistige Anforderung\nWie viel geistige Anstrengung?");
  EXPECT_EQ(item(*german, "tlx.mental").strings("anchors"), (std::vector<std::string>{"Sehr gering", "Sehr hoch"}));
  EXPECT_EQ(item(*german, "tlx.physical").prompt, item(*english, "tlx.physical").prompt) << "not reworded: published";
  const QuestionnaireItem& pair = item(*german, "tlx.w.mental-physical");
  EXPECT_EQ(pair.prompt, "Was trug mehr zur Beanspruchung bei?");
  EXPECT_EQ(pair.strings("labels"), (std::vector<std::string>{"Geistige Anforderung", "Physical Demand"}));
  EXPECT_EQ(pair.strings("options"), item(*english, "tlx.w.mental-physical").strings("options")) << "answers stay ids";
  EXPECT_EQ(design_sha256(*german), design_sha256(*english)) << "wording is not design";
}

TEST(Wording, UnknownKeysAndPlaceholdersAreErrorsWithTheirField) {
  struct Case {
    std::string toml, field, says;
  };
  for (const Case& c : std::vector<Case>{
           {"\"button.contine\" = \"Weiter\"", "text.button.contine", "did you mean 'button.continue'"},
           {"\"break.after_block\" = \"Block {done} von {total}\"", "text.break.after_block",
            "\"{total}\" is no placeholder of this text (it takes: done blocks)"},
           {"\"button.continue\" = \"Weiter {x}\"", "text.button.continue", "(it takes none)"},
           {"\"button.continue\" = 3", "text.button.continue", "expected a string"},
       }) {
    const auto diags = validate_protocol_text(pilot() + "\n[text]\n" + c.toml + "\n", "pilot.toml");
    bool found = false;
    for (const auto& d : diags)
      if (d.severity == Severity::error && d.where.field == c.field && d.where.message.find(c.says) != std::string::npos)
        found = true;
    EXPECT_TRUE(found) << c.toml;
  }
}

}  // namespace
}  // namespace dtlab::protocol
