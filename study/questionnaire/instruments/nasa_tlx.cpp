// Instrument "nasa-tlx": the NASA Task Load Index (Hart & Staveland 1988;
// Hart 2006). Six subscales on the official form's wording, each a slider of
// 21 gradations (0..100 in steps of 5) from "Very Low" to "Very High"
// (Performance: "Perfect" to "Failure"); with `weights = true` also the 15
// pairwise comparisons of the subscales ("which contributed more to the
// workload?"). Scales: the raw TLX (the mean of the six ratings; Hart 2006)
// and, with weights, the weighted workload: each subscale's weight is the
// number of comparisons it won (0..5, summing to 15), and the score is
// sum(weight x rating) / 15 (Hart & Staveland 1988, NASA TLX manual).
#include <algorithm>
#include <array>
#include <cmath>

#include "study/questionnaire/detail/items.h"

namespace dtlab::questionnaire {
namespace {

struct Dimension {
  const char* sub;
  const char* title;
  const char* question;
  const char* left;
  const char* right;
};

// The official NASA-TLX rating sheet, in its order.
constexpr std::array<Dimension, 6> kDims{{
    {"mental", "Mental Demand", "How mentally demanding was the task?", "Very Low", "Very High"},
    {"physical", "Physical Demand", "How physically demanding was the task?", "Very Low", "Very High"},
    {"temporal", "Temporal Demand", "How hurried or rushed was the pace of the task?", "Very Low", "Very High"},
    {"performance", "Performance", "How successful were you in accomplishing what you were asked to do?", "Perfect",
     "Failure"},
    {"effort", "Effort", "How hard did you have to work to accomplish your level of performance?", "Very Low",
     "Very High"},
    {"frustration", "Frustration", "How insecure, discouraged, irritated, stressed, and annoyed were you?", "Very Low",
     "Very High"},
}};

std::string pair_sub(std::size_t a, std::size_t b) { return std::string("w.") + kDims[a].sub + "-" + kDims[b].sub; }

std::vector<Item> items(const Keys& keys) {
  std::vector<Item> out;
  for (const Dimension& d : kDims) {
    Item it;
    it.sub = d.sub;
    it.type = find_item_type("slider");
    it.prompt = std::string(d.title) + "\n" + d.question;
    it.keys = {{"range", NumberPair{0, 100}}, {"step", 5.0}, {"anchors", std::vector<std::string>{d.left, d.right}}};
    out.push_back(std::move(it));
  }
  const auto w = keys.find("weights");
  if (w == keys.end() || !std::get<bool>(w->second)) return out;
  for (std::size_t a = 0; a < kDims.size(); ++a)
    for (std::size_t b = a + 1; b < kDims.size(); ++b) {
      Item it;
      it.sub = pair_sub(a, b);
      it.type = find_item_type("choice");
      it.prompt = "Which of the two was the more important contributor to the workload of the task?";
      it.keys = {{"options", std::vector<std::string>{kDims[a].sub, kDims[b].sub}},
                 {"labels", std::vector<std::string>{kDims[a].title, kDims[b].title}},
                 {"neutral", std::string()}};
      out.push_back(std::move(it));
    }
  return out;
}

bool weighted(const Keys& keys) {
  const auto w = keys.find("weights");
  return w != keys.end() && std::get<bool>(w->second);
}

std::vector<Scale> scales(const Keys& keys) {
  std::vector<Scale> s{{"raw", "Raw TLX (mean of the six subscales)", 0, 100}};
  if (weighted(keys)) s.push_back({"weighted", "Weighted TLX (pairwise-comparison weights)", 0, 100});
  return s;
}

std::vector<std::optional<double>> score(const Keys& keys, const SubAnswers& answers) {
  std::array<double, 6> rating{};
  bool complete = true;
  for (std::size_t i = 0; i < kDims.size(); ++i) {
    const auto it = answers.find(kDims[i].sub);
    const double* v = it == answers.end() ? nullptr : std::get_if<double>(&it->second);
    if (!v || !std::isfinite(*v) || *v < 0 || *v > 100) complete = false;
    else rating[i] = *v;
  }
  std::optional<double> raw;
  if (complete) {
    double sum = 0;
    for (double r : rating) sum += r;
    raw = sum / 6.0;
  }
  if (!weighted(keys)) return {raw};
  std::array<int, 6> weight{};
  bool tallied = complete;
  for (std::size_t a = 0; a < kDims.size(); ++a)
    for (std::size_t b = a + 1; b < kDims.size(); ++b) {
      const auto it = answers.find(pair_sub(a, b));
      const std::string* won = it == answers.end() ? nullptr : std::get_if<std::string>(&it->second);
      if (won && *won == kDims[a].sub) ++weight[a];
      else if (won && *won == kDims[b].sub) ++weight[b];
      else tallied = false;
    }
  std::optional<double> wwl;
  if (tallied) {
    double sum = 0;
    for (std::size_t i = 0; i < kDims.size(); ++i) sum += weight[i] * rating[i];
    wwl = sum / 15.0;
  }
  return {raw, wwl};
}

// A participant's constants: how much each subscale weighs for them, and how high they rate workload.
struct TlxTraits {
  std::array<double, 6> importance{};
  double bias = 0;
};
TlxTraits tlx_traits(std::uint64_t seed) {
  Stream r(mix64(seed, 0x746c78ULL));  // "tlx"
  const std::array<double, 6> mean{1.0, -1.0, 0.3, 0.2, 0.6, 0.0};
  TlxTraits t;
  for (std::size_t i = 0; i < 6; ++i) t.importance[i] = r.normal(mean[i], 0.5);
  t.bias = r.normal(0.0, 10.0);
  return t;
}

// docs/sim.md, "Instruments": demands rise with how much slower than its own average the
// participant was in the occasion's condition (strain, log2 of the time ratio) and with the
// share of trials it left unanswered; physical demand stays low (a mouse and a keyboard).
Answer simulate_answer(const Item& item, const Question& q, Experience& e) {
  const TlxTraits t = tlx_traits(e.seed);
  for (std::size_t a = 0; a < kDims.size(); ++a)
    for (std::size_t b = a + 1; b < kDims.size(); ++b)
      if (item.sub == pair_sub(a, b)) {
        const double da = t.importance[a] + e.rng->normal(0.0, 0.5), db = t.importance[b] + e.rng->normal(0.0, 0.5);
        return std::string(da >= db ? kDims[a].sub : kDims[b].sub);
      }
  const auto s = detail::strain_of(detail::condition_of(q, e), e);
  const double strain = s ? s->strain : 0.0, missed = s ? s->unanswered : 0.0;
  //                                  mental physical temporal performance effort frustration
  const std::array<double, 6> base{55, 15, 40, 25, 50, 25};
  const std::array<double, 6> per_strain{30, 5, 25, 20, 30, 30};
  const std::array<double, 6> per_missed{20, 0, 10, 45, 15, 40};
  for (std::size_t i = 0; i < kDims.size(); ++i) {
    if (item.sub != kDims[i].sub) continue;
    const double x = base[i] + per_strain[i] * strain + per_missed[i] * missed + t.bias + e.rng->normal(0.0, 8.0);
    return std::clamp(std::round(x / 5.0) * 5.0, 0.0, 100.0);
  }
  return 50.0;  // not one of its items: unreachable for items the instrument made
}

}  // namespace

const Instrument& instrument_nasa_tlx() {
  static const Instrument i = [] {
    Instrument i;
    i.name = "nasa-tlx";
    i.title = "NASA Task Load Index (NASA-TLX)";
    i.citation = "Hart & Staveland (1988); Hart (2006); NASA Task Load Index (TLX) v1.0 manual";
    i.keys = {KeySpec::of("weights", KeyKind::boolean).or_else(false)};
    i.items = items;
    i.scales = scales;
    i.score = score;
    i.simulate = simulate_answer;
    return i;
  }();
  return i;
}

}  // namespace dtlab::questionnaire
