// A person in front of dtlab: the session::Responder of `dtlab run`. Each
// call runs its screens in the participant window until the person is done:
// show_page() a page of the sequence (consent with agree / decline, a break
// with its minimum and maximum length, ...); train() the task's instructions
// and the free exploration of a practice scene; run_trial() the trial view, the
// "find this" panel and the answer input; answer_questionnaire() the
// post-test pages and the static depth test. The experimenter console
// (Ctrl+Shift+E) is drawn over every screen; everything it does is stored
// through the store, never only shown. Guarantees: a trial's time runs from
// the first frame presented to the answer's submission on steady_clock,
// without the paused time; every presented frame has a pose and a frame
// time; every input event is logged (docs/run.md). Never: shows the answer
// key to the participant (only the console shows it).
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "app/run/ui.h"
#include "study/protocol/protocol.h"
#include "study/session/session.h"
#include "study/store/store.h"

namespace dtlab::run {

class Console;

class WindowResponder final : public session::Responder {
 public:
  WindowResponder(Ui& ui, store::Store& store, const protocol::Protocol& protocol, std::string participant,
                  std::string experimenter);
  ~WindowResponder() override;

  session::Viewport viewport() const override;
  store::DisplayInfo display() const override;
  Status train(const session::TaskSetSpec& set) override;
  Result<session::TrialOutcome> run_trial(const session::TrialSpec& trial) override;
  Result<std::vector<session::QuestionAnswer>> answer_questionnaire(const session::QuestionnaireSpec& spec) override;
  Result<session::PageOutcome> show_page(const session::PageSpec& page) override;

  // Hooks of the runner (app/cmd_run.cpp installs them).
  void on_session_start(const store::Session& session, const design::Plan& plan);
  void on_trial_recorded(const session::TrialSpec& spec, const store::TrialRecord& record);

  bool aborted() const;  // the experimenter abandoned the session from the console

 private:
  // Runs frames of `screen` until `done` returns true; draw3d may be empty.
  Status loop(const std::string& screen, const std::function<Status()>& draw3d, const std::function<bool()>& widgets);
  Status show_instructions(const session::TaskSetSpec& set);
  Status show_training(const session::TaskSetSpec& set);

  Ui& ui_;
  store::Store& store_;
  const protocol::Protocol& protocol_;
  std::string participant_;
  std::unique_ptr<Console> console_;
};

// Default instructions of a task type (when the protocol's task gives none), in the protocol's wording.
std::string default_instructions(const protocol::Protocol& p, protocol::TaskType type);

}  // namespace dtlab::run
