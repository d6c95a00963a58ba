// design_sha256 (protocol.h): the canonical hash of everything in a protocol
// that changes what a session runs -- factors, conditions, ordering, seeds,
// time limits, training, the session's sequence (consent asked, pages,
// breaks, announcements), every scene parameter, every rendering parameter,
// the questionnaire's structure (item types, their keys but labels, `when`,
// instruments) -- and of nothing else (labels, instructions, consent and
// page texts are wording): comments, white space, key order, the title,
// descriptions and prompt texts leave it
// unchanged. The store uses it to tell a reworded protocol (sessions go on,
// analyses pool) from a changed design. A new Protocol field that changes
// what runs must be added here (tests/protocol/test_design_hash.cpp lists them).
#include <cstdio>
#include <string>
#include <type_traits>
#include <variant>

#include "study/common/hash.h"
#include "study/protocol/protocol.h"

namespace dtlab::protocol {
namespace {

// key=value lines; strings length-prefixed (no escaping ambiguity), doubles in hex (exact).
class Canon {
 public:
  void str(const std::string& key, const std::string& v) { line(key, std::to_string(v.size()) + ":" + v); }
  void num(const std::string& key, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%a", v);
    line(key, buf);
  }
  void integer(const std::string& key, long long v) { line(key, std::to_string(v)); }
  void list(const std::string& key, const std::vector<std::string>& v) {
    integer(key + ".size", static_cast<long long>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) str(key + "[" + std::to_string(i) + "]", v[i]);
  }
  void ints(const std::string& key, const std::vector<int>& v) {
    integer(key + ".size", static_cast<long long>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) integer(key + "[" + std::to_string(i) + "]", v[i]);
  }
  const std::string& text() const { return text_; }

 private:
  void line(const std::string& key, const std::string& v) { text_ += key + "=" + v + "\n"; }
  std::string text_;
};

// The registry's key groups write "rendering.<key>" lines through this.
class RenderingHash final : public technique::HashSink {
 public:
  explicit RenderingHash(Canon& c) : c_(c) {}
  void str(std::string_view name, std::string_view value) override { c_.str(key(name), std::string(value)); }
  void num(std::string_view name, double value) override { c_.num(key(name), value); }
  void integer(std::string_view name, std::int64_t value) override { c_.integer(key(name), value); }

 private:
  static std::string key(std::string_view name) { return "rendering." + std::string(name); }
  Canon& c_;
};

void scene(Canon& c, const std::string& k, const SceneParams& s) {
  c.str(k + ".kind", std::string(to_string(s.kind)));
  c.integer(k + ".objects", s.objects);
  c.num(k + ".extent", s.extent);
  c.integer(k + ".grid_width", s.grid_width);
  c.integer(k + ".grid_height", s.grid_height);
  c.num(k + ".cell_size", s.cell_size);
  c.list(k + ".object_kinds", s.object_kinds);
  c.num(k + ".object_radius.min", s.object_radius.min);
  c.num(k + ".object_radius.max", s.object_radius.max);
  c.num(k + ".target_ratio.min", s.target_ratio.min);
  c.num(k + ".target_ratio.max", s.target_ratio.max);
  c.list(k + ".letters", s.letters);
  c.integer(k + ".count_range.min", s.count_range.min);
  c.integer(k + ".count_range.max", s.count_range.max);
}

// The keys of a registration that change what runs (not its wording), in declaration order.
void keys(Canon& c, const std::string& prefix, const std::vector<questionnaire::KeySpec>& specs,
          const questionnaire::Keys& values) {
  for (const questionnaire::KeySpec& k : specs) {
    if (k.wording) continue;
    const auto it = values.find(k.name);
    if (it == values.end()) continue;
    const std::string key = prefix + "." + k.name;
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, bool>) c.integer(key, v ? 1 : 0);
          else if constexpr (std::is_same_v<T, std::int64_t>) c.integer(key, v);
          else if constexpr (std::is_same_v<T, double>) c.num(key, v);
          else if constexpr (std::is_same_v<T, std::string>) c.str(key, v);
          else if constexpr (std::is_same_v<T, std::vector<std::string>>) c.list(key, v);
          else if constexpr (std::is_same_v<T, questionnaire::NumberPair>) {
            c.num(key + ".min", v.min);
            c.num(key + ".max", v.max);
          }
        },
        it->second);
  }
}

