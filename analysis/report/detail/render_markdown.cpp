// report.md from the Document: GitHub-flavoured Markdown tables, figures as
// image links to figures/<id>.svg, call-outs as block quotes. Text is escaped
// so that level names with '_' or '*' never turn into emphasis; `code` spans
// are kept as they are.
#include <cctype>
#include <sstream>

#include "analysis/report/detail/document.h"

namespace dtlab::report::detail {
namespace {

// Escapes Markdown emphasis and table characters outside `code` spans, and what would start raw
// HTML or an entity (GitHub renders both): '<' before a letter, '/', '!' or '?' (a tag, comment or
// autolink) and '&' before a letter or '#'. A participant ID or an exclusion reason reads as the
// text typed, never as markup; "p < .001" stays as it is.
std::string md(const std::string& s, bool in_table = false) {
  std::string out;
  bool code = false;
  // A backtick opens a code span only where another one closes it; a lone one (typed into an ID)
  // is escaped, so it cannot switch the escaping off for the rest of the text.
  const std::size_t last_tick = s.rfind('`');
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const char next = i + 1 < s.size() ? s[i + 1] : '\0';
    const bool letter = std::isalpha(static_cast<unsigned char>(next)) != 0;
    if (c == '`' && !code && i == last_tick) {
      out += "\\`";
      continue;
    }
    if (c == '`') code = !code;
    if (!code && (c == '*' || c == '_' || c == '\\' || c == '[' || c == ']')) out += '\\';
    if (!code && c == '<' && (letter || next == '/' || next == '!' || next == '?')) {
      out += "&lt;";
      continue;
    }
    if (!code && c == '&' && (letter || next == '#')) {
      out += "&amp;";
      continue;
    }
    if (c == '|' && in_table) out += '\\';
    if (c == '\n' && in_table) {
      out += ' ';
      continue;
    }
    out += c;
  }
  return out;
}

}  // namespace

std::string render_markdown(const Document& doc) {
  std::ostringstream o;
  o << "# " << md(doc.title) << "\n\n";
  if (!doc.subtitle.empty()) o << md(doc.subtitle) << "\n\n";
  o << "Contents:";
  for (const auto& s : doc.sections)
    if (s.level == 2) o << " [" << md(s.title) << "](#" << s.id << ")" << (&s == &doc.sections.back() ? "" : " ·");
  o << "\n\n";
  int tables = 0, figures = 0;
  for (const auto& s : doc.sections) {
    o << "<a id=\"" << s.id << "\"></a>\n\n" << std::string(static_cast<size_t>(s.level), '#') << " " << md(s.title)
      << "\n\n";
    for (const auto& b : s.blocks) {
      if (const auto* p = std::get_if<Paragraph>(&b)) {
        o << md(p->text) << "\n\n";
      } else if (const auto* t = std::get_if<Table>(&b)) {
        o << "<a id=\"" << t->id << "\"></a>\n\n**Table " << ++tables << ".** " << md(t->caption) << "\n\n";
        std::vector<std::string> header = t->header;
        if (!t->groups.empty()) {  // Markdown has no spanning headers: prefix the labels of the later groups
          size_t col = 0;
          for (size_t g = 0; g < t->groups.size(); ++g) {
            const auto& [label, span] = t->groups[g];
            for (int k = 0; k < span && col < header.size(); ++k, ++col)
              if (g > 0 && !label.empty()) header[col] = label + ": " + header[col];
          }
        }
        o << "|";
        for (const auto& h : header) o << " " << md(h, true) << " |";
        o << "\n|";
        for (size_t c = 0; c < header.size(); ++c) o << (t->is_text(c) ? ":---|" : "---:|");
        o << "\n";
        for (size_t r = 0; r < t->rows.size(); ++r) {
          const auto& row = t->rows[r];
          o << "|";
          for (size_t c = 0; c < row.size(); ++c) {
            const bool link = c + 1 == row.size() && r < t->links.size() && !t->links[r].empty();
            o << " " << (link ? "[" + md(row[c], true) + "](" + t->links[r] + ")" : md(row[c], true)) << " |";
          }
          o << "\n";
        }
        o << "\n";
        for (const auto& n : t->notes) o << "*" << md(n) << "*\n\n";
      } else if (const auto* f = std::get_if<Figure>(&b)) {
        ++figures;
        o << "![Figure " << figures << "](figures/" << f->id << ".svg)\n\n**Figure " << figures << ".** "
          << md(f->caption) << " Also as [PNG](figures/" << f->id << ".png) and [PDF](figures/" << f->id
          << ".pdf).\n\n";
      } else if (const auto* c = std::get_if<Callout>(&b)) {
        o << "> **" << md(c->title) << "**\n";
        for (const auto& item : c->items) o << ">\n> - " << md(item) << "\n";
        o << "\n";
      }
    }
  }
  return o.str();
}

}  // namespace dtlab::report::detail
