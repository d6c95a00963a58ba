// report.tex from the Document: the same sections, tables and figures as a
// LaTeX article a researcher can compile (`pdflatex report.tex` beside the
// figures/ folder) or paste from. Tables use booktabs rules (no vertical
// lines), numbers right-aligned, spanning headers with \cmidrule; a table
// wider than the text is scaled down to it, a long one (over 30 rows) breaks
// across pages (longtable). Figures include figures/<id>.pdf. Every special
// character of LaTeX (# $ % & _ { } ~ ^ \ < >) is escaped and every
// non-ASCII character the report prints is mapped to a LaTeX command, so the
// file compiles with pdflatex and the packages of texlive-latex-recommended.
#include <sstream>

#include "analysis/report/detail/document.h"

namespace dtlab::report::detail {
namespace {

constexpr const char* kPreamble = R"tex(\documentclass[10pt]{article}
% Written by dtlab analyze: the report as LaTeX. Compile beside figures/ with `pdflatex report.tex`.
\usepackage[utf8]{inputenc}
\IfFileExists{lmodern.sty}{\usepackage[T1]{fontenc}\usepackage{lmodern}}{}
\usepackage[a4paper,margin=2cm]{geometry}
\usepackage{booktabs}
\usepackage{array}
\usepackage{longtable}
\usepackage{graphicx}
\usepackage{textcomp}
\usepackage{amssymb}
\setlength{\LTcapwidth}{\linewidth}
\setlength{\emergencystretch}{3em}  % long file names in \texttt never stick out of the margin
% A table no wider than the text: scaled down when wider, never up.
\newcommand{\fitwidth}[1]{\resizebox{\ifdim\width>\linewidth\linewidth\else\width\fi}{!}{#1}}
\newcommand{\tablenotes}[1]{\par\smallskip\begin{minipage}{\linewidth}\footnotesize #1\end{minipage}}
)tex";

// Non-ASCII characters of the report's text and their LaTeX (text mode).
struct Mapped {
  const char* utf8;
  const char* latex;
};
constexpr Mapped kUnicode[] = {
    {"η", "$\\eta$"},          {"χ", "$\\chi$"},          {"ε", "$\\varepsilon$"}, {"Δ", "$\\Delta$"},
    {"α", "$\\alpha$"},        {"β", "$\\beta$"},         {"μ", "$\\mu$"},         {"σ", "$\\sigma$"},
    {"ω", "$\\omega$"},        {"²", "\\textsuperscript{2}"}, {"³", "\\textsuperscript{3}"},
    {"−", "$-$"},              {"–", "--"},               {"—", "---"},            {"…", "\\ldots{}"},
    {"×", "$\\times$"},        {"≈", "$\\approx$"},       {"≤", "$\\leq$"},        {"≥", "$\\geq$"},
    {"±", "$\\pm$"},           {"·", "$\\cdot$"},         {"∞", "$\\infty$"},      {"→", "$\\rightarrow$"},
    {"“", "``"},               {"”", "''"},               {"‘", "`"},              {"’", "'"},
    {"√", "$\\surd$"},         {"≠", "$\\neq$"},          {"°", "\\textdegree{}"}, {"₁", "$_1$"},
    {"₂", "$_2$"},             {"ᵢ", "$_i$"},             {" ", "~"},             {"½", "\\textonehalf{}"},
    {"λ", "$\\lambda$"},       {"ρ", "$\\rho$"},          {"τ", "$\\tau$"},        {"δ", "$\\delta$"},
    {"Σ", "$\\Sigma$"},        {"⁷", "\\textsuperscript{7}"},
};

// Escapes one character run of plain text.
std::string escape(const std::string& s) {
  std::string out;
  out.reserve(s.size() + 16);
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x80) {
      bool done = false;
      for (const auto& m : kUnicode) {
        const std::string u = m.utf8;
        if (s.compare(i, u.size(), u) == 0) {
          out += m.latex;
          i += u.size();
          done = true;
          break;
        }
      }
      if (!done) {  // an unmapped character: its bytes as they are (inputenc names it if it fails)
        size_t len = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
        out += s.substr(i, len);
        i += len;
      }
      continue;
    }
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '{': out += "\\{"; break;
      case '}': out += "\\}"; break;
      case '#': out += "\\#"; break;
      case '$': out += "\\$"; break;
      case '%': out += "\\%"; break;
      case '&': out += "\\&"; break;
      case '_': out += "\\_"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '<': out += "\\textless{}"; break;
      case '>': out += "\\textgreater{}"; break;
      case '|': out += "\\textbar{}"; break;
      case '\n': out += ' '; break;
      default: out += static_cast<char>(c);
    }
    ++i;
  }
  return out;
}

// Text with `code` spans as \texttt.
std::string tex(const std::string& s) {
  std::string out, run;
  bool code = false;
  for (char c : s) {
    if (c != '`') {
      run += c;
      continue;
    }
    out += code ? "\\texttt{" + escape(run) + "}" : escape(run);
    run.clear();
    code = !code;
  }
  out += code ? "\\texttt{" + escape(run) + "}" : escape(run);
  return out;
}

void table(std::ostringstream& o, const Table& t) {
  std::string spec = "@{}";
  for (size_t c = 0; c < t.header.size(); ++c)
    spec += !t.is_text(c) ? "r" : static_cast<int>(c) < 1 ? "l" : ">{\\raggedright\\arraybackslash}p{3.6cm}";
  spec += "@{}";
  const bool long_table = t.rows.size() > 30;
  std::ostringstream head;
  if (!t.groups.empty()) {
    int col = 1;
    std::string rules;
    for (size_t g = 0; g < t.groups.size(); ++g) {
      const auto& [label, span] = t.groups[g];
      head << (g ? " & " : "") << "\\multicolumn{" << span << "}{c}{" << tex(label) << "}";
      if (!label.empty()) rules += "\\cmidrule(lr){" + std::to_string(col) + "-" + std::to_string(col + span - 1) + "}";
      col += span;
    }
    head << " \\\\\n" << rules << "\n";
  }
  for (size_t c = 0; c < t.header.size(); ++c) head << (c ? " & " : "") << tex(t.header[c]);
  head << " \\\\\n\\midrule\n";
  std::ostringstream body;
  for (const auto& row : t.rows) {
    for (size_t c = 0; c < row.size(); ++c) body << (c ? " & " : "") << tex(row[c]);
    body << " \\\\\n";
  }
  std::string notes;
  for (const auto& n : t.notes) notes += (notes.empty() ? "" : "\\par ") + tex(n);
  if (long_table) {
    o << "{\\footnotesize\n\\begin{longtable}{" << spec << "}\n\\caption{" << tex(t.caption) << "}\\label{" << t.id
      << "}\\\\\n\\toprule\n" << head.str() << "\\endfirsthead\n\\toprule\n" << head.str() << "\\endhead\n"
      << "\\bottomrule\n\\endfoot\n" << body.str() << "\\end{longtable}}\n";
    if (!notes.empty()) o << "\\tablenotes{" << notes << "}\n";
    o << "\n";
    return;
  }
  o << "\\begin{table}[htbp]\n\\centering\n\\caption{" << tex(t.caption) << "}\\label{" << t.id << "}\n"
    << "\\small\n\\fitwidth{%\n\\begin{tabular}{" << spec << "}\n\\toprule\n" << head.str() << body.str()
    << "\\bottomrule\n\\end{tabular}}\n";
  if (!notes.empty()) o << "\\tablenotes{" << notes << "}\n";
  o << "\\end{table}\n\n";
}

}  // namespace

