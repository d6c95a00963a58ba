// run_session (session.h): the session lifecycle of docs/session.md, one
// function, in the order of its state diagram. Every decision about what to
// run or ask next is read from the store (next_trial; the questionnaire
// occasions answered), so the loop is the same after any number of
// interruptions; what is kept here (the elapsed time, the last task set,
// the history) is rebuilt from the file when a session resumes.
#include <algorithm>
#include <cmath>
#include <set>

#include "study/design/design.h"
#include "study/render/gl_info.h"
#include "study/session/detail/sequence.h"
#include "study/session/detail/occasions.h"
#include "study/session/session.h"

namespace dtlab::session {

namespace {

Error responder_error(const std::string& field, const std::string& message) {
  return Error{"", 0, 0, field, message};
}

// The responder's outcome as a store record; checks the responder kept its contract.
Result<store::TrialRecord> make_record(const TrialSpec& spec, TrialOutcome&& out) {
  const std::string field = "trial " + std::to_string(spec.planned.position);
  store::TrialRecord r;
  r.position = spec.planned.position;
  r.scene_hash = spec.scene->hash;
  r.truth = answer_key(spec.scene->answer);
  if (out.answer && out.answer->index() != r.truth.index())
    return responder_error(field + ".answer", "the responder answered a " +
                                                  std::string(out.answer->index() == 0   ? "count"
                                                              : out.answer->index() == 1 ? "letter"
                                                                                         : "position") +
                                                  " to task " + spec.planned.task);
  if (out.frame_ms.size() != out.poses.size())
    return responder_error(field + ".poses", std::to_string(out.frame_ms.size()) + " frame times but " +
                                                 std::to_string(out.poses.size()) + " camera poses");
  for (double ms : out.frame_ms)
    if (!std::isfinite(ms) || ms < 0) return responder_error(field + ".frame_ms", "a frame time is negative or not finite");
  r.answer = std::move(out.answer);
  r.completion_s = out.completion_s;
  r.started_at = out.started_at;
  r.ended_at = out.ended_at;
  r.frames = store::frame_stats(out.frame_ms, out.refresh_hz);
  r.events = std::move(out.events);
  r.poses = std::move(out.poses);
  return r;
}

// Shows one page of the sequence and appends it to the session's screen log.
Status show_page(store::Store& store, const store::Session& session, Responder& responder, const PageSpec& page) {
  auto shown = responder.show_page(page);
  if (!shown) return shown.error();
  return store.record_screen(session, store::ScreenRecord{page.screen, page.shown, shown->shown_at, shown->ended_at,
                                                          shown->answer});
}

Status show_pages(store::Store& store, const store::Session& session, Responder& responder,
                  const std::vector<PageSpec>& pages) {
  for (const PageSpec& page : pages)
    if (Status st = show_page(store, session, responder, page); !st) return st;
  return {};
}

// CONSENT (docs/session.md): asked once, before anything of the participant is stored. The answer
// and the text's hash are stored with the enrollment in one transaction; a decline stores only that.
// Returns the page as shown when it was asked now (for the screen log once the session exists),
// with answer "agree" or "decline"; nullopt when an earlier call asked it and it was agreed.
struct Consent {
  bool agreed = false;
  std::optional<std::pair<PageSpec, PageOutcome>> asked_now;
};
Result<Consent> ask_consent(store::Store& store, const protocol::Protocol& p, const std::string& participant_id,
                            Responder& responder, const store::Demographics& demographics) {
  auto consents = store.read().consents();
  if (!consents) return consents.error();
  for (const store::ConsentRecord& c : *consents)
    if (c.participant == participant_id) return Consent{c.agreed, std::nullopt};
  const PageSpec page = detail::consent_page(p);
  auto answered = responder.show_page(page);
  if (!answered) return answered.error();
  const bool agreed = answered->answer == "agree";
  auto e = store.record_consent(participant_id, agreed ? demographics : store::Demographics{}, agreed, page.shown);
  if (!e) return e.error();
  return Consent{agreed, std::make_pair(page, answered.value())};
}

}  // namespace

Result<PageOutcome> Responder::show_page(const PageSpec& page) {
  const auto now = std::chrono::system_clock::now();
  return PageOutcome{page.kind == PageSpec::Kind::consent ? "agree" : "continue", now, now};
}

store::DisplayInfo Responder::display() const {
  const Viewport vp = viewport();
  return store::DisplayInfo{"headless", vp.width, vp.height, std::nullopt, render::current_gl_description(), ""};
}

namespace {

// What run_session's steps share: the store, the protocol, the participant's session.
struct Run {
  store::Store& store;
  const protocol::Protocol& p;
  const std::string& participant_id;
  Responder& responder;
  const Hooks& hooks;
  SessionSummary& sum;
  const store::Session& session;
  std::vector<RecordedTrial>& history;  // every recorded trial, in position order
};

// The pages before `planned`: a block's break, announcement and level instructions when the
// session reaches a new block, else a break inside the block (breaks.every_trials).
Status pages_before(Run& r, const design::PlannedTrial& planned) {
  const RecordedTrial* last = r.history.empty() ? nullptr : &r.history.back();
  if (!last || last->planned.block != planned.block)
    return show_pages(r.store, r.session, r.responder, detail::block_pages(r.p, r.sum.plan, planned.block));
  if (auto b = detail::trial_break(r.p, r.sum.plan, last->planned, planned))
    return show_page(r.store, r.session, r.responder, *b);
  return {};
}

// One trial: the task set's training when it starts, the trial, its record, practice feedback.
Status run_one_trial(Run& r, const design::PlannedTrial& planned, std::optional<std::pair<int, std::string>>& task_set,
                     double& elapsed) {
  const protocol::Protocol& p = r.p;
  auto setup = trial_setup(p, planned);
  if (!setup) return setup.error();
  if (!task_set || task_set->first != planned.block || task_set->second != planned.task) {
    TaskSetSpec set{&p, r.participant_id, r.sum.enrollment.index, planned.block, planned.task, &setup.value(),
                    p.training.time_limit_s, false, {}};
    // A set is resumed when a trial of it is already in the file.
    for (const RecordedTrial& t : r.history)
      if (t.planned.block == planned.block && t.planned.task == planned.task) set.resumed = true;
    set.log_screen = [&r](const PageSpec& page, const PageOutcome& shown) {
      return r.store.record_screen(r.session, store::ScreenRecord{page.screen, page.shown, shown.shown_at,
                                                                  shown.ended_at, shown.answer});
    };
    if (r.hooks.on_task_set_start) r.hooks.on_task_set_start(set);
    if (Status st = r.responder.train(set); !st) return st;
    task_set = std::make_pair(planned.block, planned.task);
  }

  auto sc = trial_scene(setup.value(), planned);
  if (!sc) return sc.error();
  const Viewport vp = r.responder.viewport();
  auto frame = frame_settings(p, *setup->rendering, vp.width, vp.height);
  if (!frame) return frame.error();
  TrialSpec spec;
  spec.protocol = &p;
  spec.participant_id = r.participant_id;
  spec.enrollment_index = r.sum.enrollment.index;
  spec.planned = planned;
  spec.planned_trials = static_cast<int>(r.sum.plan.trials.size());
  for (const design::PlannedTrial& t : r.sum.plan.trials) {
    if (t.practice) continue;
    ++spec.counted_of;
    if (!planned.practice && t.position <= planned.position) ++spec.counted;
  }
  spec.setup = &setup.value();
  spec.scene = &sc.value();
  spec.frame = std::move(frame.value());
  spec.time_limit_s = std::max(0.0, p.session_time_limit_s - elapsed);
  spec.keep_claim = [&store = r.store, &session = r.session] { return store.heartbeat(session); };
  if (Status st = r.store.begin_trial(r.session, planned.position); !st) return st;
  if (r.hooks.on_trial_start) r.hooks.on_trial_start(spec);

  auto outcome = r.responder.run_trial(spec);
  if (!outcome) return outcome.error();
  auto record = make_record(spec, std::move(outcome.value()));
  if (!record) return record.error();
  if (Status st = r.store.record_trial(r.session, record.value()); !st) return st;
  ++r.sum.trials_run;
  elapsed += record->completion_s;
  r.history.push_back(RecordedTrial{planned, record->completion_s, record->answer.has_value()});
  if (r.hooks.on_trial_recorded) r.hooks.on_trial_recorded(spec, record.value());
  if (planned.practice && p.training.feedback)
    return show_page(r.store, r.session, r.responder, detail::feedback_page(p, planned, record->truth, record->answer));
  return {};
}

// Every questionnaire occasion whose last trial is recorded and whose answers are not: asked and
// stored (one transaction each) before the next trial's pages; after an interruption, the ones missed.
Status ask_occasions(Run& r, detail::Occasions& occasions) {
  const int recorded = r.history.empty() ? 0 : r.history.back().planned.position;
  auto n = occasions.ask_due(r.store, r.session, r.participant_id, r.sum.enrollment.index, recorded, r.history,
                             r.responder);
  if (!n) return n.error();
  r.sum.occasions_recorded += n.value();
  r.sum.questionnaire_recorded = r.sum.occasions_recorded > 0;
  return {};
}

// The session from BEGUN to FINISHED: the start pages, the trials with the pages between them
// (RUNNING -> (next_trial, responder, record_trial)* until none is left), the questionnaire, the
// end pages. Every decision is read from the store, so this is the same after any interruption.
Status run_begun(Run& r, detail::Occasions& occasions) {
  double elapsed = 0;
  for (const RecordedTrial& t : r.history) elapsed += t.completion_s;
  if (r.history.empty())
    if (Status st = show_pages(r.store, r.session, r.responder,
                               detail::information_pages(r.p, protocol::Page::When::start));
        !st)
      return st;
  std::optional<std::pair<int, std::string>> task_set;  // (block, task) of the last trial run here
  for (;;) {
    if (r.hooks.stop_requested && r.hooks.stop_requested()) {
      r.sum.stopped = true;
      return {};
    }
    if (Status st = ask_occasions(r, occasions); !st) return st;
    auto next = r.store.next_trial(r.session);
    if (!next) return next.error();
    if (!next->has_value()) break;
    if (Status st = pages_before(r, **next); !st) return st;
    if (Status st = run_one_trial(r, **next, task_set, elapsed); !st) return st;
  }
  // The last occasions (the end's among them); those an interrupted run committed are not asked again.
  if (Status st = ask_occasions(r, occasions); !st) return st;
  return show_pages(r.store, r.session, r.responder, detail::information_pages(r.p, protocol::Page::When::end));
}

}  // namespace

Result<SessionSummary> run_session(store::Store& store, const protocol::Protocol& p, const std::string& participant_id,
                                   Responder& responder, const Hooks& hooks, const store::Demographics& demographics) {
  SessionSummary sum;
  Consent consent{true, std::nullopt};
  if (p.flow.consent) {
    auto asked = ask_consent(store, p, participant_id, responder, demographics);
    if (!asked) return asked.error();
    consent = std::move(asked.value());
    if (!consent.agreed) {
      sum.declined = true;
      return sum;
    }
  }
  auto enrolled = store.enroll(participant_id, demographics);
  if (!enrolled) return enrolled.error();
  sum.enrollment = enrolled.value();
  sum.plan = design::make_plan(p, sum.enrollment.index, sum.enrollment.order_row);

  // A finished session is left alone; an abandoned one is the store's to refuse.
  const auto found_finished = [&](const Result<store::Session>& s) {
    if (!s || s->status != store::SessionStatus::finished) return false;
    sum.already_finished = sum.finished = true;
    sum.trials_recorded = s->recorded;
    return true;
  };
  if (!sum.enrollment.newly_enrolled) {
    auto existing = store.session(participant_id);
    if (found_finished(existing)) return sum;
    if (!existing && existing.error().kind != ErrorKind::not_found) return existing.error();
  }

  // The questionnaire's occasions and depth-test views, made before the session begins so that a
  // questionnaire that cannot be shown stops the session before its first trial.
  auto occasions = detail::Occasions::prepare(p, sum.enrollment.index, sum.plan, responder.viewport());
  if (!occasions) return occasions.error();

  auto begun = store.begin_session(participant_id, sum.plan);
  // Another process may have finished the session since the check above (the store refuses to
  // resume a finished session): that is the same as finding it finished.
  if (!begun && begun.error().kind == ErrorKind::conflict && found_finished(store.session(participant_id))) return sum;
  if (!begun) return begun.error();
  const store::Session session = begun.value();
  sum.resumed = session.resumed;
  if (Status st = store.record_display(session, responder.display()); !st) return st.error();
  if (consent.asked_now) {  // the consent page, shown before the session existed, opens its screen log
    const auto& [page, shown] = *consent.asked_now;
    if (Status st = store.record_screen(session, store::ScreenRecord{page.screen, page.shown, shown.shown_at,
                                                                     shown.ended_at, shown.answer});
        !st)
      return st.error();
  }
  if (hooks.on_session_start) hooks.on_session_start(session, sum.plan);

  auto history = recorded_trials(store, participant_id);
  if (!history) return history.error();
  Run run{store, p, participant_id, responder, hooks, sum, session, *history};
  if (Status st = run_begun(run, *occasions); !st) return st.error();
  sum.trials_recorded = static_cast<int>(history->size());
  if (sum.stopped) return sum;

  if (Status st = store.finish_session(session); !st) return st.error();
  sum.finished = true;
  if (hooks.on_session_finished) {
    auto now = store.session(participant_id);
    if (!now) return now.error();
    hooks.on_session_finished(now.value());
  }
  return sum;
}

}  // namespace dtlab::session
