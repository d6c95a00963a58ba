// Small text helpers for messages: "did you mean ...?" (the candidate nearest
// to a misspelt word by edit distance: insertions, deletions, substitutions,
// each costing one), counts with their noun ("1 trial", "2 trials"), and
// UTF-8 decoded into code points (what a typed text or a font atlas needs).
// Guarantees: deterministic (ties go to the earliest candidate); nothing is
// suggested beyond `max_distance` edits. Used by the protocol reader (unknown
// keys), the command line (unknown subcommands) and every summary line.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace dtlab {

// Levenshtein distance between a and b (bytes).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate with the smallest edit distance to `word` if it is at most `max_distance`, else "".
std::string nearest(std::string_view word, const std::vector<std::string>& candidates, std::size_t max_distance = 2);

// "1 trial", "0 trials", "24 trials": n and the noun, plural unless n is 1 (plural = noun + "s" by default).
std::string count(long long n, std::string_view noun, std::string_view plural = {});

// The Unicode code points of UTF-8 text; a byte that starts no valid sequence (or an overlong,
// surrogate or out-of-range one) reads as U+FFFD, and decoding goes on with the next byte.
std::u32string utf8_codepoints(std::string_view text);

// The code points of valid UTF-8 text; nullopt if any byte starts no valid sequence (a bad lead or
// continuation byte, a truncated, overlong or surrogate sequence, a value past U+10FFFF).
std::optional<std::u32string> utf8_decode(std::string_view text);

}  // namespace dtlab
