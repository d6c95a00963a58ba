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

}  // namespace

store::DisplayInfo Responder::display() const {
  const Viewport vp = viewport();
  return store::DisplayInfo{"headless", vp.width, vp.height, std::nullopt, render::current_gl_description(), ""};
}

Result<SessionSummary> run_session(store::Store& store, const protocol::Protocol& p, const std::string& participant_id,
                                   Responder& responder, const Hooks& hooks) {
  SessionSummary sum;
  auto enrolled = store.enroll(participant_id);
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
  if (hooks.on_session_start) hooks.on_session_start(session, sum.plan);

  auto history = recorded_trials(store, participant_id);
  if (!history) return history.error();
  double elapsed = 0;
  for (const RecordedTrial& t : history.value()) elapsed += t.completion_s;
  const Viewport vp = responder.viewport();
  // Every questionnaire occasion whose last trial is recorded and whose answers are not: asked and
  // stored (one transaction each) before the next trial; after an interruption, the ones missed.
  const auto ask_occasions = [&]() -> Status {
    const int recorded = history->empty() ? 0 : history->back().planned.position;
    auto n = occasions->ask_due(store, session, participant_id, sum.enrollment.index, recorded, history.value(), responder);
    if (!n) return n.error();
    sum.occasions_recorded += n.value();
    sum.questionnaire_recorded = sum.occasions_recorded > 0;
    return {};
  };

  // Trials: RUNNING -> (next_trial, responder, record_trial)* until none is left.
  std::optional<std::pair<int, std::string>> task_set;  // (block, task) of the last trial run here
  for (;;) {
    if (hooks.stop_requested && hooks.stop_requested()) {
      sum.stopped = true;
      sum.trials_recorded = static_cast<int>(history->size());
      return sum;
    }
    if (Status st = ask_occasions(); !st) return st.error();
    auto next = store.next_trial(session);
    if (!next) return next.error();
    if (!next->has_value()) break;
    const design::PlannedTrial planned = **next;

    auto setup = trial_setup(p, planned);
    if (!setup) return setup.error();
    if (!task_set || task_set->first != planned.block || task_set->second != planned.task) {
      TaskSetSpec set{&p, participant_id, sum.enrollment.index, planned.block, planned.task, &setup.value(),
                      p.training.time_limit_s, false};
      // A set is resumed when a trial of it is already in the file.
      for (const RecordedTrial& t : history.value())
        if (t.planned.block == planned.block && t.planned.task == planned.task) set.resumed = true;
      if (hooks.on_task_set_start) hooks.on_task_set_start(set);
      if (Status st = responder.train(set); !st) return st.error();
      task_set = std::make_pair(planned.block, planned.task);
    }

    auto sc = trial_scene(setup.value(), planned);
    if (!sc) return sc.error();
    auto frame = frame_settings(p, *setup->rendering, vp.width, vp.height);
    if (!frame) return frame.error();
    TrialSpec spec;
    spec.protocol = &p;
    spec.participant_id = participant_id;
    spec.enrollment_index = sum.enrollment.index;
    spec.planned = planned;
    spec.planned_trials = static_cast<int>(sum.plan.trials.size());
    spec.setup = &setup.value();
    spec.scene = &sc.value();
    spec.frame = std::move(frame.value());
    spec.time_limit_s = std::max(0.0, p.session_time_limit_s - elapsed);
    spec.keep_claim = [&store, &session] { return store.heartbeat(session); };
    if (Status st = store.begin_trial(session, planned.position); !st) return st.error();
    if (hooks.on_trial_start) hooks.on_trial_start(spec);

    auto outcome = responder.run_trial(spec);
    if (!outcome) return outcome.error();
    auto record = make_record(spec, std::move(outcome.value()));
    if (!record) return record.error();
    if (Status st = store.record_trial(session, record.value()); !st) return st.error();
    ++sum.trials_run;
    elapsed += record->completion_s;
    history->push_back(RecordedTrial{planned, record->completion_s, record->answer.has_value()});
    if (hooks.on_trial_recorded) hooks.on_trial_recorded(spec, record.value());
  }
  sum.trials_recorded = static_cast<int>(history->size());

  // The last occasions (the end's among them); those an interrupted run committed are not asked again.
  if (Status st = ask_occasions(); !st) return st.error();

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
