// index.html from the Document: one self-contained page. CSS is inline in
// <style>, every figure's SVG is inline, there is no script and no URL to
// fetch, so the page reads the same offline, from a mail attachment or an
// archive (the only links go to files beside it: the walked-path figures). Tables follow the booktabs look of a journal (rules above and
// below, numbers right-aligned in tabular figures).
#include <sstream>

#include "analysis/report/detail/document.h"

namespace dtlab::report::detail {
namespace {

constexpr const char* kCss = R"css(
:root { --ink: #1d1d1f; --muted: #5f6368; --rule: #1d1d1f; --light: #d9d9de; --warn: #fff4e0; --warn-edge: #e0a030;
        --note: #eef3fb; --note-edge: #6d8fc7; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--ink); background: #fff; font: 16px/1.55 Georgia, "DejaVu Serif", "Times New Roman", serif; }
main { max-width: 76rem; margin: 0 auto; padding: 2rem 1.5rem 4rem; }
header h1 { font-size: 1.7rem; line-height: 1.25; margin: 0 0 .4rem; }
header p { color: var(--muted); margin: 0 0 1rem; }
nav { font: 14px/1.6 system-ui, "DejaVu Sans", sans-serif; border-top: 1px solid var(--light);
      border-bottom: 1px solid var(--light); padding: .5rem 0; margin-bottom: 1.5rem; }
nav a { color: #1a4f9c; text-decoration: none; margin-right: 1rem; white-space: nowrap; }
h2 { font-size: 1.35rem; margin: 2.4rem 0 .6rem; border-bottom: 1px solid var(--light); padding-bottom: .2rem; }
h3 { font-size: 1.1rem; margin: 1.8rem 0 .5rem; }
p { margin: .6rem 0; }
code { font: 0.88em/1.4 "DejaVu Sans Mono", monospace; background: #f3f3f5; padding: 0 .2em; border-radius: 3px; }
figure.table { margin: 1.4rem 0; max-width: 100%; overflow-x: auto; }
figcaption { font-size: .95rem; margin: 0 0 .4rem; }
figcaption b { font-weight: 700; }
table { border-collapse: collapse; font: 13px/1.45 system-ui, "DejaVu Sans", sans-serif;
        font-variant-numeric: tabular-nums; border-top: 2px solid var(--rule); border-bottom: 2px solid var(--rule); }
th, td { padding: .25rem .6rem; text-align: right; white-space: nowrap; vertical-align: top; }
th { white-space: normal; min-width: 3.2rem; vertical-align: bottom; }
th.text, td.text { text-align: left; white-space: normal; }
td.text { min-width: 4rem; max-width: 26rem; }
figure.table.wide table { font-size: 12px; }
figure.table.wide th, figure.table.wide td { padding: .2rem .35rem; }
thead tr:last-child th { border-bottom: 1px solid var(--rule); }
thead tr.groups th { border-bottom: 1px solid var(--light); text-align: center; font-weight: 600; color: var(--muted); }
tbody tr:nth-child(even) { background: #fafafb; }
.notes { font-size: .85rem; color: var(--muted); margin: .35rem 0 0; }
.notes p { margin: .15rem 0; }
figure.plot { margin: 1.6rem 0; }
figure.plot svg { width: 100%; height: auto; display: block; }
figure.plot figcaption { margin-top: .4rem; }
.callout { border-left: 4px solid var(--note-edge); background: var(--note); padding: .6rem 1rem; margin: 1rem 0; }
.callout.warning { border-color: var(--warn-edge); background: var(--warn); }
.callout h4 { margin: 0 0 .3rem; font: 600 15px/1.4 system-ui, "DejaVu Sans", sans-serif; }
.callout ul { margin: .2rem 0 .2rem 1.2rem; padding: 0; font-size: .95rem; }
footer { margin-top: 3rem; color: var(--muted); font-size: .85rem; }
/* Print (A4 or Letter, whichever the dialog picks): nothing is cut. Tables lose their scroll box,
   cells wrap at spaces, header rows repeat on every page; a table of many columns gets a page
   of its own turned to landscape. */
@page { margin: 14mm 12mm; }
@page wide { size: landscape; margin: 12mm; }
@media print {
  body { font-size: 10pt; line-height: 1.4; }
  main { max-width: none; padding: 0; }
  nav, footer { display: none; }
  h2, h3, figcaption { break-after: avoid; }
  figure.plot { break-inside: avoid; }
  figure.plot svg { max-height: 120mm; }
  figure.table { overflow: visible; margin: .8rem 0; }
  figure.table.wide { page: wide; }
  table { font-size: 7.5pt; line-height: 1.3; max-width: 100%; }
  thead { display: table-header-group; }
  tr { break-inside: avoid; }
  th, td { padding: .1rem .3rem; white-space: normal; min-width: 0; }
  td.text { max-width: 60mm; overflow-wrap: anywhere; }
  tbody tr:nth-child(even) { background: none; }
  .callout { break-inside: avoid; }
}
)css";

// A table of this many columns or more prints on a landscape page of its own.
constexpr size_t kWideColumns = 12;

// Escapes HTML and turns `code` spans into <code>.
std::string text_html(const std::string& s) {
  std::string out;
  bool code = false;
  std::string run;
  auto flush = [&] {
    out += html_escape(run);
    run.clear();
  };
  for (char c : s) {
    if (c == '`') {
      flush();
      out += code ? "</code>" : "<code>";
      code = !code;
    } else {
      run += c;
    }
  }
  flush();
  if (code) out += "</code>";
  return out;
}

}  // namespace

std::string render_html(const Document& doc, const std::map<std::string, std::string>& svg) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
    << "<title>" << html_escape(doc.title) << "</title>\n<style>" << kCss << "</style>\n</head>\n<body>\n<main>\n"
    << "<header>\n<h1>" << text_html(doc.title) << "</h1>\n";
  if (!doc.subtitle.empty()) o << "<p>" << text_html(doc.subtitle) << "</p>\n";
  o << "</header>\n<nav>";
  for (const auto& s : doc.sections)
    if (s.level == 2) o << "<a href=\"#" << s.id << "\">" << text_html(s.title) << "</a>\n";
  o << "</nav>\n";
  int tables = 0, figures = 0;
  for (const auto& s : doc.sections) {
    o << "<section id=\"" << s.id << "\">\n<h" << s.level << ">" << text_html(s.title) << "</h" << s.level << ">\n";
    for (const auto& b : s.blocks) {
      if (const auto* p = std::get_if<Paragraph>(&b)) {
        o << "<p>" << text_html(p->text) << "</p>\n";
      } else if (const auto* t = std::get_if<Table>(&b)) {
        o << "<figure class=\"table" << (t->header.size() >= kWideColumns ? " wide" : "") << "\" id=\"" << t->id
          << "\">\n<figcaption><b>Table " << ++tables << ".</b> "
          << text_html(t->caption) << "</figcaption>\n<table>\n<thead>\n";
        if (!t->groups.empty()) {
          o << "<tr class=\"groups\">";
          for (const auto& [label, span] : t->groups)
            o << "<th colspan=\"" << span << "\">" << text_html(label) << "</th>";
          o << "</tr>\n";
        }
        o << "<tr>";
        for (size_t c = 0; c < t->header.size(); ++c)
          o << (t->is_text(c) ? "<th class=\"text\">" : "<th>") << text_html(t->header[c])
            << "</th>";
        o << "</tr>\n</thead>\n<tbody>\n";
        for (size_t r = 0; r < t->rows.size(); ++r) {
          const auto& row = t->rows[r];
          o << "<tr>";
          for (size_t c = 0; c < row.size(); ++c) {
            const bool link = c + 1 == row.size() && r < t->links.size() && !t->links[r].empty();
            o << (t->is_text(c) ? "<td class=\"text\">" : "<td>");
            if (link) o << "<a href=\"" << html_escape(t->links[r]) << "\">";
            o << text_html(row[c]) << (link ? "</a>" : "") << "</td>";
          }
          o << "</tr>\n";
        }
        o << "</tbody>\n</table>\n";
        if (!t->notes.empty()) {
          o << "<div class=\"notes\">";
          for (const auto& n : t->notes) o << "<p>" << text_html(n) << "</p>";
          o << "</div>\n";
        }
        o << "</figure>\n";
      } else if (const auto* f = std::get_if<Figure>(&b)) {
        ++figures;
        o << "<figure class=\"plot\" id=\"" << f->id << "\"";
        if (f->width > 0) o << " style=\"max-width: " << f->width << "px\"";
        o << ">\n";
        auto it = svg.find(f->id);
        if (it != svg.end()) o << inline_svg(it->second, f->id + "-") << "\n";
        o << "<figcaption><b>Figure " << figures << ".</b> " << text_html(f->caption) << "</figcaption>\n</figure>\n";
      } else if (const auto* c = std::get_if<Callout>(&b)) {
        o << "<div class=\"callout " << c->kind << "\">\n<h4>" << text_html(c->title) << "</h4>\n";
        if (!c->items.empty()) {
          o << "<ul>";
          for (const auto& item : c->items) o << "<li>" << text_html(item) << "</li>";
          o << "</ul>\n";
        }
        o << "</div>\n";
      }
    }
    o << "</section>\n";
  }
  o << "<footer>Generated by <code>dtlab analyze</code>. Tables, figures and every number are also in "
       "<code>report.md</code>, <code>report.json</code> and the CSV files beside this page; the figures' data "
       "and gnuplot script are in <code>figures/</code>.</footer>\n</main>\n</body>\n</html>\n";
  return o.str();
}

}  // namespace dtlab::report::detail
