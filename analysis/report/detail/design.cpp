// The analysed design from a protocol; see design.h.
#include "analysis/report/detail/design.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace dtlab::report::detail {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

const protocol::Rendering* rendering_named(const protocol::Protocol& p, const std::string& name) {
  for (const auto& r : p.renderings)
    if (r.name == name) return &r;
  return nullptr;
}

// The reference study (STUDY.md): a rendering factor {off = standard, on =
// dt-*}, tasks T1..T4 of the article's types. Other protocols get no article column.
bool is_reference_design(const protocol::Protocol& p, const Design& d) {
  if (d.primary < 0 || p.factors[static_cast<size_t>(d.primary)].role != protocol::FactorRole::rendering) return false;
  const auto& lv = p.factors[static_cast<size_t>(d.primary)].levels;
  if (lv != std::vector<std::string>{"off", "on"}) return false;
  const auto* off = rendering_named(p, "off");
  const auto* on = rendering_named(p, "on");
  if (!off || !on || off->method != "standard" || on->method.rfind("dt-", 0) != 0) return false;
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
  const auto* r = rendering_named(*protocol, name);
  if (reference && f == primary) return (name == "off" ? "Standard" : "DynTrans") + std::string(" (") + name + ")";
  return r ? name + " (" + r->method + ")" : name;
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
  d.primary = 0;
  for (size_t f = 0; f < p.factors.size(); ++f) {
    d.all_factors.push_back(static_cast<int>(f));
    if (p.factors[f].role == protocol::FactorRole::scenario) d.scenario_factor = static_cast<int>(f);
  }
  bool have_rendering = false;
  for (size_t f = 0; f < p.factors.size(); ++f)
    if (p.factors[f].role == protocol::FactorRole::rendering) {
      d.primary = static_cast<int>(f);
      have_rendering = true;
    }
  if (!have_rendering)
    for (size_t f = 0; f < p.factors.size(); ++f)
      if (p.factors[f].role != protocol::FactorRole::scenario) {
        d.primary = static_cast<int>(f);
        break;
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
  d.reference = is_reference_design(p, d);
  return d;
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
