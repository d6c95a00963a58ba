// The analysed design from a protocol; see report_design.h.
#include "analysis/report/detail/report_design.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "analysis/report/detail/format.h"
#include "study/technique/technique.h"

namespace dtlab::report::detail {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The reference study: a rendering factor {off = standard, on = dt-seed or
// dt-fast}, tasks T1..T4 of the article's types. Other protocols get no article column.
bool is_reference_design(const protocol::Protocol& p, const Design& d) {
  if (d.primary < 0 || p.factors[static_cast<size_t>(d.primary)].role != protocol::FactorRole::rendering) return false;
  const auto& lv = p.factors[static_cast<size_t>(d.primary)].levels;
  if (lv != std::vector<std::string>{"off", "on"}) return false;
  const auto* off = protocol::find_rendering(p, "off");
  const auto* on = protocol::find_rendering(p, "on");
  if (!off || !on) return false;
  // off: the plain rendering; on: the article's dynamic transparency or a method approximating it
  // (the technique registry says which).
  const technique::Technique* plain = technique::find(off->method);
  const technique::Technique* dt = technique::find(on->method);
  if (!plain || !dt || plain->id != technique::Method::standard) return false;
  if (dt->id != technique::Method::dt_seed && dt->approximates != technique::Method::dt_seed) return false;
  const std::vector<std::pair<std::string, protocol::TaskType>> want = {
      {"T1", protocol::TaskType::count_targets},
      {"T2", protocol::TaskType::identify_letter},
      {"T3", protocol::TaskType::find_unique},
      {"T4", protocol::TaskType::count_kind}};
  if (d.tasks.size() != want.size()) return false;
  for (size_t i = 0; i < want.size(); ++i)
    if (d.tasks[i].id != want[i].first || d.tasks[i].type != want[i].second) return false;
  return true;
}

}  // namespace

std::string Design::level_label(int f, int level) const {
  const auto& fac = factor(f);
  const std::string& name = fac.levels[static_cast<size_t>(level)];
  if (fac.role != protocol::FactorRole::rendering) return name;
  const auto* r = protocol::find_rendering(*protocol, name);
  if (article_names && f == primary) return (name == "off" ? "Standard" : "DynTrans") + std::string(" (") + name + ")";
  return r && r->method != name ? name + " (" + r->method + ")" : name;  // "standard", not "standard (standard)"
}

const TaskInfo* Design::task(const std::string& id) const {
  for (const auto& t : tasks)
    if (t.id == id) return &t;
  return nullptr;
}

std::string Design::scenario_of(const TrialRow& t) const {
  if (scenario_factor >= 0) return t.levels[static_cast<size_t>(scenario_factor)];
  return protocol->scenarios.empty() ? std::string() : protocol->scenarios.front().name;
}

int Design::tasks_in(const std::string& scenario) const {
  int n = 0;
  for (const auto& t : tasks) n += t.scenario == scenario ? 1 : 0;
  return n;
}

std::string Design::task_label(const TaskInfo& t) const { return t.id + " (" + task_type_label(t.type) + ")"; }

std::string Design::tasks_note() const {
  std::string s = "Tasks: ";
  for (size_t i = 0; i < tasks.size(); ++i)
    s += (i ? "; " : "") + tasks[i].id + " " + task_type_label(tasks[i].type) + " (" + tasks[i].scenario + ")";
  return s + ".";
}

Design make_design(const protocol::Protocol& p) {
  Design d;
  d.protocol = &p;
  d.primary = std::max(0, protocol::compared_factor(p));  // the factor published results are given per
  for (size_t f = 0; f < p.factors.size(); ++f) {
    d.all_factors.push_back(static_cast<int>(f));
    if (p.factors[f].role == protocol::FactorRole::scenario) d.scenario_factor = static_cast<int>(f);
  }
  for (size_t s = 0; s < p.scenarios.size(); ++s) {
    // The conditions that use this scenario; a factor varies within the
    // scenario's tasks when those conditions hold more than one of its levels.
    std::vector<std::set<int>> seen(p.factors.size());
    for (const auto& c : p.conditions)
      if (c.scenario == static_cast<int>(s))
        for (size_t f = 0; f < p.factors.size(); ++f) seen[f].insert(c.levels[f]);
    std::vector<int> varying;
    for (size_t f = 0; f < p.factors.size(); ++f)
      if (seen[f].size() > 1) varying.push_back(static_cast<int>(f));
    for (const auto& t : p.scenarios[s].tasks)
      d.tasks.push_back({t.id, t.type, p.scenarios[s].name, t.trials, varying});
  }
  d.reference = p.reference_results.has_value();
  d.article_names = d.reference && is_reference_design(p, d);
  return d;
}

const protocol::ReferenceResult* Design::published(const std::string& measure, const std::string& scope) const {
  if (!protocol->reference_results) return nullptr;
  for (const auto& r : protocol->reference_results->results)
    if (r.measure == measure && r.scope == scope) return &r;
  return nullptr;
}

std::vector<std::string> Design::published_header(bool with_f) const {
  if (!reference) return {};
  std::vector<std::string> h;
  const auto& levels = factor(primary).levels;
  for (size_t l = 0; l < levels.size(); ++l)
    h.push_back(article_names ? (levels[l] == "off" ? "Standard" : "DynTrans") : levels[l]);
  if (with_f) {
    const int n = protocol->reference_results->participants;
    const int df1 = static_cast<int>(levels.size()) - 1;
    h.push_back(n > 1 ? "F(" + std::to_string(df1) + "," + std::to_string(df1 * (n - 1)) + ")" : "F");
  }
  h.push_back("p");
  return h;
}

std::vector<std::string> Design::published_cells(const std::string& measure, const std::string& scope, int decimals,
                                                 bool with_f) const {
  if (!reference) return {};
  std::vector<std::string> cells(published_header(with_f).size(), kDash);
  const protocol::ReferenceResult* r = published(measure, scope);
  if (!r) return cells;
  for (size_t l = 0; l < r->mean.size() && l + 1 < cells.size(); ++l) cells[l] = mean_sd(r->mean[l], r->sd[l], decimals);
  if (with_f && !r->F.empty()) cells[cells.size() - 2] = r->F;
  if (!r->p.empty()) cells.back() = r->p;
  return cells;
}

std::string Design::published_group(const std::vector<std::string>& measures) const {
  if (!reference) return "";
  std::vector<std::string> where;
  for (const auto& r : protocol->reference_results->results)
    if (std::find(measures.begin(), measures.end(), r.measure) != measures.end() && !r.location.empty() && std::find(where.begin(), where.end(), r.location) == where.end())
      where.push_back(r.location);
  std::string g = protocol->reference_results->label;
  for (size_t i = 0; i < where.size(); ++i) g += (i ? ", " : " (") + where[i] + (i + 1 == where.size() ? ")" : "");
  return g;
}

std::string Design::published_note(const std::vector<std::string>& measures) const {
  if (!reference) return "";
  const auto& rr = *protocol->reference_results;
  std::string label = rr.label;
  if (!label.empty()) label[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(label[0])));
  const std::string group = published_group(measures);
  const size_t open = group.find(" (");
  return label + ": the values printed in " + rr.source +
         (open == std::string::npos ? "" : ", " + group.substr(open + 2, group.size() - open - 3)) +
         (rr.participants > 0 ? " (" + std::to_string(rr.participants) + " participants" : " (") +
         (rr.participants > 0 ? "; " : "") + "tests as printed there), declared in the protocol's "
         "[reference_results]. Quoted for comparison, not computed here.";
}

