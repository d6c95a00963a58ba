// Escaping and SVG inlining for the renderers; see document.h.
#include "analysis/report/detail/document.h"

#include <cctype>
#include <map>

namespace dtlab::report::detail {
namespace {

bool starts_with(const std::string& s, size_t i, const char* lit) { return s.compare(i, std::char_traits<char>::length(lit), lit) == 0; }

// Removes every `<!...>` / `<?...?>` before the root element.
std::string strip_prolog(const std::string& svg) {
  const size_t root = svg.find("<svg");
  return root == std::string::npos ? svg : svg.substr(root);
}

// Removes xmlns and xmlns:* attributes (quoted values) from the text.
std::string strip_xmlns(std::string s) {
  for (size_t i = s.find("xmlns"); i != std::string::npos; i = s.find("xmlns", i)) {
    const size_t eq = s.find('=', i);
    if (eq == std::string::npos || eq + 1 >= s.size() || (s[eq + 1] != '"' && s[eq + 1] != '\'')) {
      ++i;
      continue;
    }
    const size_t close = s.find(s[eq + 1], eq + 2);
    if (close == std::string::npos) break;
    size_t start = i;
    while (start > 0 && std::isspace(static_cast<unsigned char>(s[start - 1]))) --start;
    s.erase(start, close + 1 - start);
    i = start;
  }
  return s;
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string inline_svg(const std::string& svg, const std::string& prefix) {
  const std::string s = strip_xmlns(strip_prolog(svg));
  std::string out;
  out.reserve(s.size() + 1024);
  bool in_tag = false;
  std::map<std::string, int> seen;
  for (size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == '<') in_tag = true;
    if (c == '>') in_tag = false;
    if (in_tag) {
      const bool attr_start = i > 0 && std::isspace(static_cast<unsigned char>(s[i - 1]));
      if (attr_start && starts_with(s, i, "id=") && i + 3 < s.size() && (s[i + 3] == '"' || s[i + 3] == '\'')) {
        const char q = s[i + 3];
        const size_t close = s.find(q, i + 4);
        if (close != std::string::npos) {
          // gnuplot may repeat an id inside one SVG (e.g. an opaque key drawn twice): later copies
          // get a suffix, and references keep pointing at the first.
          const std::string id = s.substr(i + 4, close - i - 4);
          const int n = ++seen[id];
          out += "id=";
          out += q;
          out += prefix + id + (n > 1 ? "-" + std::to_string(n) : "");
          out += q;
          i = close + 1;
          continue;
        }
      }
      if (starts_with(s, i, "href=") && i + 6 < s.size() && (s[i + 5] == '"' || s[i + 5] == '\'') &&
          s[i + 6] == '#') {
        out += "href=";
        out += s[i + 5];
        out += "#" + prefix;
        i += 7;
        continue;
      }
      if (starts_with(s, i, "url(#")) {
        out += "url(#" + prefix;
        i += 5;
        continue;
      }
    }
    out += c;
    ++i;
  }
  return out;
}

}  // namespace dtlab::report::detail
