// WindowResponder::answer_questionnaire (responder.h): one page per question
// of the occasion, in the protocol's order, each drawn by its item type's
// screen (item_screen.h, app/run/items/). Answers are returned to the
// runner, which checks them through their item types, scores the depth test
// and stores the occasion in one transaction.
#include "app/run/console.h"
#include "app/run/item_screen.h"
#include "app/run/responder.h"
#include "study/protocol/wording.h"

namespace dtlab::run {

Result<std::vector<session::QuestionAnswer>> WindowResponder::answer_questionnaire(
    const session::QuestionnaireSpec& spec) {
  console_->set_trial(nullptr);
  std::vector<session::QuestionAnswer> answers;
  for (std::size_t i = 0; i < spec.questions.size(); ++i) {
    ItemPage page{&ui_, &spec.questions[i], &spec,
                  protocol::text(*spec.protocol, "question.progress",
                                 {{"n", std::to_string(i + 1)}, {"total", std::to_string(spec.questions.size())}})};
    auto screen = make_item_screen(page);
    if (!screen) return screen.error();
    ItemScreen& s = *screen.value();
    ui_.new_instance();  // every question restarts its script section, even with the same screen name
    std::function<Status()> draw3d;
    if (s.has_view()) draw3d = [&s] { return s.draw3d(); };
    if (Status st = loop(s.name(), draw3d, [&s] { return s.frame(); }); !st) return st.error();
    answers.push_back(s.answer());
  }
  return answers;
}

}  // namespace dtlab::run
