// The report as a document: sections of paragraphs, tables, figures and
// call-outs, built by the analysis sections and rendered three times, to
// Markdown (report.md), to a self-contained HTML page (index.html) and to
// LaTeX (report.tex). Keeping one document for all guarantees that they show
// the same tables. Text is
// plain; `backticks` mark code (file names, columns) in both renderings.
// Renderers number tables and figures in order of appearance.
#pragma once
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace dtlab::report::detail {

struct Paragraph {
  std::string text;
};

struct Table {
  std::string id;                                         // anchor, e.g. "table-time"
  std::string caption;                                    // without "Table N."
  std::vector<std::pair<std::string, int>> groups;        // optional spanning header: (label, columns)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> notes;                         // printed under the table
  int text_columns = 1;                                   // leading columns of text (left-aligned); the rest are numbers
  bool last_is_text = false;                              // the last column is text too (e.g. a reading)
  std::vector<std::string> links;                         // optional, per row: the last cell links to this relative path
  bool is_text(size_t column) const {
    return static_cast<int>(column) < text_columns || (last_is_text && column + 1 == header.size());
  }
};

struct Figure {
  std::string id;       // also the SVG's file stem: figures/<id>.svg
  std::string caption;  // without "Figure N."
  int width = 0;        // natural width in pixels (the page never draws it wider); 0 = the column's
};

struct Callout {
  std::string kind;  // "warning" or "note"
  std::string title;
  std::vector<std::string> items;
};

using Block = std::variant<Paragraph, Table, Figure, Callout>;

struct Section {
  std::string id;  // anchor
  std::string title;
  int level = 2;   // 2 = section, 3 = subsection
  std::vector<Block> blocks;

  Section& text(std::string t) { blocks.emplace_back(Paragraph{std::move(t)}); return *this; }
  Section& add(Table t) { blocks.emplace_back(std::move(t)); return *this; }
  Section& add(Figure f) { blocks.emplace_back(std::move(f)); return *this; }
  Section& add(Callout c) { blocks.emplace_back(std::move(c)); return *this; }
};

struct Document {
  std::string title;
  std::string subtitle;
  std::vector<Section> sections;
};

// report.md: GitHub-flavoured Markdown; figures as links to figures/<id>.svg.
std::string render_markdown(const Document& doc);
// index.html: one file, inline CSS, the SVG of each figure inline (svg[id] =
// its markup without XML prolog, ids made unique), no script, no external URL.
std::string render_html(const Document& doc, const std::map<std::string, std::string>& svg);

// report.tex: a LaTeX article (booktabs tables, figures/<id>.pdf), compiled by pdflatex with
// texlive-latex-recommended; every LaTeX special and non-ASCII character of the text escaped.
std::string render_latex(const Document& doc);

// Escapes for the renderers.
std::string latex_escape(const std::string& s);  // text mode; `code` spans become \texttt
std::string html_escape(const std::string& s);
// The SVG text prepared for inlining: no XML prolog or DOCTYPE, no xmlns
// declarations (HTML5 inline SVG needs none), every id and #reference
// prefixed with `prefix` so several figures never share an id.
std::string inline_svg(const std::string& svg, const std::string& prefix);

}  // namespace dtlab::report::detail
