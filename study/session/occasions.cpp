// The runner's questionnaire occasions (detail/occasions.h): prepared before
// the session begins, asked as its trials reach them, each stored in one
// transaction. Answers are checked and encoded by their item types
// (questionnaire::encode); the depth test is scored against its key here.
#include "study/session/detail/occasions.h"

#include <algorithm>
#include <set>
#include <tuple>

namespace dtlab::session::detail {

namespace {

Error responder_error(const std::string& field, const std::string& message) { return Error{"", 0, 0, field, message}; }

bool is_depth_test(const questionnaire::Item& item) { return item.type && item.type->name == "depth-test"; }

}  // namespace

Result<Occasions> Occasions::prepare(const protocol::Protocol& p, int index, const design::Plan& plan, const Viewport& vp) {
  Occasions o;
  o.protocol_ = &p;
  o.occasions_ = questionnaire_occasions(p, plan);
  const questionnaire::DesignNames names = protocol::design_names(p);
  for (const protocol::QuestionnaireItem& item : p.questionnaire) {
    if (!is_depth_test(item)) continue;
    std::vector<Question> questions = questionnaire::expand(item, names);
    auto key = depth_test_view(p, item, index, vp, questions);
    if (!key) return key.error();
    DepthTest dt{std::move(key.value()), {}};
    for (const Question& q : questions) dt.objects.emplace_back(q.object_a, q.object_b);
    o.depth_tests_.emplace(item.id, std::move(dt));
  }
  return o;
}

Result<int> Occasions::ask_due(store::Store& store, const store::Session& session, const std::string& participant,
                               int enrollment_index, int recorded, const std::vector<RecordedTrial>& history,
                               Responder& responder) {
  const protocol::Protocol& p = *protocol_;
  std::set<std::pair<std::string, std::string>> stored;
  bool read = false;
  int asked = 0;
  for (; next_ < occasions_.size(); ++next_) {
    const questionnaire::Occasion& oc = occasions_[next_];
    if (oc.after_position > recorded) break;
    QuestionnaireSpec spec{&p, participant, enrollment_index, oc, expand_questionnaire(p, oc), {}, {}};
    if (spec.questions.empty()) continue;
    if (!read) {  // what the file holds, read once per call (a resumed session's answers included)
      auto answered = store.read().questionnaire(participant);
      if (!answered) return answered.error();
      for (const store::QuestionnaireRecord& r : answered.value()) stored.emplace(r.item, r.scope);
      read = true;
    }
    bool done = false;
    for (Question& q : spec.questions) {
      done = done || stored.count({q.item->id, questionnaire::stored_scope(oc, q)}) > 0;
      if (!is_depth_test(*q.item)) continue;
      const DepthTest& dt = depth_tests_.at(q.item->id);
      if (q.pair < 1 || q.pair > static_cast<int>(dt.objects.size())) continue;
      std::tie(q.object_a, q.object_b) = dt.objects[static_cast<std::size_t>(q.pair - 1)];
      const bool listed = std::any_of(spec.depth_tests.begin(), spec.depth_tests.end(),
                                      [&](const DepthTestView& v) { return v.item == q.item->id; });
      if (!listed) spec.depth_tests.push_back(dt.key.view);
    }
    if (done) continue;  // one transaction per occasion: any answer stored means all of them are
    spec.history = history;

    auto answers = responder.answer_questionnaire(spec);
    if (!answers) return answers.error();
    if (answers->size() != spec.questions.size())
      return responder_error("questionnaire", std::to_string(answers->size()) + " answers to " +
                                                  std::to_string(spec.questions.size()) + " questions");
    questionnaire::EncodeContext ctx;
    ctx.closer = [&](const Question& q) -> std::optional<std::uint32_t> {
      const auto it = depth_tests_.find(q.item->id);
      if (it == depth_tests_.end() || q.pair < 1 || q.pair > static_cast<int>(it->second.key.closer.size())) return std::nullopt;
      return it->second.key.closer[static_cast<std::size_t>(q.pair - 1)];
    };
    std::vector<store::QuestionnaireAnswer> rows;
    for (std::size_t i = 0; i < spec.questions.size(); ++i) {
      const Question& q = spec.questions[i];
      auto value = questionnaire::encode(q, (*answers)[i], ctx);
      if (!value) return value.error();
      rows.push_back({q.item->id, questionnaire::stored_scope(oc, q), std::move(value.value())});
    }
    if (Status st = store.record_questionnaire(session, rows); !st) return st.error();
    for (const auto& r : rows) stored.emplace(r.item, r.scope);
    ++asked;
  }
  return asked;
}

}  // namespace dtlab::session::detail
