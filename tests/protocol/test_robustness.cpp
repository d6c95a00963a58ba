// No input crashes the validator: every prefix of the reference protocol,
// the protocol with any one line deleted, and thousands of seeded byte
// mutations either validate or produce errors that name a line (>= 1) and say
// what is wrong; load_protocol agrees with validate; and whatever loads can be
// planned without an exception (validation guarantees what make_plan needs).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "study/common/random.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"

namespace {

using namespace dtlab::protocol;

std::string reference_text() {
  std::ifstream in(DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Checks one input; returns true if it was valid.
bool check(const std::string& text, const std::string& what) {
  std::vector<dtlab::Diagnostic> diags;
  EXPECT_NO_THROW(diags = validate_protocol_text(text, "m.toml")) << what;
  for (const auto& d : diags) {
    if (d.severity != dtlab::Severity::error) continue;
    EXPECT_GE(d.where.line, 1) << what << ": " << d.to_string();
    EXPECT_GE(d.where.column, 1) << what << ": " << d.to_string();
    EXPECT_FALSE(d.where.message.empty()) << what;
    EXPECT_EQ(d.where.file, "m.toml") << what;
  }
  const auto p = load_protocol_text(text, "m.toml");
  EXPECT_EQ(p.ok(), !has_errors(diags)) << what;
  if (p.ok()) {
    EXPECT_NO_THROW({
      const int rows = dtlab::design::order_rows(*p);
      for (int k = 0; k < std::min(rows, 4); ++k) (void)dtlab::design::make_plan(*p, k);
    }) << what;
  }
  return p.ok();
}

TEST(Robustness, EveryPrefixOfTheReferenceProtocol) {
  const std::string text = reference_text();
  ASSERT_GT(text.size(), 1000u);
  // The last required part is [rendering.on]'s method; everything after it
  // (the other rendering keys, the questionnaire) is optional.
  const std::string last_required = "method = \"dt-seed\"";
  const std::size_t complete = text.find(last_required) + last_required.size();
  ASSERT_NE(text.find(last_required), std::string::npos);
  for (std::size_t n = 0; n <= text.size(); n += 3) {
    const bool valid = check(text.substr(0, n), "prefix " + std::to_string(n));
    if (n < complete) {
      EXPECT_FALSE(valid) << "a prefix of " << n << " bytes lacks required parts";
    }
  }
  EXPECT_TRUE(check(text, "whole"));
}

TEST(Robustness, EveryLineDeleted) {
  const std::string text = reference_text();
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  for (std::size_t skip = 0; skip < lines.size(); ++skip) {
    std::string t;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (i != skip) t += lines[i] + "\n";
    check(t, "without line " + std::to_string(skip + 1) + ": " + lines[skip]);
  }
}

TEST(Robustness, SeededByteMutations) {
  const std::string text = reference_text();
  static const char kBytes[] = "[]{}\"'=,.#\n\\0123456789-+xeZ \t\x7f\xff\xc3";
  dtlab::Random<dtlab::SplitMix64> rng(20240601);  // dtlab's own stream (study/common/random.h)
  int valid = 0;
  for (int i = 0; i < 3000; ++i) {
    std::string t = text;
    const int edits = 1 + static_cast<int>(rng.below(3));
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng.below(t.size());
      const char b = kBytes[rng.below(sizeof kBytes - 1)];
      switch (rng.below(3)) {
        case 0: t[at] = b; break;
        case 1: t.insert(t.begin() + static_cast<std::ptrdiff_t>(at), b); break;
        default: t.erase(at, 1 + rng.below(8)); break;
      }
      if (t.empty()) t = " ";
    }
    valid += check(t, "mutation " + std::to_string(i));
  }
  // Most mutations land in comments or strings and stay valid; many do not.
  EXPECT_GT(valid, 0);
  EXPECT_LT(valid, 3000);
}

}  // namespace
