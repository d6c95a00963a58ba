// Reading one design revision of a study for the report; see study_data.h.
// Everything comes from the store's StudyReader; this file only selects (the
// revision, the exclusions) and maps the store's rows to the report's.
#include "analysis/report/detail/study_data.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <set>
#include <tuple>

namespace dtlab::report::detail {
namespace {

TrialRow to_report_row(const store::TrialRow& t, const protocol::Protocol& p) {
  TrialRow r;
  static_cast<store::TrialRow&>(r) = t;
  for (const protocol::Factor& f : p.factors) {
    r.levels.push_back(t.level(f.name));
    const auto it = std::find(f.levels.begin(), f.levels.end(), r.levels.back());
    r.level_index.push_back(it == f.levels.end() ? -1 : static_cast<int>(it - f.levels.begin()));
  }
  return r;
}

}  // namespace

std::optional<std::int64_t> count_of(const std::optional<store::Answer>& a) {
  if (!a) return std::nullopt;
  if (const auto* c = std::get_if<store::Count>(&*a)) return c->n;
  return std::nullopt;
}

Result<std::vector<store::Revision>> design_revisions(store::StudyReader& reader) {
  auto revs = reader.revisions();
  if (!revs) return revs.error();
  std::vector<store::Revision> out;  // index k-1: the latest row of design revision k
  for (const store::Revision& r : *revs) {
    const int k = r.design_revision > 0 ? r.design_revision : static_cast<int>(out.size()) + 1;
    if (static_cast<int>(out.size()) < k) out.resize(static_cast<std::size_t>(k));
    out[static_cast<std::size_t>(k - 1)] = r;
  }
  if (out.empty())
    return Error{reader.path(), 0, 0, "studies", "the database records no protocol (no study was ever started)"};
  return out;
}

namespace {

// The sessions of the database, by participant and by id (pointers into `all`).
struct Sessions {
  std::vector<store::SessionRecord> all;
  std::map<std::string, const store::SessionRecord*> of;
  std::map<std::int64_t, const store::SessionRecord*> by_id;
};

// The participants enrolled under the protocol texts `studies` (withdrawn ones to d.withdrawn), with their
// sessions; `members` gets every analysable participant's ID.
Status read_participants(store::StudyReader& reader, const std::set<std::int64_t>& studies, const Sessions& sessions,
                         StudyData& d, std::set<std::string>& members) {
  auto ledger = reader.ledger();
  if (!ledger) return ledger.error();
  for (const store::LedgerEntry& e : *ledger) {
    const auto it = sessions.of.find(e.participant);
    const std::int64_t study = it != sessions.of.end() ? it->second->study_id : e.study_id;
    if (!studies.count(study)) continue;
    if (e.withdrawn) {  // their data are never analysed: consent was declined or taken back
      d.withdrawn.push_back(e.participant);
      continue;
    }
    members.insert(e.participant);
    ParticipantRow p;
    p.id = e.participant;
    p.index = e.index;
    p.order_row = e.order_row;
    p.released = e.released_at.has_value();
    for (const auto& [k, v] : e.demographics) p.demographics[k] = v;
    if (it != sessions.of.end()) {
      p.session_status = it->second->status;
      p.planned = it->second->planned;
      p.recorded = it->second->recorded;
      p.resumes = static_cast<int>(it->second->resumes.size());
      p.software_version = it->second->software_version;
      p.pauses = static_cast<int>(it->second->pauses.size());
      p.paused_s = it->second->paused_s();
    }
    d.participants.push_back(std::move(p));
  }
  return {};
}

// Consent answers (withdrawn participants included), the study's and the participants' notes, the exclusions.
Status read_consents_notes_exclusions(store::StudyReader& reader, const std::set<std::string>& members,
                                      StudyData& d) {
  auto consents = reader.consents();
  if (!consents) return consents.error();
  for (const store::ConsentRecord& c : *consents)
    if (members.count(c.participant) ||
        std::find(d.withdrawn.begin(), d.withdrawn.end(), c.participant) != d.withdrawn.end())
      (c.agreed ? d.consented : d.declined) += 1;

  auto notes = reader.notes();
  if (!notes) return notes.error();
  for (const store::Note& n : *notes) {
    if (n.participant.empty()) {
      d.study_notes.push_back(n.text + " (" + n.author + ")");
      continue;
    }
    for (ParticipantRow& p : d.participants)
      if (p.id == n.participant)
        p.notes.push_back((n.position ? "trial " + std::to_string(*n.position) + ": " : std::string()) + n.text + " (" +
                          n.author + ")");
  }

  auto exclusions = reader.exclusions();
  if (!exclusions) return exclusions.error();
  std::map<std::string, bool> participant_out;  // the latest decision about each participant as a whole
  for (const store::Exclusion& x : *exclusions) {
    if (!members.count(x.participant)) continue;
    d.exclusions.push_back(x);
    if (!x.position) participant_out[x.participant] = x.exclude;
  }
  for (const auto& [who, out] : participant_out)
    if (out) d.excluded_participants.push_back(who);
  return {};
}

// The members' trials as the report's rows, each with the display its session recorded.
void add_trials(const std::vector<store::TrialRow>& trials, const std::set<std::string>& members,
                const Sessions& sessions, bool with_excluded, StudyData& d) {
  for (const store::TrialRow& t : trials) {
    if (!members.count(t.participant)) {
      ++d.other_revision_trials;
      continue;
    }
    if (t.excluded) {
      ++d.excluded_trials;
      if (!with_excluded) continue;
    }
    TrialRow row = to_report_row(t, d.protocol);
    // The display the session recorded last at or before the trial started (its first when none).
    const store::Display* shown = nullptr;
    if (const auto it = sessions.by_id.find(t.session_id); it != sessions.by_id.end())
      for (const auto& disp : it->second->displays)
        if (!shown || disp.recorded_at <= t.started_at) shown = &disp;
    if (shown) {
      row.display_kind = shown->info.kind;
      row.display_width = shown->info.width;
      row.display_height = shown->info.height;
      row.renderer = shown->info.renderer;
    }
    d.trials.push_back(std::move(row));
  }
}

// The members' questionnaire answers (excluded participants' only with with_excluded), per participant
// (enrollment order), by item and scope.
Status read_answers(store::StudyReader& reader, const std::set<std::string>& members, bool with_excluded,
                    StudyData& d) {
  auto answers = reader.questionnaire();
  if (!answers) return answers.error();
  const std::set<std::string> out(d.excluded_participants.begin(), d.excluded_participants.end());
  for (const store::QuestionnaireRecord& a : *answers) {
    if (!members.count(a.participant) || (!with_excluded && out.count(a.participant))) continue;
    AnswerRow r{a.participant, a.item, a.scope, std::nullopt, std::nullopt};
    if (const double* v = std::get_if<double>(&a.value)) r.number = *v;
    else r.text = std::get<std::string>(a.value);
    d.answers.push_back(std::move(r));
  }
  std::map<std::string, int> order;
  for (const auto& p : d.participants) order[p.id] = p.index;
  std::stable_sort(d.answers.begin(), d.answers.end(), [&](const AnswerRow& a, const AnswerRow& b) {
    return std::tie(order[a.participant], a.item, a.scope) < std::tie(order[b.participant], b.item, b.scope);
  });
  return {};
}

}  // namespace

Result<StudyData> read_study(store::StudyReader& reader, const std::vector<store::TrialRow>& trials, int revision,
                             bool with_excluded) {
  auto designs = design_revisions(reader);
  if (!designs) return designs.error();
  if (revision < 1 || revision > static_cast<int>(designs->size()))
    return Error{reader.path(), 0, 0, "revision",
                 "the database has design revision" + std::string(designs->size() == 1 ? " 1" : "s 1.." +
                     std::to_string(designs->size())) + "; there is no revision " + std::to_string(revision),
                 ErrorKind::not_found};
  const store::Revision& latest = (*designs)[static_cast<std::size_t>(revision - 1)];
  auto revs = reader.revisions();
  if (!revs) return revs.error();
  std::set<std::int64_t> studies;  // the protocol texts (study rows) of this design revision
  auto in_revision = [&](const store::Revision& r) {
    return r.design_revision == revision || (r.design_revision == 0 && r.study_id == latest.study_id);
  };
  for (const store::Revision& r : *revs)
    if (in_revision(r)) studies.insert(r.study_id);

  StudyData d;
  d.path = reader.path();
  d.design_revision = revision;
  d.design_revisions = static_cast<int>(designs->size());
  d.protocol_texts = static_cast<int>(studies.size());
  d.software_version = latest.software_version;
  d.with_excluded = with_excluded;
  auto proto = protocol::load_protocol_text(latest.protocol_text, reader.path() + " (recorded protocol)");
  if (!proto) {
    Error e = proto.error();
    e.message = "the protocol recorded in the database does not load: " + e.message;
    return e;
  }
  d.protocol = std::move(*proto);

  auto read_sessions = reader.sessions();
  if (!read_sessions) return read_sessions.error();
  Sessions sessions{std::move(*read_sessions), {}, {}};
  for (const auto& s : sessions.all) {
    sessions.of[s.participant] = &s;
    sessions.by_id[s.id] = &s;
  }
  std::set<std::string> members;
  if (auto st = read_participants(reader, studies, sessions, d, members); !st) return st.error();
  if (auto st = read_consents_notes_exclusions(reader, members, d); !st) return st.error();
  add_trials(trials, members, sessions, with_excluded, d);
  if (auto st = read_answers(reader, members, with_excluded, d); !st) return st.error();
  return d;
}

Result<StudyData> read_study(store::StudyReader& reader, int revision, bool with_excluded) {
  auto trials = reader.trials();
  if (!trials) return trials.error();
  return read_study(reader, *trials, revision, with_excluded);
}

Result<std::vector<int>> chosen_revisions(const std::string& spec, int count, const std::string& path) {
  if (spec == "all" || spec.empty()) {
    std::vector<int> all;
    for (int k = 1; k <= count; ++k) all.push_back(k);
    return all;
  }
  if (spec == "latest") return std::vector<int>{count};
  int k = 0;
  const auto [ptr, ec] = std::from_chars(spec.data(), spec.data() + spec.size(), k);
  if (ec != std::errc() || ptr != spec.data() + spec.size() || k < 1)
    return Error{path, 0, 0, "revision", "\"" + spec + "\": expected all, latest or a revision number 1.." +
                                             std::to_string(count)};
  if (k > count)
    return Error{path, 0, 0, "revision",
                 "there is no design revision " + spec + "; the database has " + std::to_string(count) +
                     (count == 1 ? " (revision 1)" : " (revisions 1.." + std::to_string(count) + ")"),
                 ErrorKind::not_found};
  return std::vector<int>{k};
}

}  // namespace dtlab::report::detail
