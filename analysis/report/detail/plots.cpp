// gnuplot as a subprocess; see plots.h. posix_spawnp with an argument vector
// (no shell, so no quoting of paths), stdout and stderr to a log file whose
// tail goes into the Error when gnuplot fails.
#include "analysis/report/detail/plots.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

extern char** environ;

namespace dtlab::report::detail {
namespace {

namespace fs = std::filesystem;

Error gnuplot_error(const std::string& file, std::string message) {
  return Error{file, 0, 0, "gnuplot", std::move(message), ErrorKind::environment};
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  out.flush();
  return static_cast<bool>(out);
}

// Runs exe with args, output to log; returns the exit status, or an Error when it cannot start.
Result<int> run(const std::string& exe, const std::vector<std::string>& args, const std::string& log) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> all = {exe};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    std::string why = std::strerror(rc);
    if (rc == ENOENT)
      why = "not found; install Debian's gnuplot-nox (apt-get install gnuplot-nox) or set DTLAB_GNUPLOT to its path";
    return gnuplot_error(exe, "cannot run gnuplot: " + why);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return gnuplot_error(exe, std::string("waiting for gnuplot failed: ") + std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

std::string tail_lines(const std::string& text, int n) {
  size_t pos = text.size();
  while (pos > 0 && (text[pos - 1] == '\n' || text[pos - 1] == ' ')) --pos;
  size_t start = pos;
  for (int k = 0; k < n && start > 0; ++k) {
    start = text.rfind('\n', start - 1);
    if (start == std::string::npos) {
      start = 0;
      break;
    }
  }
  return text.substr(start == 0 ? 0 : start + 1, pos - (start == 0 ? 0 : start + 1));
}

}  // namespace

std::string gnuplot_executable(const std::string& configured) {
  if (!configured.empty()) return configured;
  if (const char* env = std::getenv("DTLAB_GNUPLOT"); env && *env) return env;
  return "gnuplot";
}

Status check_gnuplot(const std::string& exe) {
  char tmpl[] = "/tmp/dtlab-gnuplot-XXXXXX";
  const int fd = mkstemp(tmpl);
  if (fd < 0) return gnuplot_error(exe, std::string("cannot create a temporary file: ") + std::strerror(errno));
  close(fd);
  auto rc = run(exe, {"--version"}, tmpl);
  const std::string out = read_file(tmpl);
  std::remove(tmpl);
  if (!rc) return rc.error();
  if (*rc != 0) return gnuplot_error(exe, "gnuplot --version failed (exit " + std::to_string(*rc) + "): " + tail_lines(out, 3));
  return {};
}

Result<std::map<std::string, std::string>> render_plots(const std::vector<PlotSpec>& plots,
                                                        const std::string& figures_dir, const std::string& exe) {
  const fs::path dir(figures_dir);
  std::string script =
      "# The report's figures: run `gnuplot report.gp` in this folder to draw them again.\n"
      "# Written by dtlab analyze; each figure reads the .dat files beside this script.\n";
  for (const auto& p : plots) {
    for (const auto& [name, content] : p.data)
      if (!write_file(dir / name, content))
        return Error{(dir / name).string(), 0, 0, "output", "cannot write the plot data file", ErrorKind::environment};
    // The same figure three times, by the same gnuplot process: SVG (the page), PNG at twice the
    // pixels (slides, word processors) and PDF (LaTeX), sized so that text reads 12 px / 9 pt.
    const std::string w = std::to_string(p.width), h = std::to_string(p.height);
    const std::pair<std::string, std::string> terminals[] = {
        {"svg", "svg size " + w + "," + h + " dynamic enhanced font 'DejaVu Sans,12'"},
        {"png", "pngcairo size " + std::to_string(2 * p.width) + "," + std::to_string(2 * p.height) +
                    " enhanced font 'DejaVu Sans,12' fontscale 2 linewidth 2"},
        {"pdf", "pdfcairo size " + gp_value(p.width / 100.0) + "in," + gp_value(p.height / 100.0) +
                    "in enhanced font 'DejaVu Sans,9'"},
    };
    for (const auto& [ext, terminal] : terminals) {
      script += "\n# --- " + p.id + "." + ext + " ---\nreset\n";
      script += "set terminal " + terminal + " background rgb 'white'\n";
      script += "set output " + gp_quote(p.id + "." + ext) + "\n";
      script += gp_style() + p.commands + "\nunset multiplot\nset output\n";
    }
  }
  const fs::path gp = dir / "report.gp";
  if (!write_file(gp, script)) return Error{gp.string(), 0, 0, "output", "cannot write the gnuplot script", ErrorKind::environment};
  // gnuplot reads and writes relative to its working directory: `cd` first.
  const std::string log = (dir / "gnuplot.log").string();
  auto rc = run(exe, {"-e", "cd " + gp_quote(fs::absolute(dir).string()), fs::absolute(gp).string()}, log);
  if (!rc) return rc.error();
  const std::string out = read_file(log);
  if (*rc != 0) return gnuplot_error(gp.string(), "gnuplot failed (exit " + std::to_string(*rc) + "): " + tail_lines(out, 6));
  std::map<std::string, std::string> svg;
  for (const auto& p : plots) {
    const fs::path f = dir / (p.id + ".svg");
    std::string text = read_file(f);
    if (text.find("<svg") == std::string::npos)
      return gnuplot_error(f.string(), "gnuplot wrote no SVG for figure " + p.id + ": " + tail_lines(out, 6));
    for (const char* ext : {".png", ".pdf"})
      if (std::error_code ec; fs::file_size(dir / (p.id + ext), ec) == 0 || ec)
        return gnuplot_error((dir / (p.id + ext)).string(), "gnuplot wrote no " + std::string(ext + 1) +
                                                                " for figure " + p.id + " (pngcairo and pdfcairo "
                                                                "need gnuplot built with cairo, as Debian's "
                                                                "gnuplot-nox is): " + tail_lines(out, 6));
    svg[p.id] = std::move(text);
  }
  return svg;
}

std::string gp_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

std::string gp_value(double v) {
  if (!std::isfinite(v)) return "NaN";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

const char* series_color(size_t i) {
  // Okabe & Ito (2008) colour-blind-safe palette.
  static const char* kColors[] = {"#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442", "#000000"};
  return kColors[i % 8];
}

std::string gp_style() {
  return "set border 3 lc rgb '#444444'\n"
         "set tics nomirror textcolor rgb '#333333'\n"
         "set grid ytics lc rgb '#e3e3e3' lw 1 lt 1\n"
         "set key top center horizontal noopaque box lc rgb '#cccccc'\n"
         "set datafile missing 'NaN'\n";
}

}  // namespace dtlab::report::detail
