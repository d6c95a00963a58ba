// Documented ranges are the enforced ranges. docs/protocol.md's tables are
// parsed (every "A..B" in a key's range column) and compared with
// limits::documented(), the table the reader checks with; then, for every
// numeric key, the reference protocol with the key at each documented end
// reads without a range error for it, and one step outside each end is an
// error naming the key at its line. (That the ends also pass the whole
// validation, cross-key constraints included, is tests/session/test_runnable.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "study/protocol/limits.h"
#include "study/protocol/protocol.h"
#include "tests/common/run_cli.h"

namespace {

using namespace dtlab::protocol;

using dtlab::test::read_text;

double number(const std::string& text) {
  if (text == "2^63-1") return static_cast<double>(std::numeric_limits<std::int64_t>::max());
  return std::stod(text);
}

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::stringstream in(row);
  std::string cell;
  std::getline(in, cell, '|');  // before the first bar
  while (std::getline(in, cell, '|')) out.push_back(cell);
  if (!out.empty()) out.pop_back();  // after the last bar
  return out;
}

// The section a docs heading opens ("" for sections without a key table of their own).
std::string section_of(const std::string& heading) {
  if (heading.find("Top level") != std::string::npos) return "top level";
  if (heading.find(".tasks.") != std::string::npos) return "tasks";
  for (const char* s : {"session", "training", "breaks", "factors", "order", "scenarios", "rendering", "questionnaire",
                        "demographics", "reference_results"})
    if (heading.find(std::string("`[") + s) != std::string::npos) return s;
  return "";
}

// section -> key -> every range written in the key's range column, in order.
std::map<std::string, std::map<std::string, std::vector<std::pair<double, double>>>> documented_in_docs() {
  std::map<std::string, std::map<std::string, std::vector<std::pair<double, double>>>> out;
  std::stringstream in(read_text(DTLAB_SOURCE_DIR "/docs/protocol.md"));
  const std::regex range(R"((-?[0-9][0-9.e+]*|2\^63-1)\.\.(-?[0-9][0-9.e+]*(?:\^63-1)?))");
  std::string section;
  int range_column = -1;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) == 0) {
      section = section_of(line);
      range_column = -1;
      continue;
    }
    if (line.rfind("|", 0) != 0) {
      range_column = -1;
      continue;
    }
    const std::vector<std::string> row = cells(line);
    if (range_column < 0) {  // the header row of a table
      for (std::size_t c = 0; c < row.size(); ++c)
        if (row[c].find("range") != std::string::npos || row[c].find("values") != std::string::npos)
          range_column = static_cast<int>(c);
      if (range_column < 0) range_column = 1000;  // a table without ranges
      continue;
    }
    if (section.empty() || range_column >= static_cast<int>(row.size())) continue;
    const std::size_t a = row[0].find('`'), b = row[0].find('`', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string key = row[0].substr(a + 1, b - a - 1);
    const std::string& cell = row[static_cast<std::size_t>(range_column)];
    for (auto it = std::sregex_iterator(cell.begin(), cell.end(), range); it != std::sregex_iterator(); ++it)
      out[section][key].emplace_back(number((*it)[1]), number((*it)[2]));
  }
  return out;
}

TEST(Ranges, DocsStateExactlyTheEnforcedRanges) {
  auto docs = documented_in_docs();
  ASSERT_FALSE(docs.empty());
  std::map<std::string, std::map<std::string, std::vector<std::pair<double, double>>>> table;
  for (const limits::Documented& d : limits::documented()) table[std::string(d.section)][std::string(d.key)].emplace_back(d.min, d.max);
  for (const auto& [section, keys] : table)
    for (const auto& [key, ranges] : keys)
      EXPECT_EQ(docs[section][key], ranges) << "docs/protocol.md, section " << section << ", key " << key;
  for (const auto& [section, keys] : docs) {
    for (const auto& [key, ranges] : keys) {
      EXPECT_TRUE(ranges.empty() || table[section].count(key))
          << "docs/protocol.md documents a range for " << section << "." << key << " that the reader does not check";
    }
  }
  // Bounds stated in prose.
  const std::string text = read_text(DTLAB_SOURCE_DIR "/docs/protocol.md");
  EXPECT_NE(text.find("at most " + std::to_string(limits::kTrialsPerParticipant.max) + " trials"), std::string::npos);
  EXPECT_NE(text.find("more than " + std::to_string(limits::kOrderRows.max) + " rows"), std::string::npos);
  EXPECT_NE(text.find("At most " + std::to_string(limits::kConditions.max) + " conditions"), std::string::npos);
  EXPECT_NE(text.find(std::to_string(limits::kFactors.min) + " to " + std::to_string(limits::kFactors.max) + " factors"),
            std::string::npos);
}

