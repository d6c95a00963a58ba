// edit_distance and nearest (text.h): the classic two-row dynamic program; count.
#include "study/common/text.h"

#include <algorithm>

namespace dtlab {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string nearest(std::string_view word, const std::vector<std::string>& candidates, std::size_t max_distance) {
  std::string best;
  std::size_t best_d = max_distance + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

std::string count(long long n, std::string_view noun, std::string_view plural) {
  std::string s = std::to_string(n) + " ";
  if (n == 1) return s.append(noun);
  if (!plural.empty()) return s.append(plural);
  return s.append(noun).append("s");
}

namespace {

// The code point of the UTF-8 sequence at text[i] and its length; length 0 where no valid
// sequence starts there (a bad lead or continuation byte, truncated, overlong, surrogate, > U+10FFFF).
std::pair<char32_t, std::size_t> utf8_at(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  const std::size_t len = b < 0x80 ? 1 : (b >> 5) == 0x6 ? 2 : (b >> 4) == 0xE ? 3 : (b >> 3) == 0x1E ? 4 : 0;
  if (len == 0 || i + len > text.size()) return {0, 0};
  char32_t c = len == 1 ? b : len == 2 ? (b & 0x1F) : len == 3 ? (b & 0x0F) : (b & 0x07);
  for (std::size_t k = 1; k < len; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return {0, 0};
    c = (c << 6) | (byte(i + k) & 0x3F);
  }
  static constexpr char32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
  if (c < kMin[len] || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return {0, 0};
  return {c, len};
}

}  // namespace

std::optional<std::u32string> utf8_decode(std::string_view text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto [c, len] = utf8_at(text, i);
    if (len == 0) return std::nullopt;
    out.push_back(c);
    i += len;
  }
  return out;
}

std::u32string utf8_codepoints(std::string_view text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto [c, len] = utf8_at(text, i);
    out.push_back(len ? c : U'\uFFFD');
    i += len ? len : 1;
  }
  return out;
}

}  // namespace dtlab
