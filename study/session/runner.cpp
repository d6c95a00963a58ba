// run_session (session.h): the session lifecycle of docs/session.md, one
// function, in the order of its state diagram. Every decision about what to
// run next is read from the store (next_trial), never from a counter kept
// here, so the loop is the same after any number of interruptions.
#include <algorithm>
#include <cmath>
#include <set>

#include "study/design/design.h"
#include "study/render/gl_info.h"
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

// The stored form of the responder's answers; ratings in range, choices among the options,
// depth-test answers scored against the key (1 = the closer object named, 0 = not).
Result<std::vector<store::QuestionnaireAnswer>> score_questionnaire(const std::vector<Question>& questions,
                                                                    const std::vector<QuestionAnswer>& answers,
                                                                    const std::vector<DepthTestKey>& keys) {
  if (answers.size() != questions.size())
    return responder_error("questionnaire", std::to_string(answers.size()) + " answers to " +
                                                std::to_string(questions.size()) + " questions");
  std::vector<store::QuestionnaireAnswer> out;
  for (std::size_t i = 0; i < questions.size(); ++i) {
    const Question& q = questions[i];
    const protocol::QuestionnaireItem& item = *q.item;
    const std::string field = "questionnaire." + item.id + (q.scope.empty() ? "" : "[" + q.scope + "]");
    const double* num = std::get_if<double>(&answers[i]);
    const std::string* text = std::get_if<std::string>(&answers[i]);
    store::QuestionnaireAnswer a{item.id, q.scope, 0.0};
    switch (item.type) {
      case protocol::ItemType::rating:
        if (!num || *num != std::floor(*num) || *num < item.scale_min || *num > item.scale_max)
          return responder_error(field, "expected an integer rating in [" + std::to_string(item.scale_min) + ", " +
                                            std::to_string(item.scale_max) + "]");
        a.value = *num;
        break;
      case protocol::ItemType::choice:
        if (!text || std::find(q.options.begin(), q.options.end(), *text) == q.options.end())
          return responder_error(field, "expected one of the item's options");
        a.value = *text;
        break;
      case protocol::ItemType::depth_test: {
        if (!num || (*num != q.object_a && *num != q.object_b))
          return responder_error(field, "expected the Object::id of one of the pair (" + std::to_string(q.object_a) +
                                            " or " + std::to_string(q.object_b) + ")");
        const DepthTestKey* key = nullptr;
        for (const auto& k : keys)
          if (k.view.item == item.id) key = &k;
        if (!key || q.pair < 1 || q.pair > static_cast<int>(key->closer.size()))
          return responder_error(field, "no depth-test key for this pair");
        a.value = static_cast<std::uint32_t>(*num) == key->closer[static_cast<std::size_t>(q.pair - 1)] ? 1.0 : 0.0;
        break;
      }
    }
    out.push_back(std::move(a));
  }
  return out;
}

// The questions and depth-test views of participant `index`, made before the session begins so
// that a questionnaire that cannot be shown stops the session before its first trial.
struct PreparedQuestionnaire {
  std::vector<Question> questions;
  std::vector<DepthTestKey> keys;  // one per depth-test item
};
Result<PreparedQuestionnaire> prepare_questionnaire(const protocol::Protocol& p, int index, const Viewport& vp) {
  PreparedQuestionnaire q;
  q.questions = expand_questionnaire(p);
  for (const protocol::QuestionnaireItem& item : p.questionnaire) {
    if (item.type != protocol::ItemType::depth_test) continue;
    auto key = depth_test_view(p, item, index, vp, q.questions);
    if (!key) return key.error();
    q.keys.push_back(std::move(key.value()));
  }
  return q;
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

  auto prepared = prepare_questionnaire(p, sum.enrollment.index, responder.viewport());
  if (!prepared) return prepared.error();

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

  // Trials: RUNNING -> (next_trial, responder, record_trial)* until none is left.
  std::optional<std::pair<int, std::string>> task_set;  // (block, task) of the last trial run here
  for (;;) {
    if (hooks.stop_requested && hooks.stop_requested()) {
      sum.stopped = true;
      sum.trials_recorded = static_cast<int>(history->size());
      return sum;
    }
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

  // Questionnaire: one transaction. If an interrupted run committed it already, nobody is asked
  // again and the session goes straight on to FINISHED.
  auto answered = store.read().questionnaire(participant_id);
  if (!answered) return answered.error();
  QuestionnaireSpec q;
  q.protocol = &p;
  q.participant_id = participant_id;
  q.enrollment_index = sum.enrollment.index;
  q.questions = std::move(prepared->questions);
  q.history = history.value();
  const std::vector<DepthTestKey>& keys = prepared->keys;
  for (const DepthTestKey& key : keys) q.depth_tests.push_back(key.view);
  if (!q.questions.empty() && answered->empty()) {
    auto answers = responder.answer_questionnaire(q);
    if (!answers) return answers.error();
    auto stored = score_questionnaire(q.questions, answers.value(), keys);
    if (!stored) return stored.error();
    if (Status st = store.record_questionnaire(session, stored.value()); !st) return st.error();
    sum.questionnaire_recorded = true;
  }

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
