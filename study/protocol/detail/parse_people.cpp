// The [demographics.<field>] tables: what the experimenter records about a
// participant at enrollment (docs/protocol.md, "Demographics"). Each field
// has a type (text, integer, choice), a prompt, whether it is required, and
// its range or options. check_demographics() holds a participant's answers
// to the same rules. Never part of the design hash: what is asked about a
// person does not change what the session runs.
#include <algorithm>
#include <charconv>

#include "study/protocol/detail/parser.h"

namespace dtlab::protocol {
namespace detail {

void parse_demographics(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("demographics", false);
  if (!t) return;
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string id(k->str());
    const std::string path = join("demographics", id);
    if (!is_identifier(id))
      s.d.error(pos_of(*k), path, "field id \"" + id + "\" is not an identifier (letters, digits, '_', '-')");
    if (id == "simulated" || id == "agent")
      s.d.error(pos_of(*k), path, "\"" + id + "\" is reserved for simulated participants (dtlab simulate)");
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with type and prompt, got " + type_name(*n));
      continue;
    }
    TableReader fr(*n->as_table(), path, s.d, pos_of(*k));
    DemographicField f;
    f.id = id;
    const auto type = fr.choice("type", true, {"text", "integer", "choice"});
    if (auto v = fr.string("prompt", true)) f.prompt = *v;
    if (const toml::node* r = fr.node("required")) {
      if (auto b = r->value<bool>()) f.required = *b;
      else s.d.error(fr.pos("required"), fr.field("required"), "expected true or false, got " + type_name(*r));
    }
    const auto range = fr.int_range("range", false, limits::kDemographicRange, /*strictly_increasing=*/true);
    const auto options = fr.strings("options", false, limits::kDemographicOptions);
    fr.finish();
    if (!type) continue;
    f.type = *type == "text" ? DemographicField::Type::text
             : *type == "integer" ? DemographicField::Type::integer
                                  : DemographicField::Type::choice;
    if (f.type != DemographicField::Type::integer && fr.has("range"))
      s.d.error(fr.pos("range"), fr.field("range"), "applies only to type = \"integer\"");
    if (f.type != DemographicField::Type::choice && fr.has("options"))
      s.d.error(fr.pos("options"), fr.field("options"), "applies only to type = \"choice\"");
    if (f.type == DemographicField::Type::choice && !fr.has("options"))
      s.d.error(fr.pos(), fr.field("options"), "a choice needs options = [\"...\", ...] (at least two)");
    if (range) {
      f.min = range->min;
      f.max = range->max;
    }
    if (options) f.options = *options;
    s.p.demographics.push_back(std::move(f));
  }
}

}  // namespace detail

Status check_demographics(const Protocol& p, const std::vector<std::pair<std::string, std::string>>& values) {
  auto bad = [](const std::string& field, std::string message) {
    return Error{"", 0, 0, "demographics." + field, std::move(message)};
  };
  for (const auto& [key, value] : values)
    if (std::none_of(p.demographics.begin(), p.demographics.end(),
                     [&](const DemographicField& f) { return f.id == key; }))
      return bad(key, "the protocol declares no such field");
  for (const DemographicField& f : p.demographics) {
    const auto it = std::find_if(values.begin(), values.end(), [&](const auto& v) { return v.first == f.id; });
    const std::string value = it == values.end() ? std::string() : it->second;
    if (value.empty()) {
      if (f.required) return bad(f.id, "is required (" + f.prompt + ")");
      continue;
    }
    switch (f.type) {
      case DemographicField::Type::text:
        if (value.size() > 200) return bad(f.id, "at most 200 characters");
        break;
      case DemographicField::Type::integer: {
        long long v = 0;
        const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
        if (ec != std::errc() || ptr != value.data() + value.size())
          return bad(f.id, "\"" + value + "\" is not a whole number");
        if (v < f.min || v > f.max)
          return bad(f.id, std::to_string(v) + " is outside " + std::to_string(f.min) + ".." + std::to_string(f.max));
        break;
      }
      case DemographicField::Type::choice:
        if (std::find(f.options.begin(), f.options.end(), value) == f.options.end())
          return bad(f.id, "\"" + value + "\" is not one of the options");
        break;
    }
  }
  return {};
}

std::string_view to_string(DemographicField::Type type) {
  switch (type) {
    case DemographicField::Type::integer: return "integer";
    case DemographicField::Type::choice: return "choice";
    case DemographicField::Type::text: break;
  }
  return "text";
}

}  // namespace dtlab::protocol
