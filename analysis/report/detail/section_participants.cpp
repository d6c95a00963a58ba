// The report's "Participants" section: who took part as a paper's method
// section describes them -- consent given and declined, who withdrew (left
// out of every analysis), the demographics the protocol asked for (integer
// fields: n, mean, SD, range; choice fields: a count per option; text fields:
// how many answered), and what happened around the sessions: the
// experimenter's pauses and notes per participant and about the study.
// Computed first into a plain result (participants_result), then laid out;
// report.json's "sample" and sessions_notes.csv are laid out from the result
// by render_data.h. Never reads the database (StudyData holds what it needs).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "analysis/report/detail/format.h"
#include "analysis/report/detail/sections.h"
#include "analysis/stats/descriptives.h"

namespace dtlab::report::detail {
namespace {

using NumericField = ParticipantsResult::NumericField;
using ChoiceField = ParticipantsResult::ChoiceField;
using TextField = ParticipantsResult::TextField;
using AroundSession = ParticipantsResult::AroundSession;

ParticipantsResult participants_result(const Context& ctx) {
  const StudyData& data = ctx.data;
  const std::set<std::string> analysed(ctx.subjects.begin(), ctx.subjects.end());
  ParticipantsResult r;
  std::vector<const ParticipantRow*> rows;
  for (const ParticipantRow& p : data.participants)
    if (analysed.count(p.id)) rows.push_back(&p);
  r.described = static_cast<int>(rows.size());
  r.consent_asked = data.protocol.flow.consent.has_value() || data.consented + data.declined > 0;
  r.consented = data.consented;
  r.declined = data.declined;
  r.withdrawn = data.withdrawn;
  for (const protocol::DemographicField& f : data.protocol.demographics) {
    using Type = protocol::DemographicField::Type;
    if (f.type == Type::integer) {
      std::vector<double> v;
      for (const ParticipantRow* p : rows)
        if (auto it = p->demographics.find(f.id); it != p->demographics.end() && !it->second.empty())
          v.push_back(std::strtod(it->second.c_str(), nullptr));
      r.numeric.push_back({f.id, f.prompt, stats::describe(v)});
    } else if (f.type == Type::choice) {
      ChoiceField c{f.id, f.prompt, {}, 0};
      std::map<std::string, int> n;
      for (const ParticipantRow* p : rows)
        if (auto it = p->demographics.find(f.id); it != p->demographics.end() && !it->second.empty()) {
          ++n[it->second];
          ++c.answered;
        }
      for (const std::string& o : f.options) c.counts.emplace_back(o, n.count(o) ? n[o] : 0);
      for (const auto& [answer, k] : n)
        if (std::find(f.options.begin(), f.options.end(), answer) == f.options.end()) c.counts.emplace_back(answer, k);
      r.choices.push_back(std::move(c));
    } else {
      TextField t{f.id, f.prompt, 0};
      for (const ParticipantRow* p : rows)
        if (auto it = p->demographics.find(f.id); it != p->demographics.end() && !it->second.empty()) ++t.answered;
      r.texts.push_back(std::move(t));
    }
  }
  for (const ParticipantRow& p : data.participants)
    if (p.pauses > 0 || !p.notes.empty()) r.around.push_back({p.id, p.pauses, p.paused_s, p.notes});
  r.study_notes = data.study_notes;
  return r;
}

Table demographics_table(const ParticipantsResult& r) {
  Table t;
  t.id = "table-demographics";
  t.caption = "Demographics of the " + std::to_string(r.described) + " analysed participants.";
  t.header = {"Field", "Question", "n", "Summary"};
  t.text_columns = 2;
  t.last_is_text = true;
  for (const NumericField& f : r.numeric)
    t.rows.push_back({f.id, f.prompt, std::to_string(f.d.n),
                      f.d.n == 0 ? kDash
                                 : "M = " + fixed(f.d.mean, 1) + ", SD = " + fixed(f.d.sd, 1) + ", range " +
                                       fixed(f.d.min, 0) + "–" + fixed(f.d.max, 0)});
  for (const ChoiceField& c : r.choices) {
    std::string counts;
    for (const auto& [option, n] : c.counts) counts += (counts.empty() ? "" : "; ") + option + " " + std::to_string(n);
    t.rows.push_back({c.id, c.prompt, std::to_string(c.answered), counts.empty() ? kDash : counts});
  }
  for (const TextField& f : r.texts)
    t.rows.push_back({f.id, f.prompt, std::to_string(f.answered), "free text (not summarised)"});
  t.notes.push_back("n: participants who answered the field; SD with n − 1.");
  return t;
}

// "Consent: 11 agreed, 1 declined. Withdrawn ...": what a method section says about consent.
std::string consent_text(const ParticipantsResult& r) {
  std::string t;
  if (r.consent_asked)
    t = "Consent: " + std::to_string(r.consented) + " agreed, " + std::to_string(r.declined) +
        " declined (of those who declined, only the refusal is stored).";
  if (!r.withdrawn.empty()) {
    std::string who;
    for (const std::string& w : r.withdrawn) who += (who.empty() ? "" : ", ") + w;
    t += std::string(t.empty() ? "" : " ") + std::to_string(r.withdrawn.size()) +
         (r.withdrawn.size() == 1 ? " participant" : " participants") +
         " withdrew consent (declined it, or withdrew later) and " + (r.withdrawn.size() == 1 ? "is" : "are") +
         " left out of every analysis: " + who + ".";
  }
  return t;
}

}  // namespace

ParticipantsResult section_participants(Context& ctx) { return participants_result(ctx); }

void lay_out_participants(Layout& out, const ParticipantsResult& r) {
  Section s{"participants", "Participants", 2, {}};
  if (const std::string consent = consent_text(r); !consent.empty()) s.text(consent);
  if (!r.numeric.empty() || !r.choices.empty() || !r.texts.empty()) s.add(demographics_table(r));
  else s.text("The protocol asks no demographics (`[demographics.*]`).");
  if (!r.around.empty()) {
    Table t;
    t.id = "table-around-sessions";
    t.caption = "Pauses and the experimenter's notes, per participant.";
    t.header = {"Participant", "Pauses", "Paused (s)", "Notes"};
    t.text_columns = 1;
    t.last_is_text = true;
    for (const AroundSession& a : r.around) {
      std::string notes;
      for (const std::string& n : a.notes) notes += (notes.empty() ? "" : "; ") + n;
      t.rows.push_back({a.id, std::to_string(a.pauses), fixed(a.paused_s, 1), notes.empty() ? kDash : notes});
    }
    t.notes.push_back("Paused time is not completion time: a trial's clock stops while the session is paused.");
    s.add(t);
  }
  if (!r.study_notes.empty()) {
    std::string all;
    for (const std::string& n : r.study_notes) all += (all.empty() ? "" : " ") + n + ".";
    s.text("Notes about the study: " + all);
  }
  out.doc.sections.push_back(std::move(s));
}

}  // namespace dtlab::report::detail
