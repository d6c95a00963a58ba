// The pilot protocol (protocols/pilot.toml) with lighter scenes -- 40
// primitives, an 8 x 8 building with 20 models, one pair in the depth test
// (such a small building may not show three) -- for tests of several
// processes sharing a study, where the claims, the ledger and the store are
// under test, not the rendering. Reads the file; never writes one.
#pragma once
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace dtlab::test {

// The lighter pilot's text; "" if the pilot changed so that a replaced line is missing.
inline std::string light_pilot_text() {
  std::ifstream in(std::string(DTLAB_SOURCE_DIR) + "/protocols/pilot.toml", std::ios::binary);
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"objects = 200", "objects = 40"},
           {"grid = [16, 16]", "grid = [8, 8]"},
           {"objects = 50", "objects = 20"},
           {"pairs = 3", "pairs = 1"}}) {
    const auto at = text.find(from);
    if (at == std::string::npos) return "";
    text.replace(at, from.size(), to);
  }
  return text;
}

}  // namespace dtlab::test
