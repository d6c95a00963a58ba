// Message helpers (study/common/text.h): edit distances against hand-counted
// values, "did you mean" picks the nearest candidate only within its bound,
// and counts agree with their noun.
#include <gtest/gtest.h>

#include "study/common/text.h"

namespace {

TEST(Text, EditDistanceCountsSingleEdits) {
  EXPECT_EQ(dtlab::edit_distance("", ""), 0u);
  EXPECT_EQ(dtlab::edit_distance("analyse", "analyze"), 1u);  // one substitution
  EXPECT_EQ(dtlab::edit_distance("plan", "plans"), 1u);       // one insertion
  EXPECT_EQ(dtlab::edit_distance("kitten", "sitting"), 3u);   // the textbook case: k->s, e->i, +g
  EXPECT_EQ(dtlab::edit_distance("abc", ""), 3u);
}

TEST(Text, NearestSuggestsOnlyCloseWords) {
  const std::vector<std::string> commands{"validate", "plan", "analyze", "export", "simulate"};
  EXPECT_EQ(dtlab::nearest("analyse", commands), "analyze");
  EXPECT_EQ(dtlab::nearest("simlate", commands), "simulate");
  EXPECT_EQ(dtlab::nearest("foo", commands), "");
  EXPECT_EQ(dtlab::nearest("pln", commands, 0), "");
  EXPECT_EQ(dtlab::nearest("pln", commands, 1), "plan");
  EXPECT_EQ(dtlab::nearest("x", {}), "");
  EXPECT_EQ(dtlab::nearest("ab", {"ax", "xb"}), "ax");  // ties go to the first
}

TEST(Text, CountsAgreeWithTheirNoun) {
  EXPECT_EQ(dtlab::count(1, "trial"), "1 trial");
  EXPECT_EQ(dtlab::count(0, "trial"), "0 trials");
  EXPECT_EQ(dtlab::count(24, "trial"), "24 trials");
  EXPECT_EQ(dtlab::count(1, "order row"), "1 order row");
  EXPECT_EQ(dtlab::count(2, "analysis", "analyses"), "2 analyses");
  EXPECT_EQ(dtlab::count(-1, "step"), "-1 steps");
}

}  // namespace

namespace dtlab {
namespace {

// UTF-8 decoding (a script's typed text, the font atlas's glyphs): valid sequences of every
// length, and each kind of invalid byte read as U+FFFD without losing the text after it.
TEST(Utf8Codepoints, DecodesEveryLengthAndReplacesInvalidBytes) {
  EXPECT_EQ(utf8_codepoints("Aä€𝄞"), (std::u32string{U'A', U'\u00E4', U'\u20AC', U'\U0001D11E'}));
  EXPECT_EQ(utf8_codepoints("Größe, Ελλάδα, Россия, Łódź"),
            std::u32string(U"Größe, Ελλάδα, Россия, Łódź"));
  EXPECT_EQ(utf8_codepoints("a\x80" "b"), (std::u32string{U'a', U'\uFFFD', U'b'}));        // a lone continuation
  EXPECT_EQ(utf8_codepoints("a\xC3"), (std::u32string{U'a', U'\uFFFD'}));                   // cut short at the end
  EXPECT_EQ(utf8_codepoints("\xC0\xAF"), (std::u32string{U'\uFFFD', U'\uFFFD'}));          // overlong '/'
  EXPECT_EQ(utf8_codepoints("\xED\xA0\x80"), (std::u32string{U'\uFFFD', U'\uFFFD', U'\uFFFD'}));  // a surrogate
  EXPECT_EQ(utf8_codepoints("\xF4\x90\x80\x80").front(), U'\uFFFD');                       // above U+10FFFF
  EXPECT_TRUE(utf8_codepoints("").empty());
}

// The strict form refuses what the lenient one replaces: any invalid sequence makes the whole text invalid.
TEST(Text, Utf8DecodeRefusesEveryInvalidSequence) {
  EXPECT_EQ(utf8_decode("Größe, Ελλάδα, Россия, Łódź 𝄞"), std::u32string(U"Größe, Ελλάδα, Россия, Łódź 𝄞"));
  EXPECT_EQ(utf8_decode(""), std::u32string());
  for (const char* bad : {"a\x80" "b", "a\xC3", "\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80", "\xFF"})
    EXPECT_FALSE(utf8_decode(bad).has_value()) << bad;
}

}  // namespace
}  // namespace dtlab
