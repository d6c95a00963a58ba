// Order rows and trial plans; see design.h. Violated preconditions (a row out
// of range, a protocol that did not come from load_protocol) throw
// std::invalid_argument with the protocol id and the offending value.
#include "study/design/design.h"

#include <stdexcept>
#include <string>

#include "study/design/seeds.h"
#include "study/protocol/limits.h"

namespace dtlab::design {

namespace {

using protocol::OrderUnit;
using protocol::Protocol;
using protocol::Scheme;

void require(bool ok, const Protocol& p, const std::string& what) {
  if (!ok) throw std::invalid_argument("protocol '" + p.id + "': " + what);
}

// Row `r` of `scheme` over n items.
Order scheme_row(Scheme scheme, int n, const std::vector<int>& fixed, std::uint64_t seed, int r) {
  switch (scheme) {
    case Scheme::latin_square: return cyclic_latin_square_row(n, r);
    case Scheme::williams: return williams_row(n, r);
    case Scheme::full_permutation: return permutation_row(n, r);
    case Scheme::random: return random_order(n, seed, r);
    case Scheme::fixed: break;
  }
  return fixed;
}

int product_of_levels(const Protocol& p, int skip) {
  int n = 1;
  for (int f = 0; f < static_cast<int>(p.factors.size()); ++f)
    if (f != skip) n *= static_cast<int>(p.factors[f].levels.size());
  return n;
}

void check_protocol(const Protocol& p) {
  require(!p.factors.empty() && static_cast<int>(p.conditions.size()) == product_of_levels(p, -1), p,
          "conditions do not match the factors; load protocols with load_protocol()");
  for (const auto& c : p.conditions)
    require(c.scenario >= 0 && c.scenario < static_cast<int>(p.scenarios.size()) && c.rendering >= 0 &&
                c.rendering < static_cast<int>(p.renderings.size()),
            p, "condition " + c.name + " has no scenario or rendering; load protocols with load_protocol()");
  require(order_rows(p) >= 1, p, "the ordering has no rows; load protocols with load_protocol()");
}

}  // namespace

int order_rows(const Protocol& p) {
  const std::int64_t rows = protocol::declared_order_rows(p);
  require(rows <= protocol::limits::kOrderRows.max, p,
          "the ordering has " + std::to_string(rows) + " rows, more than a loaded protocol can have (" +
              std::to_string(protocol::limits::kOrderRows.max) + "); load protocols with load_protocol()");
  return static_cast<int>(rows);
}

Order order_row(const Protocol& p, int row) {
  const int rows = order_rows(p);
  require(row >= 0 && row < rows, p,
          "order row " + std::to_string(row) + " out of range [0, " + std::to_string(rows) + ")");
  const auto& o = p.order;
  if (o.unit == OrderUnit::conditions)
    return scheme_row(o.scheme, static_cast<int>(p.conditions.size()), o.fixed, order_seed(p.master_seed, 0), row);

  // Blocks: row = outer row + outer_rows * nested row.
  const int bf = o.block_factor;
  const int k = static_cast<int>(p.factors[bf].levels.size());
  const int nested = product_of_levels(p, bf);
  const int outer_rows = static_cast<int>(protocol::scheme_rows(o.scheme, k, o.rows));
  const Order outer = scheme_row(o.scheme, k, o.fixed, order_seed(p.master_seed, 0), row % outer_rows);
  const Order inner =
      scheme_row(o.nested_scheme, nested, o.nested_fixed, order_seed(p.master_seed, 1), row / outer_rows);
  Order out;
  out.reserve(p.conditions.size());
  for (int level : outer) {
    for (int cell : inner) {
      std::vector<int> levels(p.factors.size());
      for (int f = static_cast<int>(p.factors.size()) - 1; f >= 0; --f) {  // cell: other factors, first slowest
        if (f == bf) continue;
        const int kf = static_cast<int>(p.factors[f].levels.size());
        levels[f] = cell % kf;
        cell /= kf;
      }
      levels[bf] = level;
      out.push_back(protocol::condition_index(p, levels));
    }
  }
  return out;
}

OrderTable order_table(const Protocol& p) {
  OrderTable t;
  const int rows = order_rows(p);
  t.reserve(rows);
  for (int r = 0; r < rows; ++r) t.push_back(order_row(p, r));
  return t;
}

Plan make_plan(const Protocol& p, int index, std::optional<int> row) {
  check_protocol(p);
  require(index >= 0, p, "enrollment index must be >= 0, got " + std::to_string(index));
  Plan plan;
  plan.protocol_id = p.id;
  plan.index = index;
  plan.order_row = row.value_or(index % order_rows(p));
  const Order conditions = order_row(p, plan.order_row);
  int position = 0;
  int block = 0;
  for (int c : conditions) {
    ++block;
    const auto& cond = p.conditions[c];
    const auto& scenario = p.scenarios[cond.scenario];
    const auto& rendering = p.renderings[cond.rendering];
    const auto add = [&](const protocol::Task& task, int trial, bool practice) {
      PlannedTrial t;
      t.position = ++position;
      t.block = block;
      for (std::size_t f = 0; f < p.factors.size(); ++f)
        t.levels.emplace_back(p.factors[f].name, p.factors[f].levels[cond.levels[f]]);
      t.task = task.id;
      t.trial = trial;
      t.seed = trial_seed(p.master_seed, static_cast<std::uint64_t>(index), static_cast<std::uint64_t>(t.position));
      t.method = rendering.method;
      t.practice = practice;
      plan.trials.push_back(std::move(t));
    };
    for (const auto& task : scenario.tasks) {
      for (int i = 1; i <= p.training.practice_trials; ++i) add(task, i, true);
      for (int i = 1; i <= task.trials; ++i) add(task, i, false);
    }
  }
  return plan;
}

}  // namespace dtlab::design