// The reference protocol with one value replaced; `from` must occur in it.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::string shown(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  std::string t = s.str();
  if (t.find_first_of(".e") == std::string::npos) t += ".0";
  return t;
}

// How to write one documented key into the reference protocol.
struct Writer {
  std::string section, key;  // as in limits::documented()
  bool integer;
  std::string field;         // the diagnostic's field
  std::string from;          // text of the reference to replace; "{}" in `to` is the value
  std::string to;
};

std::vector<Writer> writers() {
  return {
      {"top level", "format", true, "format", "format = 1", "format = {}"},
      {"top level", "participants", true, "participants", "participants = 16", "participants = {}"},
      {"top level", "master_seed", true, "master_seed", "master_seed = 20080401", "master_seed = {}"},
      {"session", "time_limit_s", false, "session.time_limit_s", "time_limit_s = 3600", "time_limit_s = {}"},
      {"training", "time_limit_s", false, "training.time_limit_s", "time_limit_s = 300", "time_limit_s = {}"},
      {"training", "practice_trials", true, "training.practice_trials", "practice_trials = 0", "practice_trials = {}"},
      {"breaks", "every_trials", true, "breaks.every_trials", "[training]", "[breaks]\nevery_trials = {}\n[training]"},
      {"breaks", "min_s", false, "breaks.min_s", "[training]", "[breaks]\nmin_s = {}\n[training]"},
      {"breaks", "max_s", false, "breaks.max_s", "[training]", "[breaks]\nmax_s = {}\n[training]"},
      {"order", "rows", true, "order.rows", "scheme = \"latin-square\"", "scheme = \"random\"\nrows = {}"},
      {"order", "nested_rows", true, "order.nested_rows", "unit = \"conditions\"",
       "unit = \"blocks\"\nblock_factor = \"scenario\"\nnested_scheme = \"random\"\nnested_rows = {}"},
      {"scenarios", "objects", true, "scenarios.abstract.objects", "objects = 200", "objects = {}"},
      {"scenarios", "objects", true, "scenarios.walkthrough.objects", "objects = 50", "objects = {}"},
      {"scenarios", "extent", false, "scenarios.abstract.extent", "extent = 100.0", "extent = {}"},
      {"scenarios", "object_radius", false, "scenarios.abstract.object_radius[0]", "object_radius = [3.0, 6.0]",
       "object_radius = [{}, 6.0]"},
      {"scenarios", "object_radius", false, "scenarios.abstract.object_radius[1]", "object_radius = [3.0, 6.0]",
       "object_radius = [3.0, {}]"},
      {"scenarios", "target_ratio", false, "scenarios.abstract.target_ratio[0]", "target_ratio = [0.10, 0.20]",
       "target_ratio = [{}, 1.0]"},
      {"scenarios", "target_ratio", false, "scenarios.abstract.target_ratio[1]", "target_ratio = [0.10, 0.20]",
       "target_ratio = [0.001, {}]"},
      {"scenarios", "grid", true, "scenarios.walkthrough.grid[0]", "grid = [16, 16]", "grid = [{}, 16]"},
      {"scenarios", "cell_size", false, "scenarios.walkthrough.cell_size", "cell_size = 4.0", "cell_size = {}"},
      {"scenarios", "count_range", true, "scenarios.walkthrough.tasks.T4.count_range[0]", "count_range = [3, 8]",
       "count_range = [{}, 8]"},
      {"scenarios", "count_range", true, "scenarios.walkthrough.tasks.T4.count_range[1]", "count_range = [3, 8]",
       "count_range = [1, {}]"},
      {"tasks", "trials", true, "scenarios.abstract.tasks.T1.trials", "trials = 3", "trials = {}"},
      {"rendering", "a0", false, "rendering.on.a0", "a0 = 0.1", "a0 = {}"},
      {"rendering", "aT", false, "rendering.on.aT", "aT = 0.3", "aT = {}"},
      {"rendering", "gradient_width", true, "rendering.on.gradient_width", "gradient_width = 8", "gradient_width = {}"},
      {"rendering", "mask_resolution", true, "rendering.on.mask_resolution", "mask_resolution = 128",
       "mask_resolution = {}"},
      {"rendering", "layer_limit", true, "rendering.on.layer_limit", "layer_limit = 0", "layer_limit = {}"},
      {"rendering", "searchlight_radius", false, "rendering.on.searchlight_radius", "layer_limit = 0",
       "layer_limit = 0\nsearchlight_radius = {}"},
      {"rendering", "radius", false, "rendering.off.radius", "method = \"standard\"  ",
       "method = \"lens\"\ndistance = 100.0\nradius = {}\n"},
      {"rendering", "distance", false, "rendering.off.distance", "method = \"standard\"  ",
       "method = \"lens\"\nradius = 10.0\ndistance = {}\n"},
      {"rendering", "length", false, "rendering.off.length", "method = \"standard\"  ",
       "method = \"lens\"\nradius = 10.0\ndistance = 100.0\nlength = {}\n"},
      {"rendering", "screen_door_mask", true, "rendering.off.screen_door_mask", "method = \"standard\"  ",
       "method = \"screen-door\"\nscreen_door_mask = {}\n"},
      {"rendering", "falloff", false, "rendering.off.falloff", "method = \"standard\"  ",
       "method = \"vdt\"\nfalloff = {}\n"},
      {"rendering", "opaque_alpha", false, "rendering.off.opaque_alpha", "method = \"standard\"  ",
       "method = \"vdt\"\nopaque_alpha = {}\n"},
      {"rendering", "background_alpha", false, "rendering.off.background_alpha", "method = \"standard\"  ",
       "method = \"vdt\"\nbackground_alpha = {}\n"},
      {"rendering", "alpha", false, "rendering.off.alpha", "method = \"standard\"  ",
       "method = \"ghosting\"\nalpha = {}\n"},
      {"questionnaire", "scale", true, "questionnaire.rating.scale[0]", "scale = [0, 4]", "scale = [{}, 100]"},
      // The item types' keys: an item of the type added before [demographics.age].
      {"questionnaire", "points", true, "questionnaire.x.points", "[demographics.age]",
       "[questionnaire.x]\ntype = \"likert\"\nprompt = \"p\"\nlabels = [\"a\", \"b\"]\npoints = {}\n[demographics.age]"},
      {"questionnaire", "first", true, "questionnaire.x.first", "[demographics.age]",
       "[questionnaire.x]\ntype = \"likert\"\nprompt = \"p\"\nlabels = [\"a\", \"b\"]\npoints = 5\nfirst = {}\n[demographics.age]"},
      {"questionnaire", "range", false, "questionnaire.x.range[0]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"slider\"\nprompt = \"p\"\nrange = [{}, 1000000.0]\n[demographics.age]"},
      {"questionnaire", "range", false, "questionnaire.x.range[1]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"slider\"\nprompt = \"p\"\nrange = [-1000000.0, {}]\n[demographics.age]"},
      {"questionnaire", "step", false, "questionnaire.x.step", "[demographics.age]",
       "[questionnaire.x]\ntype = \"slider\"\nprompt = \"p\"\nrange = [-1000000.0, 1000000.0]\nstep = {}\n[demographics.age]"},
      {"questionnaire", "select", true, "questionnaire.x.select[0]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"multiple-choice\"\nprompt = \"p\"\noptions = [\"a\", \"b\"]\nselect = [{}, 32]\n[demographics.age]"},
      {"questionnaire", "select", true, "questionnaire.x.select[1]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"multiple-choice\"\nprompt = \"p\"\noptions = [\"a\", \"b\"]\nselect = [0, {}]\n[demographics.age]"},
      {"questionnaire", "range", false, "questionnaire.x.range[0]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"numeric\"\nprompt = \"p\"\nrange = [{}, 1000000000.0]\n[demographics.age]"},
      {"questionnaire", "range", false, "questionnaire.x.range[1]", "[demographics.age]",
       "[questionnaire.x]\ntype = \"numeric\"\nprompt = \"p\"\nrange = [-1000000000.0, {}]\n[demographics.age]"},
      {"questionnaire", "decimals", true, "questionnaire.x.decimals", "[demographics.age]",
       "[questionnaire.x]\ntype = \"numeric\"\nprompt = \"p\"\nrange = [0, 1]\ndecimals = {}\n[demographics.age]"},
      {"questionnaire", "max_length", true, "questionnaire.x.max_length", "[demographics.age]",
       "[questionnaire.x]\ntype = \"text\"\nprompt = \"p\"\nmax_length = {}\n[demographics.age]"},
      {"questionnaire", "lines", true, "questionnaire.x.lines", "[demographics.age]",
       "[questionnaire.x]\ntype = \"text\"\nprompt = \"p\"\nlines = {}\n[demographics.age]"},
      {"questionnaire", "scale", true, "questionnaire.rating.scale[1]", "scale = [0, 4]", "scale = [-100, {}]"},
      {"questionnaire", "pairs", true, "questionnaire.depth_test.pairs", "pairs = 3", "pairs = {}"},
      {"demographics", "range", true, "demographics.age.range[0]", "range = [16, 99]", "range = [{}, 1000000]"},
      {"demographics", "range", true, "demographics.age.range[1]", "range = [16, 99]", "range = [0, {}]"},
      {"reference_results", "participants", true, "reference_results.participants",
       "label = \"article\"\nparticipants = 16", "label = \"article\"\nparticipants = {}"},
      {"reference_results", "mean", false, "reference_results.results[0].mean.off", "mean = { off = 56.26,",
       "mean = { off = {},"},
      {"reference_results", "sd", false, "reference_results.results[0].sd.off", "sd = { off = 38.72,",
       "sd = { off = {},"},
  };
}

