// The report's "Participants" section as a computation: who took part as a
// paper's method section describes them -- consent given and declined, who
// withdrew (left out of every analysis), the demographics the protocol asked
// for (integer fields: n, mean, SD, range; choice fields: a count per option;
// text fields: how many answered), and what happened around the sessions:
// the experimenter's pauses and notes per participant and about the study.
// layout_overview.cpp lays the result out; report.json's "sample" and
// sessions_notes.csv come from it through render_data.h. Never reads the
// database (StudyData holds what it needs).
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

}  // namespace

ParticipantsResult section_participants(Context& ctx) { return participants_result(ctx); }

}  // namespace dtlab::report::detail