// One item. The three types older than the item-type seam (rating, choice, depth-test) hash
// exactly as they did, every field of all three for each item, so that their studies keep their
// design hash; every other type hashes its own declared keys. `when` counts when it is not "end".
void questionnaire_item(Canon& c, const QuestionnaireItem& q) {
  const std::string type = q.type ? q.type->name : "";
  c.str("item", q.id);
  c.str("item.type", type);
  if (type == "rating" || type == "choice" || type == "depth-test") {
    const auto text = [&](const char* key) { return type == "choice" || type == "depth-test" ? q.text(key) : ""; };
    const questionnaire::NumberPair scale = type == "rating" ? q.range("scale") : questionnaire::NumberPair{0, 4};
    c.integer("item.scale_min", static_cast<long long>(scale.min));
    c.integer("item.scale_max", static_cast<long long>(scale.max));
    c.list("item.per", type == "rating" ? q.strings("per") : std::vector<std::string>{});
    c.str("item.factor", type == "choice" ? text("factor") : "");
    c.list("item.options", type == "choice" ? q.strings("options") : std::vector<std::string>{});
    c.str("item.scenario", type == "depth-test" ? text("scenario") : "");
    c.str("item.rendering", type == "depth-test" ? text("rendering") : "");
    c.integer("item.pairs", type == "depth-test" ? q.integer("pairs") : 3);
  } else if (q.type) {
    keys(c, "item", q.type->keys, q.keys);
  }
  if (q.when.kind != questionnaire::When::Kind::end) c.str("item.when", questionnaire::to_string(q.when));
}

}  // namespace

std::string design_sha256(const Protocol& p) {
  Canon c;
  c.str("id", p.id);
  c.integer("master_seed", static_cast<long long>(p.master_seed));
  c.num("session_time_limit_s", p.session_time_limit_s);
  c.integer("order_rows", declared_order_rows(p));
  c.integer("factors.size", static_cast<long long>(p.factors.size()));
  for (const Factor& f : p.factors) {
    c.str("factor", f.name);
    c.str("factor.role", std::string(to_string(f.role)));
    c.list("factor.levels", f.levels);
  }
  for (const Condition& k : p.conditions) {
    c.str("condition", k.name);
    c.ints("condition.levels", k.levels);
    c.integer("condition.scenario", k.scenario);
    c.integer("condition.rendering", k.rendering);
  }
  const Ordering& o = p.order;
  c.str("order.unit", std::string(to_string(o.unit)));
  c.str("order.scheme", std::string(to_string(o.scheme)));
  c.integer("order.rows", o.rows);
  c.ints("order.fixed", o.fixed);
  c.integer("order.block_factor", o.block_factor);
  c.str("order.nested_scheme", std::string(to_string(o.nested_scheme)));
  c.integer("order.nested_rows", o.nested_rows);
  c.ints("order.nested_fixed", o.nested_fixed);
  c.num("training.time_limit_s", p.training.time_limit_s);
  c.integer("training.practice_trials", p.training.practice_trials);
  // The session's sequence: each key only when it is not the default, so that every protocol
  // written before these keys keeps its hash. Its wording (consent and page texts, labels,
  // instructions) never enters.
  if (!p.training.practice_label) c.str("training.practice_label", "false");
  if (p.training.feedback) c.str("training.feedback", "true");
  if (p.flow.trial_counter) c.str("flow.trial_counter", "true");
  if (p.flow.announce_blocks) c.str("flow.announce_blocks", "true");
  if (p.flow.consent) c.str("flow.consent", "asked");
  for (const Page& page : p.flow.pages)
    c.str("flow.page", page.id + (page.when == Page::When::start ? "@start" : "@end"));
  const Breaks& b = p.flow.breaks;
  if (!b.after_blocks) c.str("flow.breaks.after_blocks", "false");
  if (b.every_trials != 0) c.integer("flow.breaks.every_trials", b.every_trials);
  if (b.min_s != 0) c.num("flow.breaks.min_s", b.min_s);
  if (b.max_s != 0) c.num("flow.breaks.max_s", b.max_s);
  if (!b.skippable) c.str("flow.breaks.skippable", "false");
  for (const Scenario& s : p.scenarios) {
    c.str("scenario", s.name);
    scene(c, "scenario.scene", s.scene);
    for (const Task& t : s.tasks) {
      c.str("task", t.id);
      c.str("task.type", std::string(to_string(t.type)));
      c.integer("task.trials", t.trials);
      scene(c, "task.scene", t.scene);
    }
  }
  for (const Rendering& r : p.renderings) {
    c.str("rendering", r.name);
    c.str("rendering.method", r.method);
    // Each key group writes its own part, in the registry's order (technique/settings.h).
    RenderingHash sink(c);
    const technique::Technique* method = technique::find(r.method);
    if (method == nullptr) continue;  // a Rendering built by hand with an unknown method: only its name
    for (const technique::KeyGroup* g : technique::key_groups()) g->hash(sink, *method, r.keys);
  }
  for (const QuestionnaireItem& q : p.questionnaire) questionnaire_item(c, q);
  for (const questionnaire::InstrumentUse& u : p.instruments) {
    c.str("instrument", u.id);
    c.str("instrument.name", u.instrument ? u.instrument->name : "");
    if (u.instrument) keys(c, "instrument", u.instrument->keys, u.keys);
  }
  return sha256_hex("dtlab design v1\n" + c.text());
}

std::optional<std::string> design_sha256_of_text(const std::string& text) {
  auto p = load_protocol_text(text, "(recorded protocol)");
  if (!p) return std::nullopt;
  return design_sha256(p.value());
}

}  // namespace dtlab::protocol