// Diagnostics of the reference with `w`'s key set to v; `range_error` says whether one of them is
// an out-of-range error for the key.
std::vector<dtlab::Diagnostic> diagnostics_with(const std::string& ref, const Writer& w, const std::string& v) {
  std::string to = w.to;
  to.replace(to.find("{}"), 2, v);
  return validate_protocol_text(with(ref, w.from, to), "r.toml");
}

const dtlab::Diagnostic* range_error(const std::vector<dtlab::Diagnostic>& diags, const std::string& field) {
  for (const auto& d : diags)
    if (d.severity == dtlab::Severity::error && d.where.field == field &&
        d.where.message.find("out of range") != std::string::npos)
      return &d;
  return nullptr;
}

TEST(Ranges, TheReaderEnforcesEachDocumentedRangeAtItsEnds) {
  const std::string ref = read_text(DTLAB_SOURCE_DIR "/protocols/elmqvist2008.toml");
  const auto all = writers();
  for (const limits::Documented& d : limits::documented()) {
    bool written = false;
    for (const Writer& w : all) {
      if (w.section != d.section || w.key != d.key) continue;
      if (w.key == "objects" && (d.max > limits::kWalkthroughObjects.max) != (w.field.find("abstract") != std::string::npos))
        continue;  // the abstract range with the abstract scenario, the walkthrough one with its own
      if (w.section == "questionnaire" && w.key == "range" &&
          (d.max > 1e6) != (w.to.find("\"numeric\"") != std::string::npos))
        continue;  // the slider's range with a slider, the numeric item's with a numeric item
      written = true;
      const auto text = [&](double v) { return w.integer ? std::to_string(static_cast<long long>(v)) : shown(v); };
      for (double v : {d.min, d.max}) {
        if (w.key == "master_seed" && v == d.max) v = 0;  // 2^63-1 is not a double; checked below
        const auto diags = diagnostics_with(ref, w, text(v));
        const dtlab::Diagnostic* e = range_error(diags, w.field);
        EXPECT_EQ(e, nullptr) << w.field << " = " << text(v) << " is documented: " << (e ? e->to_string() : "");
      }
      const double below = w.integer ? d.min - 1 : std::nextafter(d.min, -1e300);
      const double above = w.integer ? d.max + 1 : std::nextafter(d.max, 1e300);
      for (double v : {below, above}) {
        if (w.key == "master_seed" && v == above) continue;
        const auto diags = diagnostics_with(ref, w, text(v));
        const dtlab::Diagnostic* e = range_error(diags, w.field);
        ASSERT_NE(e, nullptr) << w.field << " = " << text(v) << " is outside the documented range";
        EXPECT_GE(e->where.line, 10) << e->to_string();
        EXPECT_GE(e->where.column, 1) << e->to_string();
      }
    }
    if (d.key == "levels" || d.key == "letters" || d.key == "options" || d.key == "labels" || d.key == "per" ||
        d.key == "anchors")
      continue;  // counts, not values
    EXPECT_TRUE(written) << d.section << "." << d.key << " has no writer in this test";
  }
  // master_seed's top end, exactly.
  const auto diags = validate_protocol_text(with(ref, "master_seed = 20080401", "master_seed = 9223372036854775807"), "r.toml");
  EXPECT_EQ(range_error(diags, "master_seed"), nullptr);
}

}  // namespace
