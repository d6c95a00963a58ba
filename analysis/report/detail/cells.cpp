// Participant x cell aggregation; see cells.h.
#include "analysis/report/detail/cells.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/report/detail/format.h"

namespace dtlab::report::detail {

std::vector<size_t> CellMatrix::complete() const {
  std::vector<size_t> out;
  for (size_t s = 0; s < subjects.size(); ++s) {
    bool ok = true;
    for (double v : value[s]) ok = ok && !std::isnan(v);
    if (ok) out.push_back(s);
  }
  return out;
}

std::vector<std::string> CellMatrix::missing_notes() const {
  std::vector<std::string> out;
  for (size_t s = 0; s < subjects.size(); ++s) {
    std::string note;
    for (size_t c = 0; c < cells(); ++c) {
      if (!std::isnan(value[s][c])) continue;
      note += (note.empty() ? "" : ", ") + cell_names[c] + (trials[s][c] == 0 ? ": no trial" : ": no value");
    }
    if (!note.empty()) out.push_back(subjects[s] + " (" + note + ")");
  }
  return out;
}

CellMatrix aggregate(const StudyData& data, const Design& design, const std::vector<std::string>& subjects,
                     const std::vector<int>& factors, const TrialFilter& include, const Reducer& reduce) {
  CellMatrix m;
  m.factors = factors;
  // Cells: the full factorial of `factors`, first factor slowest.
  m.cell_levels = {{}};
  for (int f : factors) {
    std::vector<std::vector<int>> next;
    for (const auto& prefix : m.cell_levels)
      for (int l = 0; l < static_cast<int>(design.factor(f).levels.size()); ++l) {
        auto c = prefix;
        c.push_back(l);
        next.push_back(std::move(c));
      }
    m.cell_levels = std::move(next);
  }
  for (const auto& c : m.cell_levels) {
    std::string name;
    for (size_t k = 0; k < c.size(); ++k)
      name += (k ? "/" : "") + design.factor(factors[k]).levels[static_cast<size_t>(c[k])];
    m.cell_names.push_back(factors.empty() ? "all" : name);
  }
  m.subjects = subjects;
  std::map<std::string, size_t> subject_index;
  for (size_t s = 0; s < subjects.size(); ++s) subject_index[subjects[s]] = s;

  std::vector<std::vector<std::vector<const TrialRow*>>> bins(
      subjects.size(), std::vector<std::vector<const TrialRow*>>(m.cells()));
  for (const auto& t : data.trials) {
    auto it = subject_index.find(t.participant);
    if (it == subject_index.end() || !include(t)) continue;
    size_t cell = 0;
    bool known = true;
    for (int f : factors) {
      const int l = t.level_index[static_cast<size_t>(f)];
      if (l < 0) known = false;
      cell = cell * design.factor(f).levels.size() + static_cast<size_t>(std::max(l, 0));
    }
    if (known) bins[it->second][cell].push_back(&t);
  }
  m.value.assign(subjects.size(), std::vector<double>(m.cells(), kNaN));
  m.trials.assign(subjects.size(), std::vector<int>(m.cells(), 0));
  for (size_t s = 0; s < subjects.size(); ++s)
    for (size_t c = 0; c < m.cells(); ++c) {
      m.trials[s][c] = static_cast<int>(bins[s][c].size());
      if (!bins[s][c].empty()) m.value[s][c] = reduce(bins[s][c]);
    }
  return m;
}

std::vector<double> marginal(const CellMatrix& m, size_t k, int level) {
  std::vector<double> out(m.subjects.size(), kNaN);
  for (size_t s = 0; s < m.subjects.size(); ++s) {
    double sum = 0;
    int n = 0;
    bool missing = false;
    for (size_t c = 0; c < m.cells(); ++c) {
      if (m.level(c, k) != level) continue;
      if (std::isnan(m.value[s][c])) missing = true;
      sum += m.value[s][c];
      ++n;
    }
    if (!missing && n > 0) out[s] = sum / n;
  }
  return out;
}

CellMatrix marginal_matrix(const CellMatrix& m, size_t k) {
  CellMatrix out;
  out.factors = {m.factors[k]};
  out.subjects = m.subjects;
  int levels = 0;
  for (size_t c = 0; c < m.cells(); ++c) levels = std::max(levels, m.level(c, k) + 1);
  for (int l = 0; l < levels; ++l) {
    out.cell_levels.push_back({l});
    for (size_t c = 0; c < m.cells(); ++c)
      if (m.level(c, k) == l) {
        std::string name = m.cell_names[c];  // "off/abstract": the k-th part
        for (size_t i = 0; i < k; ++i) name = name.substr(name.find('/') + 1);
        out.cell_names.push_back(name.substr(0, name.find('/')));
        break;
      }
  }
  out.value.assign(m.subjects.size(), std::vector<double>(static_cast<size_t>(levels), kNaN));
  out.trials.assign(m.subjects.size(), std::vector<int>(static_cast<size_t>(levels), 0));
  for (int l = 0; l < levels; ++l) {
    const auto v = marginal(m, k, l);
    for (size_t s = 0; s < m.subjects.size(); ++s) {
      out.value[s][static_cast<size_t>(l)] = v[s];
      for (size_t c = 0; c < m.cells(); ++c)
        if (m.level(c, k) == l) out.trials[s][static_cast<size_t>(l)] += m.trials[s][c];
    }
  }
  return out;
}

stats::LongData long_data(const CellMatrix& m, const Design& design, const std::vector<size_t>& kept,
                          const std::string& dv) {
  stats::LongData d;
  d.dv_name = dv;
  for (int f : m.factors) d.within.push_back({design.factor(f).name, {}});
  std::vector<double> y;
  for (size_t s : kept)
    for (size_t c = 0; c < m.cells(); ++c) {
      d.subject.push_back(m.subjects[s]);
      for (size_t k = 0; k < m.factors.size(); ++k)
        d.within[k].level.push_back(design.factor(m.factors[k]).levels[static_cast<size_t>(m.level(c, k))]);
      y.push_back(m.value[s][c]);
    }
  d.dv = stats::Measurements::from_doubles(std::move(y));
  return d;
}

Reducer mean_of(std::function<std::optional<double>(const TrialRow&)> field) {
  return [field](const std::vector<const TrialRow*>& ts) {
    double sum = 0;
    int n = 0;
    for (const TrialRow* t : ts)
      if (auto v = field(*t)) {
        sum += *v;
        ++n;
      }
    return n ? sum / n : kNaN;
  };
}

Reducer mean_of_task_means(std::function<std::optional<double>(const TrialRow&)> field) {
  return [field](const std::vector<const TrialRow*>& ts) {
    std::map<std::string, std::pair<double, int>> per_task;
    for (const TrialRow* t : ts)
      if (auto v = field(*t)) {
        per_task[t->planned.task].first += *v;
        ++per_task[t->planned.task].second;
      }
    if (per_task.empty()) return kNaN;
    double sum = 0;
    for (const auto& [task, sn] : per_task) sum += sn.first / sn.second;
    return sum / static_cast<double>(per_task.size());
  };
}

Reducer aggregated_relative_error() {
  return [](const std::vector<const TrialRow*>& ts) {
    double truths = 0, answers = 0;
    int n = 0;
    for (const TrialRow* t : ts) {
      const auto truth = count_of(t->truth), answer = count_of(t->answer);
      if (answer && truth) {
        truths += static_cast<double>(*truth);
        answers += static_cast<double>(*answer);
        ++n;
      }
    }
    if (n == 0 || truths <= 0) return kNaN;
    return std::fabs(truths - answers) / truths;
  };
}

Reducer proportion_correct() {
  return [](const std::vector<const TrialRow*>& ts) {
    int right = 0, n = 0;
    for (const TrialRow* t : ts)
      if (t->scores.correct) {
        right += *t->scores.correct ? 1 : 0;
        ++n;
      }
    return n ? static_cast<double>(right) / n : kNaN;
  };
}

}  // namespace dtlab::report::detail