std::string Design::published_summary(const std::string& measure, const std::string& scope, int decimals) const {
  const protocol::ReferenceResult* r = published(measure, scope);
  if (!r) return "";
  std::string out;
  if (!r->per_level && !r->mean.empty()) out = mean_sd(r->mean[0], r->sd[0], decimals);
  if (r->per_level)
    for (size_t l = 0; l < r->mean.size(); ++l)
      out += (l ? ", " : "") + factor(primary).levels[l] + " " + mean_sd(r->mean[l], r->sd[l], decimals);
  if (!r->p.empty()) out += (out.empty() ? "p " : "; p ") + r->p;
  return out;
}

std::string Design::published_cf() const {
  return reference ? "; cf. " + protocol->reference_results->source : "";
}

std::string task_type_label(protocol::TaskType t) {
  std::string s(protocol::to_string(t));
  std::replace(s.begin(), s.end(), '-', ' ');
  return s;
}

std::vector<std::string> simulated_participants(const StudyData& d) {
  std::vector<std::string> out;
  for (const auto& p : d.participants) {
    bool sim = false;
    for (const auto& [k, v] : p.demographics) {
      const std::string key = lower(k), val = lower(v);
      if (key == "simulated" && (val == "true" || val == "1" || val == "yes")) sim = true;
      if ((key == "source" || key == "provenance" || key == "kind" || key == "agent") &&
          val.find("sim") != std::string::npos)
        sim = true;
    }
    if (sim) out.push_back(p.id);
  }
  return out;
}

}  // namespace dtlab::report::detail
