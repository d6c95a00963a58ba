// The post-test questionnaire, item by item as the protocol declares them.
// Ratings asked per level of the primary factor: Friedman's test across its
// levels, per combination of the item's other factors (e.g. per scenario)
// and overall (a participant's mean over those combinations). Other
// ratings: descriptives. Choices: counts and proportions, and for a
// two-level factor a sign test among the participants who chose a side.
// Depth tests: pairs judged correctly. Answer scopes read
// "factor=level;factor=level" (levels matched without regard to case); a
// depth test's answers are summed per participant (one answer holding the
// number correct, or one 0/1 answer per pair). Computes the
// QuestionnaireResult only; layout_questionnaire.cpp lays it out.
#include <cctype>
#include <cmath>
#include <map>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"

namespace dtlab::report::detail {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// factor index -> level index from "scenario=abstract;transparency=on"; -1 entries when absent/unknown.
std::vector<int> parse_scope(const Design& d, const std::string& scope) {
  std::vector<int> out(d.all_factors.size(), -1);
  size_t start = 0;
  while (start <= scope.size()) {
    size_t end = scope.find(';', start);
    if (end == std::string::npos) end = scope.size();
    const std::string part = scope.substr(start, end - start);
    const size_t eq = part.find('=');
    if (eq != std::string::npos)
      for (int f : d.all_factors)
        if (lower(d.factor(f).name) == lower(part.substr(0, eq)))
          for (size_t l = 0; l < d.factor(f).levels.size(); ++l)
            if (lower(d.factor(f).levels[l]) == lower(part.substr(eq + 1))) out[static_cast<size_t>(f)] = static_cast<int>(l);
    start = end + 1;
  }
  return out;
}

CellMatrix empty_matrix(const Design& d, const std::vector<std::string>& subjects, int factor) {
  CellMatrix m;
  m.factors = {factor};
  for (size_t l = 0; l < d.factor(factor).levels.size(); ++l) {
    m.cell_levels.push_back({static_cast<int>(l)});
    m.cell_names.push_back(d.factor(factor).levels[l]);
  }
  m.subjects = subjects;
  m.value.assign(subjects.size(), std::vector<double>(m.cells(), std::nan("")));
  m.trials.assign(subjects.size(), std::vector<int>(m.cells(), 0));
  return m;
}

std::vector<std::string> answered_by(const StudyData& data, const std::string& item) {
  std::vector<std::string> out;
  for (const auto& a : data.answers)
    if (a.item == item && (out.empty() || out.back() != a.participant)) out.push_back(a.participant);
  return out;
}

size_t index_of(const std::vector<std::string>& v, const std::string& x) {
  return static_cast<size_t>(std::find(v.begin(), v.end(), x) - v.begin());
}

// A key of the item's type, or `none` when its type does not declare it (a rating's per, ...).
const std::vector<std::string>& strings_or_none(const protocol::QuestionnaireItem& item, const char* key) {
  static const std::vector<std::string> none;
  if (!item.type) return none;
  for (const auto& k : item.type->keys)
    if (k.name == key) return item.strings(key);
  return none;
}

using questionnaire::Measure;

// The items this section reports: asked at the end, not part of an instrument, not free text
// (section_instruments.cpp reports the others).
bool reported_here(const protocol::QuestionnaireItem& item) {
  return item.type && !item.instrument && item.when.kind == questionnaire::When::Kind::end &&
         item.type->measure != Measure::text;
}

// A rating's participant x primary-level matrices: one per combination of its other `per` factors (keyed by
// their levels, -1 = unknown) and `all`, a participant's mean over the combinations (complete ones only).
struct RatingMatrices {
  std::map<std::vector<int>, CellMatrix> split;
  CellMatrix all;
};

RatingMatrices rating_matrices(const Context& ctx, const protocol::QuestionnaireItem& item,
                               const std::vector<std::string>& subjects, const std::vector<int>& others) {
  const Design& d = ctx.design;
  const int pf = d.primary;
  RatingMatrices out;
  out.all = empty_matrix(d, subjects, pf);
  CellMatrix& all = out.all;
  std::vector<std::vector<double>> sum(subjects.size(), std::vector<double>(all.cells(), 0));
  std::vector<std::vector<int>> cnt(subjects.size(), std::vector<int>(all.cells(), 0));
  for (const auto& a : ctx.data.answers) {
    if (a.item != item.id || !a.number) continue;
    const auto lv = parse_scope(d, a.scope);
    if (lv[static_cast<size_t>(pf)] < 0) continue;
    std::vector<int> key;
    for (int f : others) key.push_back(lv[static_cast<size_t>(f)]);
    auto it = out.split.find(key);
    if (it == out.split.end()) it = out.split.emplace(key, empty_matrix(d, subjects, pf)).first;
    const size_t si = index_of(subjects, a.participant), c = static_cast<size_t>(lv[static_cast<size_t>(pf)]);
    it->second.value[si][c] = *a.number;
    it->second.trials[si][c] = 1;
    sum[si][c] += *a.number;
    ++cnt[si][c];
  }
  size_t combos = 1;
  for (int f : others) combos *= d.factor(f).levels.size();
  for (size_t si = 0; si < subjects.size(); ++si)
    for (size_t c = 0; c < all.cells(); ++c) {
      all.trials[si][c] = cnt[si][c];
      if (static_cast<size_t>(cnt[si][c]) == combos) all.value[si][c] = sum[si][c] / cnt[si][c];
    }
  return out;
}

// Friedman's test of one rating matrix (its scope: the combination of the other factors, or "overall").
void rating_test(Context& ctx, const protocol::QuestionnaireItem& item, const CellMatrix& m, const std::string& scope,
                 QuestionnaireItemResult& out, Tally& tally) {
  out.tests.push_back(&ctx.add_test(
      "questionnaire", run_friedman(ctx.keep(m), ctx.design, item.id, "rating", scope, ctx.options.seed), tally));
}

// A rating asked per level of the primary factor: a test per combination of its other factors, and overall.
void rating_item(Context& ctx, const protocol::QuestionnaireItem& item, const std::vector<std::string>& subjects,
                 const std::vector<std::string>& per, QuestionnaireItemResult& out, Tally& tally) {
  const Design& d = ctx.design;
  std::vector<int> others;
  for (const auto& name : per)
    for (int f : d.all_factors)
      if (d.factor(f).name == name && f != d.primary) others.push_back(f);
  const RatingMatrices rm = rating_matrices(ctx, item, subjects, others);
  out.kind = QuestionnaireItemResult::Kind::rating;
  for (const auto& [key, m] : rm.split) {
    std::string scope;
    bool known = true;
    for (size_t k = 0; k < others.size(); ++k) {
      if (key[k] < 0) known = false;
      else scope += (scope.empty() ? "" : ", ") + d.factor(others[k]).levels[static_cast<size_t>(key[k])];
    }
    if (known) rating_test(ctx, item, m, scope.empty() ? "all" : scope, out, tally);
  }
  if (!others.empty()) rating_test(ctx, item, rm.all, "overall", out, tally);
}

// Per participant: a rating (mean if asked several times) or the depth-test pairs correct (summed); descriptives.
void numeric_item(const Context& ctx, const protocol::QuestionnaireItem& item, const std::vector<std::string>& subjects,
                  QuestionnaireItemResult& out) {
  const Measure measure = item.type->measure;
  std::vector<double> v;
  for (const auto& who : subjects) {
    double sum = 0;
    int n = 0;
    for (const auto& a : ctx.data.answers)
      if (a.item == item.id && a.participant == who && a.number) {
        sum += *a.number;
        ++n;
      }
    if (n) v.push_back(measure == Measure::correct ? sum : sum / n);
  }
  const auto ds = stats::describe(v);
  const bool depth = measure == Measure::correct;
  const int pairs = depth ? static_cast<int>(item.integer("pairs")) : 0;
  const questionnaire::NumberPair b = item.type->bounds ? item.type->bounds(item) : questionnaire::NumberPair{};
  out.scale =
      depth ? "pairs correct of " + std::to_string(pairs) : "scale " + csv_number(b.min) + "–" + csv_number(b.max);
  out.kind = QuestionnaireItemResult::Kind::numeric;
  out.descriptives = ds;
  if (depth) out.proportion_correct = ds.mean / pairs;
}

// The answers of a choice item counted per option ("other: ..." for an answer outside them).
struct ChoiceCounts {
  std::vector<std::string> options;  // the item's options, or its factor's levels
  int factor = -1;                   // the factor whose levels are the options, -1 = none
  std::string neutral;
  std::map<std::string, int> count;
  int answered = 0;
  std::vector<double> first, second;  // indicators for a sign test between two options
};

ChoiceCounts count_choices(const Context& ctx, const protocol::QuestionnaireItem& item,
                           const std::vector<std::string>& subjects) {
  const Design& d = ctx.design;
  const Measure measure = item.type->measure;
  ChoiceCounts c;
  c.options = item.strings("options");
  const std::string& item_factor = measure == Measure::nominal ? item.text("factor") : std::string();
  c.neutral = measure == Measure::nominal ? item.text("neutral") : std::string();
  for (int f : d.all_factors)
    if (!item_factor.empty() && d.factor(f).name == item_factor) {
      c.factor = f;
      c.options = d.factor(f).levels;
    }
  for (const auto& who : subjects)
    for (const auto& a : ctx.data.answers)
      if (a.item == item.id && a.participant == who && a.text) {
        ++c.answered;
        if (measure == Measure::multiple) {  // each option chosen counts once
          for (const auto& o : c.options)
            if (("\n" + *a.text + "\n").find("\n" + o + "\n") != std::string::npos) ++c.count[o];
          continue;
        }
        std::string chosen = "other: " + *a.text;
        for (const auto& o : c.options)
          if (lower(o) == lower(*a.text)) chosen = o;
        if (!c.neutral.empty() && lower(c.neutral) == lower(*a.text)) chosen = c.neutral;
        ++c.count[chosen];
        if (c.options.size() == 2) {
          c.first.push_back(chosen == c.options[0] ? 1 : 0);
          c.second.push_back(chosen == c.options[1] ? 1 : 0);
        }
      }
  return c;
}

// A choice item: counts and proportions per option, and for two options a sign test.
void choice_item(Context& ctx, const protocol::QuestionnaireItem& item, const std::vector<std::string>& subjects,
                 QuestionnaireItemResult& out, Tally& tally) {
  const Design& d = ctx.design;
  const ChoiceCounts c = count_choices(ctx, item, subjects);
  const auto& options = c.options;
  out.kind = QuestionnaireItemResult::Kind::choice;
  out.answered = c.answered;
  for (const auto& [option, n] : c.count) {
    const double p = c.answered ? static_cast<double>(n) / c.answered : std::nan("");
    const double sd = c.answered > 1 ? std::sqrt(p * (1 - p) * c.answered / (c.answered - 1)) : std::nan("");
    const std::string label = c.factor >= 0 && option.rfind("other: ", 0) != 0 && option != c.neutral
                                  ? d.level_label(c.factor, static_cast<int>(index_of(options, option)))
                                  : option;
    out.choices[option] = {n, p, sd, label};
  }
  if (item.type->measure == Measure::nominal && options.size() == 2 && c.answered > 0) {
    out.sign_test = stats::sign_test(c.second, c.first);
    out.first_option = options[0];
    out.second_option = options[1];
    ++tally.tests;
  }
}

// One item by its measure.
QuestionnaireItemResult questionnaire_item(Context& ctx, const protocol::QuestionnaireItem& item, Tally& tally) {
  const Design& d = ctx.design;
  const auto subjects = answered_by(ctx.data, item.id);
  QuestionnaireItemResult ji;
  ji.id = item.id;
  ji.type = item.type->name;
  ji.prompt = item.prompt;
  ji.n = subjects.size();
  const Measure measure = item.type->measure;
  const std::vector<std::string>& per = strings_or_none(item, "per");
  const bool per_primary = std::find(per.begin(), per.end(), d.factor(d.primary).name) != per.end();
  if (measure == Measure::ordinal && per_primary)
    rating_item(ctx, item, subjects, per, ji, tally);
  else if (measure == Measure::ordinal || measure == Measure::interval || measure == Measure::correct)
    numeric_item(ctx, item, subjects, ji);
  else if (measure == Measure::nominal || measure == Measure::multiple)
    choice_item(ctx, item, subjects, ji, tally);
  return ji;
}

}  // namespace

QuestionnaireResult section_questionnaire(Context& ctx) {
  QuestionnaireResult result;
  std::vector<protocol::QuestionnaireItem> items;
  for (const auto& item : ctx.design.protocol->questionnaire)
    if (reported_here(item)) items.push_back(item);
  if (items.empty()) return result;
  result.items.emplace();
  if (ctx.data.answers.empty()) return result;
  for (const auto& item : items) result.items->push_back(questionnaire_item(ctx, item, result.tally));
  return result;
}

}  // namespace dtlab::report::detail
