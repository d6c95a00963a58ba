// The T2 letters C, K, R, X, Y as 5 x 7 bitmaps (the classic 5 x 7 dot-matrix
// font). Row 0 is the top row; '#' marks a lit cell. Seen from above (+y,
// looking down, screen-up = -z) a letter reads unmirrored when column c lies
// at x = (c - 2) * spacing and row r at z = (r - 3) * spacing, before the
// letter's rotation about the vertical axis (docs/scene.md).
#pragma once
#include <array>
#include <string_view>

namespace dtlab::scene {

struct LetterBitmap {
  char letter;
  std::array<std::string_view, 7> rows;  // 7 rows of 5 characters, '#' lit, '.' dark
  int lit() const {                      // number of lit cells (= letter cones)
    int n = 0;
    for (auto r : rows)
      for (char c : r) n += c == '#';
    return n;
  }
};

inline constexpr std::array<LetterBitmap, 5> kLetters{{
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
}};

// The bitmap of `letter`, or nullptr when it is not one of C K R X Y.
inline const LetterBitmap* find_letter(char letter) {
  for (const auto& l : kLetters)
    if (l.letter == letter) return &l;
  return nullptr;
}

}  // namespace dtlab::scene
