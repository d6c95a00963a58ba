// Internal: the helpers of detail/items.h: message text, answer checks, and
// what a simulated participant reads from the trials it has done so far.
// Never: draws from a stream except in ease_point (one normal per call).
#include <algorithm>
#include <charconv>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire::detail {

std::string quoted_list(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) s += (i ? ", \"" : "\"") + items[i] + "\"";
  return s;
}

std::string num(double v) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

Error answer_error(const Question& q, const std::string& message) { return Error{"", 0, 0, field_of(q), message}; }

Result<double> number_answer(const Question& q, const Answer& a, const std::string& expected) {
  const double* v = std::get_if<double>(&a);
  if (!v || !std::isfinite(*v)) return answer_error(q, "expected " + expected);
  return *v;
}

namespace {

bool matches(const PastTrial& t, const Levels& levels, const std::string& except) {
  for (const auto& [factor, level] : levels) {
    if (factor == except) continue;
    const auto it = std::find_if(t.levels.begin(), t.levels.end(), [&](const auto& l) { return l.first == factor; });
    if (it == t.levels.end() || it->second != level) return false;
  }
  return true;
}

}  // namespace

CellTimes cell_times(const std::vector<PastTrial>& history, const Levels& levels, const std::string& except) {
  CellTimes c;
  int none = 0;
  for (const auto& t : history) {
    if (t.practice || !matches(t, levels, except)) continue;
    c.mean += t.completion_s;
    none += !t.answered;
    ++c.n;
  }
  if (c.n > 0) {
    c.mean /= c.n;
    c.unanswered = static_cast<double>(none) / c.n;
  }
  return c;
}

Levels condition_of(const Question& q, const Experience& e) {
  if (!q.levels.empty()) return q.levels;
  return e.occasion ? e.occasion->levels : Levels{};
}

std::string compared_factor(const Levels& levels, const Experience& e) {
  if (levels.empty()) return "";
  const std::string rendering = e.design ? e.design->rendering_factor : "";
  for (const auto& [factor, level] : levels)
    if (factor == rendering) return factor;
  if (e.occasion && e.occasion->kind == When::Kind::level) return e.occasion->factor;
  return levels.front().first;
}

std::optional<Strain> strain_of(const Levels& levels, const Experience& e) {
  if (levels.empty()) return std::nullopt;
  const CellTimes cell = cell_times(e.history, levels, "");
  const CellTimes ref = cell_times(e.history, levels, compared_factor(levels, e));
  if (cell.n == 0 || ref.n == 0 || cell.mean <= 0 || ref.mean <= 0) return std::nullopt;
  return Strain{std::log2(cell.mean / ref.mean), cell.unanswered};
}

double ease_point(double lo, double hi, double step, const Question& q, Experience& e) {
  const double mid = 0.5 * (lo + hi), unit = (hi - lo) / 4.0;
  double raw = mid;
  if (const auto s = strain_of(condition_of(q, e), e)) raw = mid + unit * (-e.rating_gain * s->strain - 2.0 * s->unanswered);
  const double x = raw + unit * (e.rating_bias + e.rng->normal(0.0, e.rating_noise));
  const double snapped = lo + std::round((x - lo) / step) * step;
  return std::clamp(snapped, lo, hi);
}

}  // namespace dtlab::questionnaire::detail
