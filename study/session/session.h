// The session runner: runs one participant's session of a protocol against a
// study database, with a Responder (a person behind a window, or a simulated
// participant) doing the trials. Study -> Participant -> Session -> Block ->
// Trial as in UXF (docs/session.md has the model, the lifecycle and the state
// diagram). Guarantees: every finished trial is committed in ONE
// Store::record_trial transaction before the next one starts; the next trial
// is always read from the file, so a crash at any point loses at most the
// trial in progress and rerunning resumes with exactly the trials it would
// have run; the answer key comes from the generated scene, scores from
// store::score(). Never: creates a GL context, writes SQL, or keeps results
// only in memory.
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "study/common/error.h"
#include "study/design/plan.h"
#include "study/protocol/protocol.h"
#include "study/render/render.h"
#include "study/scene/scene.h"
#include "study/session/mapping.h"
#include "study/store/store.h"

namespace dtlab::session {

// The pixel size a responder draws and looks at; frame settings are made for it.
struct Viewport {
  int width = 800;
  int height = 600;
};

// One trial as handed to the responder. Pointers stay valid until run_trial returns.
struct TrialSpec {
  const protocol::Protocol* protocol = nullptr;
  std::string participant_id;
  int enrollment_index = 0;       // the participant's 0-based index in the ledger
  design::PlannedTrial planned;   // position, block, levels, task, trial, seed, method, practice
  int planned_trials = 0;         // trials in the whole session
  int counted = 0, counted_of = 0;  // what a trial counter shows: this trial's number among the
                                    // session's non-practice trials, and how many there are (0 for practice)
  const TrialSetup* setup = nullptr;  // condition, scenario, task and rendering of the protocol
  const scene::Scene* scene = nullptr;  // the generated scene (answer key inside: never show it)
  render::FrameSettings frame;    // the condition's rendering for the responder's viewport()
  double time_limit_s = 0;        // session time left: session.time_limit_s - completion times recorded so far
  // Renews this process's claim on the session (Store::heartbeat). A responder whose trials can
  // outlast the claim's lifetime (a person) calls it every few seconds; an Error means another
  // process took the session over: stop the trial and return that Error.
  std::function<Status()> keep_claim;
};

// What the responder measured in one trial.
struct TrialOutcome {
  std::optional<store::Answer> answer;  // nullopt: no answer (time ran out, skipped); else the task's kind
  double completion_s = 0;              // completion time in seconds (>= 0)
  std::chrono::system_clock::time_point started_at, ended_at;  // wall clock
  std::vector<double> frame_ms;          // frame time of every rendered frame
  std::vector<store::CameraPose> poses;  // the camera of every rendered frame (same length as frame_ms)
  std::vector<store::InputEvent> events;  // in time order
  std::optional<double> refresh_hz;       // the display's refresh rate (late frames count against it); nullopt: unknown
};

// A task set: the consecutive trials of one task in one block; training precedes it.
struct PageSpec;
struct PageOutcome;

struct TaskSetSpec {
  const protocol::Protocol* protocol = nullptr;
  std::string participant_id;
  int enrollment_index = 0;
  int block = 0;                  // 1-based
  std::string task;               // task id
  const TrialSetup* setup = nullptr;
  double time_limit_s = 0;        // training.time_limit_s
  bool resumed = false;           // the set was begun before an interruption (its first trial is recorded)
  // Appends a page the responder showed for the set (its instructions, its training) to the
  // session's screen log; set by the runner. A responder that shows nothing does not call it.
  std::function<Status(const PageSpec&, const PageOutcome&)> log_screen;
};

// One question of a questionnaire, expanded from a protocol item (study/questionnaire).
using Question = questionnaire::Question;

// The static view of a depth-test item: one scene, one camera, transparency as the item says.
struct DepthTestView {
  std::string item;
  scene::Scene scene;
  scene::CameraStart camera;     // the fixed view (walk mode, chosen so that every pair is in it)
  render::FrameSettings frame;   // the item's rendering for the responder's viewport()
};

// A recorded trial as stored in the file (the responder's "memory" of the session).
struct RecordedTrial {
  design::PlannedTrial planned;
  double completion_s = 0;
  bool answered = false;
};

// One occasion's questionnaire (after a block, a task set, the last block of a level, or at the end).
struct QuestionnaireSpec {
  const protocol::Protocol* protocol = nullptr;
  std::string participant_id;
  int enrollment_index = 0;
  questionnaire::Occasion occasion;     // when it is asked; scope "" at the end
  std::vector<Question> questions;      // the items asked at this occasion, in protocol order, then scope order
  std::vector<DepthTestView> depth_tests;  // one per depth-test item asked here
  std::vector<RecordedTrial> history;   // every trial recorded so far, in position order
};

// A page of the session's sequence around the trials (docs/session.md, "The sequence"): the
// consent page, an information page, a block's announcement, a level's instructions, a break,
// the feedback after a practice trial. Built by the runner from the protocol (wording included);
// the responder shows it and says how it ended.
struct PageSpec {
  enum class Kind { consent, information, announcement, level_instructions, pause, feedback };
  Kind kind = Kind::information;
  const protocol::Protocol* protocol = nullptr;
  std::string screen;  // its name for scripts and the screen log: "consent", "page <id>",
                       // "announce <block>", "level <factor>=<level>", "break", "feedback <task>"
  std::string title, text;
  std::string shown;   // what the screen log records as shown (a page's id, the text's SHA-256, ...)
  double min_s = 0;       // pause: the participant can go on after min_s (unless skippable)
  double max_s = 0;       // pause: it ends by itself after max_s (0: never)
  bool skippable = true;  // pause: the participant can go on at once
};

// How a page ended. answer: consent "agree" | "decline"; otherwise "continue" (the participant
// went on) | "timed out" (a pause reached max_s).
struct PageOutcome {
  std::string answer;
  std::chrono::system_clock::time_point shown_at, ended_at;  // wall clock
};

// An answer: a number (rating, Likert, slider, numeric; depth test: the Object::id judged closer),
// a text (choice, free text) or several (multiple choice); questionnaire::encode checks and stores it.
using QuestionAnswer = questionnaire::Answer;

// Who does the trials. Calls come in session order from one thread; a responder may keep
// state between calls, but a resumed session must not need it (the file is the memory).
class Responder {
 public:
  virtual ~Responder() = default;
  virtual Viewport viewport() const = 0;                       // constant for the responder's life
  // The display the trials are shown on, recorded once per session start. Default: headless at
  // viewport(), the current GL context's renderer, refresh rate unknown.
  virtual store::DisplayInfo display() const;
  virtual Status train(const TaskSetSpec& set) = 0;            // before the first trial of a task set run here
  virtual Result<TrialOutcome> run_trial(const TrialSpec& trial) = 0;  // one trial, start to answer
  // One answer per question, in the order of spec.questions; once per occasion (spec.occasion),
  // right after the block, task set, level or session it follows.
  virtual Result<std::vector<QuestionAnswer>> answer_questionnaire(const QuestionnaireSpec& spec) = 0;
  // One page of the sequence. Default (headless, simulated): agrees to consent and goes on at
  // once, stamped now.
  virtual Result<PageOutcome> show_page(const PageSpec& page);
};

// Lifecycle hooks (all optional), called on the runner's thread. docs/session.md says what is
// safe in each; none may write to the store, and none should throw (an exception propagates
// out of run_session; everything committed stays committed).
struct Hooks {
  std::function<void(const store::Session&, const design::Plan&)> on_session_start;  // after begin_session
  std::function<void(const TaskSetSpec&)> on_task_set_start;   // before training
  std::function<void(const TrialSpec&)> on_trial_start;        // scene generated; not in the file yet
  std::function<void(const TrialSpec&, const store::TrialRecord&)> on_trial_recorded;  // committed
  std::function<void(const store::Session&)> on_session_finished;  // questionnaires stored, status finished
  std::function<bool()> stop_requested;  // polled before each trial: true = return now (resumable)
};

struct SessionSummary {
  store::Enrollment enrollment;
  design::Plan plan;
  int trials_run = 0;          // trials recorded by this call
  int trials_recorded = 0;     // trials in the file now
  bool resumed = false;        // the session was running before this call
  bool already_finished = false;  // nothing to do: the session had finished before
  bool questionnaire_recorded = false;  // some occasion's answers were recorded by this call
  int occasions_recorded = 0;  // questionnaire occasions recorded by this call
  bool finished = false;       // the session is finished now
  bool stopped = false;        // stop_requested ended the call early
  bool declined = false;       // the participant declined consent: only the refusal is stored
};

// Asks for consent where the protocol has a [consent] page and the participant has not answered
// it (a decline stores only the refusal and ends the call: declined), enrolls `participant_id`
// with `demographics` (or looks them up), builds the plan with the ledger's index and order row,
// begins or resumes the session, shows the start pages, runs every remaining trial with the
// sequence's pages between them (announcements, level instructions, breaks, practice feedback)
// and each questionnaire occasion right after the trial it follows (one transaction each; a
// resumed session asks only the occasions not in the file), then the end pages, and finishes the
// session. A finished session is left alone (already_finished). Every page is recorded in the
// session's screen log. Errors: the store's, the protocol mapping's, the responder's; the file
// then holds every trial committed before.
Result<SessionSummary> run_session(store::Store& store, const protocol::Protocol& protocol,
                                   const std::string& participant_id, Responder& responder, const Hooks& hooks = {},
                                   const store::Demographics& demographics = {});

// The questions asked at occasion `o` (default: the end), in protocol item order: each item
// whose `when` is the occasion's, expanded by its type (a rating with `per` once per combination
// of those factors' levels, first factor slowest; a depth test once per pair, objects filled in by
// depth_test_view).
std::vector<Question> expand_questionnaire(const protocol::Protocol& p, const questionnaire::Occasion& o = {});

// The occasions of participant plan `plan` at which the protocol asks something, in order.
std::vector<questionnaire::Occasion> questionnaire_occasions(const protocol::Protocol& p, const design::Plan& plan);

// The view and object pairs of depth-test `item` for participant `index`: a scene of the item's
// scenario (seed design::depth_test_seed, study/design/seeds.h), a camera from the start cell facing the most objects, and
// item.pairs pairs of objects in view whose distances from the eye differ by 20% to 100%.
// Fills questions' object ids; returns the view and, per pair, the id of the closer object.
struct DepthTestKey {
  DepthTestView view;
  std::vector<std::uint32_t> closer;  // per pair: Object::id of the closer object
};
Result<DepthTestKey> depth_test_view(const protocol::Protocol& p, const protocol::QuestionnaireItem& item,
                                     int enrollment_index, const Viewport& viewport, std::vector<Question>& questions);

// Where object `object` (an Object::id) of depth-test view `v` appears on a viewport of `vp` pixels:
// its mesh's bounding-box centre projected by the view's camera, in pixels from the top-left corner;
// nullopt when the object is not in the scene or lies behind the eye. The window draws the pair's
// A and B markers there.
std::optional<glm::vec2> depth_test_marker(const DepthTestView& v, std::uint32_t object, const Viewport& vp);

// The recorded trials of `participant_id`, read through the store, in position order.
Result<std::vector<RecordedTrial>> recorded_trials(store::Store& store, const std::string& participant_id);

}  // namespace dtlab::session
