// Internal: the [questionnaire.<id>] tables: each item's type, prompt and the
// keys of its type, checked against the declared factors, scenarios and
// renderings (a key of another type is an error, a name must exist). Runs
// after the factors, scenarios and renderings are parsed. Never aborts: every
// problem is a Diagnostic at the key's line.
#include "study/protocol/detail/parser.h"

namespace dtlab::protocol::detail {

void parse_questionnaire(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const toml::table* t = root.table("questionnaire", false);
  if (!t) return;
  std::vector<std::string> scenario_names, rendering_names;
  for (const auto& sc : p.scenarios) scenario_names.push_back(sc.name);
  for (const auto& r : p.renderings) rendering_names.push_back(r.name);
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string id(k->str());
    const std::string path = join("questionnaire", id);
    if (!is_identifier(id))
      s.d.error(pos_of(*k), path, "item id \"" + id + "\" is not an identifier (letters, digits, '_', '-')");
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with type and prompt, got " + type_name(*n));
      continue;
    }
    TableReader qr(*n->as_table(), path, s.d, pos_of(*k));
    QuestionnaireItem item;
    item.id = id;
    const auto type = qr.choice("type", true, {"rating", "choice", "depth-test"});
    if (auto v = qr.string("prompt", true)) item.prompt = *v;
    const auto scale = qr.int_range("scale", false, limits::kScale, true);
    const auto per = qr.strings("per", false, limits::kPer);
    const auto factor = qr.string("factor", false);
    const auto options = qr.strings("options", false, limits::kOptions);
    const auto neutral = qr.string("neutral", false);
    const auto scenario = qr.string("scenario", false);
    const auto rendering = qr.string("rendering", false);
    const auto pairs = qr.integer("pairs", false, limits::kPairs);
    qr.finish();
    if (!type) continue;
    item.type = *type == "rating" ? ItemType::rating : *type == "choice" ? ItemType::choice : ItemType::depth_test;
    const auto only = [&](const char* key, ItemType applies) {
      if (item.type != applies && qr.has(key))
        s.d.error(qr.pos(key), qr.field(key),
                  "applies only to type = \"" + std::string(to_string(applies)) + "\"; this item is \"" + *type +
                      "\"");
    };
    for (const char* key : {"scale", "per"}) only(key, ItemType::rating);
    for (const char* key : {"factor", "options", "neutral"}) only(key, ItemType::choice);
    for (const char* key : {"scenario", "rendering", "pairs"}) only(key, ItemType::depth_test);
    const auto known = [&](const char* key, const std::string& name, const std::vector<std::string>& names,
                           const char* what) {
      if (find_index(names, name) >= 0) return true;
      s.d.error(qr.pos(key), qr.field(key),
                std::string("no ") + what + " named '" + name + "' (declared: " + quoted_list(names) + ")");
      return false;
    };
    switch (item.type) {
      case ItemType::rating:
        if (scale) {
          item.scale_min = scale->min;
          item.scale_max = scale->max;
        }
        if (per) {
          const toml::array& a = *qr.node("per")->as_array();
          for (std::size_t i = 0; i < per->size(); ++i)
            if (find_index(factor_names(p), (*per)[i]) < 0)
              s.d.error(pos_of(*a.get(i)), indexed(qr.field("per"), i),
                        "no factor named '" + (*per)[i] + "' (factors: " + quoted_list(factor_names(p)) + ")");
          item.per = *per;
        }
        break;
      case ItemType::choice:
        if (!qr.has("options") && !qr.has("factor"))
          s.d.error(qr.pos(), path, "a choice needs factor = \"<factor>\" (its levels are the options) or "
                                    "options = [...]");
        else if (qr.has("factor") && qr.has("options"))
          s.d.error(qr.pos("options"), qr.field("options"), "give either factor or options, not both");
        if (factor && known("factor", *factor, factor_names(p), "factor")) item.factor = *factor;
        if (options) item.options = *options;
        if (!item.factor.empty()) item.options = p.factors[find_index(factor_names(p), item.factor)].levels;
        if (neutral) {
          if (find_index(item.options, *neutral) >= 0)
            s.d.error(qr.pos("neutral"), qr.field("neutral"),
                      "\"" + *neutral + "\" is already one of the options; the neutral option must differ");
          else {
            item.neutral = *neutral;
            item.options.push_back(*neutral);
          }
        }
        break;
      case ItemType::depth_test:
        if (!qr.has("scenario"))
          s.d.error(qr.pos(), qr.field("scenario"), "missing required key 'scenario' (the scenario shown)");
        if (!qr.has("rendering"))
          s.d.error(qr.pos(), qr.field("rendering"), "missing required key 'rendering' (the rendering used)");
        if (scenario && known("scenario", *scenario, scenario_names, "scenario")) item.scenario = *scenario;
        if (rendering && known("rendering", *rendering, rendering_names, "rendering")) item.rendering = *rendering;
        if (pairs) item.pairs = static_cast<int>(*pairs);
        break;
    }
    p.questionnaire.push_back(std::move(item));
  }
}

}  // namespace dtlab::protocol::detail
