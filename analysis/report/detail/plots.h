// Plots through gnuplot (Debian's gnuplot-nox: terminals svg, pngcairo,
// pdfcairo), run as a subprocess: each figure is a data file plus gnuplot
// commands, drawn as <id>.svg, <id>.png (twice the pixels) and <id>.pdf; all figures
// go into one script, figures/report.gp, run by one gnuplot process, so a
// reader can re-draw or restyle every figure from the files left beside it.
// Guarantees: gnuplot is found or a clear Error says how to get it; a failing
// gnuplot returns an Error quoting its own message; nothing is drawn by
// assembling SVG by hand. Never runs a shell.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "study/common/error.h"

namespace dtlab::report::detail {

struct PlotSpec {
  std::string id;                            // output figures/<id>.svg
  int width = 760, height = 440;             // SVG size in pixels
  std::map<std::string, std::string> data;   // data files (names relative to figures/) -> content
  std::string commands;                      // gnuplot commands after terminal and output are set
  bool empty = false;                        // nothing finite to draw: the figure is left out (gnuplot
                                             // stops with "x range is invalid" on a plot without points)
};

// The gnuplot to run: `configured` if not empty, else $DTLAB_GNUPLOT, else "gnuplot" (PATH).
std::string gnuplot_executable(const std::string& configured);

// Runs `gnuplot --version`; an Error (field "gnuplot") when it is missing or fails.
Status check_gnuplot(const std::string& exe);

// Writes the data files and figures/report.gp into `figures_dir` (existing),
// runs gnuplot once (SVG, PNG and PDF of each figure) and returns id -> SVG text. Error field
// "gnuplot" (also when a PNG or PDF is missing: a gnuplot without cairo) or "output".
Result<std::map<std::string, std::string>> render_plots(const std::vector<PlotSpec>& plots,
                                                        const std::string& figures_dir, const std::string& exe);

// --- helpers for building plots --------------------------------------------------------
std::string gp_quote(const std::string& s);   // a gnuplot single-quoted string literal
std::string gp_value(double v);               // a number for a data file; NaN/inf -> "NaN" (skipped by gnuplot)
const char* series_color(size_t i);           // colour of series i (colour-blind-safe palette)
// Common style: white background, light grid, sans font, legend on top.
std::string gp_style();

}  // namespace dtlab::report::detail