std::string latex_escape(const std::string& s) { return tex(s); }

std::string render_latex(const Document& doc) {
  std::ostringstream o;
  o << kPreamble << "\\title{" << tex(doc.title) << "}\n\\date{}\n\\begin{document}\n\\maketitle\n";
  if (!doc.subtitle.empty()) o << "\\noindent " << tex(doc.subtitle) << "\n\n";
  for (const auto& s : doc.sections) {
    o << (s.level <= 2 ? "\\section{" : "\\subsection{") << tex(s.title) << "}\\label{" << s.id << "}\n\n";
    for (const auto& b : s.blocks) {
      if (const auto* p = std::get_if<Paragraph>(&b)) {
        o << tex(p->text) << "\n\n";
      } else if (const auto* t = std::get_if<Table>(&b)) {
        table(o, *t);
      } else if (const auto* f = std::get_if<Figure>(&b)) {
        o << "\\begin{figure}[htbp]\n\\centering\n\\includegraphics[width=\\linewidth,height=0.8\\textheight,"
             "keepaspectratio]{figures/" << f->id << ".pdf}\n\\caption{" << tex(f->caption) << "}\\label{" << f->id
          << "}\n\\end{figure}\n\n";
      } else if (const auto* c = std::get_if<Callout>(&b)) {
        o << "\\begin{quote}\n\\textbf{" << (c->kind == "warning" ? "Warning: " : "") << tex(c->title) << "}\n";
        if (!c->items.empty()) {
          o << "\\begin{itemize}\n";
          for (const auto& item : c->items) o << "\\item " << tex(item) << "\n";
          o << "\\end{itemize}\n";
        }
        o << "\\end{quote}\n\n";
      }
    }
  }
  o << "\\end{document}\n";
  return o.str();
}

}  // namespace dtlab::report::detail
