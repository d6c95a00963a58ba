// The session's sequence around the trials: [session], [training], [consent],
// [pages.<id>] and [breaks] (docs/protocol.md, "The session's sequence").
// Guarantees: a protocol that declares none of these tables runs the
// reference order (no consent, no pages, a break between blocks); texts are
// kept as written (they are wording, never part of the design hash).
// Never: reads a file; consent and page texts live in the protocol itself, so
// the study database records exactly what participants read.
#include "study/protocol/detail/parser.h"
#include "study/protocol/wording.h"

namespace dtlab::protocol::detail {
namespace {

void parse_session(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const toml::table* t = root.table("session", false);
  if (!t) return;
  TableReader sr(*t, "session", s.d, root.pos("session"));
  if (auto v = sr.number("time_limit_s", false, limits::kSessionTimeLimit)) p.session_time_limit_s = *v;
  if (auto v = sr.boolean("trial_counter", false)) p.flow.trial_counter = *v;
  if (auto v = sr.boolean("announce_blocks", false)) p.flow.announce_blocks = *v;
  if (auto v = sr.string("language", false)) p.flow.language = *v;
  sr.finish();
}

void parse_training(TableReader& root, ParseState& s) {
  Protocol& p = s.p;
  const toml::table* t = root.table("training", false);
  if (!t) return;
  TableReader tr(*t, "training", s.d, root.pos("training"));
  if (auto v = tr.number("time_limit_s", false, limits::kTrainingTimeLimit)) p.training.time_limit_s = *v;
  if (auto v = tr.integer("practice_trials", false, limits::kPracticeTrials))
    p.training.practice_trials = static_cast<int>(*v);
  if (auto v = tr.boolean("practice_label", false)) p.training.practice_label = *v;
  if (auto v = tr.boolean("feedback", false)) p.training.feedback = *v;
  tr.finish();
  if (p.training.feedback && p.training.practice_trials == 0)
    s.d.warning(tr.pos("feedback"), tr.field("feedback"),
                "feedback follows practice trials, and practice_trials is 0: nobody will see it");
}

void parse_consent(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("consent", false);
  if (!t) return;
  TableReader cr(*t, "consent", s.d, root.pos("consent"));
  Consent c;
  if (auto v = cr.string("title", false)) c.title = *v;
  if (auto v = cr.string("text", true)) c.text = *v;
  cr.finish();
  if (!c.text.empty()) s.p.flow.consent = std::move(c);
}

void parse_pages(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("pages", false);
  if (!t) return;
  for (const auto& [k, n] : in_file_order(*t)) {
    const std::string id(k->str());
    const std::string path = join("pages", id);
    if (!is_identifier(id))
      s.d.error(pos_of(*k), path, "page id \"" + id + "\" is not an identifier (letters, digits, '_', '-')");
    if (!n->is_table()) {
      s.d.error(pos_of(*n), path, "expected a table [" + path + "] with when, title and text, got " + type_name(*n));
      continue;
    }
    TableReader pr(*n->as_table(), path, s.d, pos_of(*k));
    Page page;
    page.id = id;
    if (auto when = pr.choice("when", false, {"start", "end"}))
      page.when = *when == "start" ? Page::When::start : Page::When::end;
    if (auto v = pr.string("title", false)) page.title = *v;
    if (auto v = pr.string("text", true)) page.text = *v;
    pr.finish();
    s.p.flow.pages.push_back(std::move(page));
  }
}

void parse_breaks(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("breaks", false);
  if (!t) return;
  Breaks& b = s.p.flow.breaks;
  TableReader br(*t, "breaks", s.d, root.pos("breaks"));
  if (auto v = br.boolean("after_blocks", false)) b.after_blocks = *v;
  if (auto v = br.integer("every_trials", false, limits::kBreakEvery)) b.every_trials = static_cast<int>(*v);
  if (auto v = br.number("min_s", false, limits::kBreakSeconds)) b.min_s = *v;
  if (auto v = br.number("max_s", false, limits::kBreakSeconds)) b.max_s = *v;
  if (auto v = br.boolean("skippable", false)) b.skippable = *v;
  br.finish();
  if (b.max_s > 0 && b.max_s < b.min_s)
    s.d.error(br.pos("max_s"), br.field("max_s"),
              "a break that ends by itself after " + std::to_string(b.max_s) + " s cannot last at least min_s = " +
                  std::to_string(b.min_s) + " s; give max_s >= min_s, or 0 for no limit");
  if (!b.skippable && b.min_s == 0 && b.max_s == 0)
    s.d.warning(br.pos("skippable"), br.field("skippable"),
                "skippable = false with min_s = 0 changes nothing: the participant may go on at once");
}

// [text]: only the keys of the wording table, each a string whose {placeholders} are the key's own.
void parse_text(TableReader& root, ParseState& s) {
  const toml::table* t = root.table("text", false);
  if (!t) return;
  TableReader xr(*t, "text", s.d, root.pos("text"));
  for (const TextKey& k : text_keys()) {
    auto v = xr.string(k.key, false, /*non_empty=*/false);
    if (!v) continue;
    const std::string allowed = " " + std::string(k.placeholders) + " ";
    for (std::size_t open = v->find('{'); open != std::string::npos; open = v->find('{', open + 1)) {
      const std::size_t close = v->find('}', open);
      const std::string name = close == std::string::npos ? "" : v->substr(open + 1, close - open - 1);
      if (!name.empty() && allowed.find(" " + name + " ") != std::string::npos) continue;
      s.d.error(xr.pos(k.key), xr.field(k.key),
                "\"{" + name + (close == std::string::npos ? "" : "}") + "\" is no placeholder of this text" +
                    (k.placeholders.empty() ? " (it takes none)"
                                            : " (it takes: " + std::string(k.placeholders) + ")"));
      break;
    }
    s.p.text.emplace_back(std::string(k.key), *v);
  }
  xr.finish();
}

}  // namespace

void parse_flow(TableReader& root, ParseState& s) {
  parse_session(root, s);
  parse_training(root, s);
  parse_consent(root, s);
  parse_pages(root, s);
  parse_breaks(root, s);
  parse_text(root, s);
}

}  // namespace dtlab::protocol::detail
