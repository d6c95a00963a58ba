// The one place that turns a protocol into the parameters of the stages it
// drives: scene::Params / Kind / Task from a task's SceneParams, the
// render::FrameSettings of a [rendering.*] table, the answer key in the
// store's terms, the StudyInfo a database is opened with. docs/session.md,
// "From protocol to stages", lists every field and where it arrives.
// Guarantees: pure functions but ledger_plan, which reads the enrollment
// ledger through the StudyReader it is given (and never writes); a value a stage cannot take (an
// unknown model family, a method name the renderer does not know, a subset of
// primitives the generator cannot place) is an Error naming the protocol
// field, never a silent default. Never: touches GL or files, or opens a
// database.
#pragma once
#include <string>

#include "study/common/error.h"
#include "study/design/plan.h"
#include "study/protocol/protocol.h"
#include "study/render/render.h"
#include "study/scene/generate.h"
#include "study/store/read.h"
#include "study/store/store.h"

namespace dtlab::session {

// The generator kind of a scenario kind (abstract -> abstract, walkthrough -> walkthrough).
scene::Kind scene_kind(protocol::ScenarioKind kind);

// The generator task of a task type (count-targets T1, identify-letter T2, find-unique T3, count-kind T4).
scene::Task scene_task(protocol::TaskType type);

// Generator parameters from a task's SceneParams; `field` is the protocol path of the
// task (e.g. "scenarios.abstract.tasks.T1") used in errors. Runs scene::validate too.
Result<scene::Params> scene_params(const protocol::Protocol& p, const protocol::Scenario& scenario,
                                   const protocol::Task& task);

// Frame settings of a [rendering.*] table for a width x height viewport (both >= 1): each key
// group its method reads (technique::Technique::groups) converts its keys (study/technique: the
// protocol's gradient width in mask pixels becomes output pixels, an active searchlight or lens
// starts at the viewport centre, ...). Error naming the key the frame cannot take.
Result<render::FrameSettings> frame_settings(const protocol::Protocol& p, const protocol::Rendering& rendering,
                                             int width, int height);

// Everything a planned trial needs, looked up in the protocol.
struct TrialSetup {
  int condition = 0;  // index into Protocol::conditions
  const protocol::Scenario* scenario = nullptr;
  const protocol::Task* task = nullptr;
  const protocol::Rendering* rendering = nullptr;
  scene::Kind kind = scene::Kind::abstract;
  scene::Task scene_task = scene::Task::T1;
  scene::Params params;
};

// Finds the trial's condition (from its levels), scenario, task and rendering. Error if
// the plan names a level or task the protocol does not have (a plan of another protocol).
Result<TrialSetup> trial_setup(const protocol::Protocol& p, const design::PlannedTrial& trial);

// The trial's scene: scene::generate(kind, task, trial seed, params).
Result<scene::Scene> trial_scene(const TrialSetup& setup, const design::PlannedTrial& trial);

// The answer key of a scene in the store's terms: T1/T4 Count, T2 Letter, T3 Position.
store::Answer answer_key(const scene::Answer& answer);

// What Store::open needs to know about the protocol (id, text, hash, design hash, version, rows, factors).
store::StudyInfo study_info(const protocol::Protocol& p);

// The plan of `participant` as enrolled in the study database behind `reader`: the ledger's
// enrollment index and order row applied to protocol `p`. not_found: unknown participant;
// conflict: the participant was enrolled under another design than p's (another protocol,
// or a revision that changed what runs); a reworded protocol with the same design is fine.
Result<design::Plan> ledger_plan(store::StudyReader& reader, const protocol::Protocol& p, const std::string& participant);

// How every command opens or reads a study database: recorded protocol texts are hashed by
// protocol::design_sha256_of_text (for revisions recorded before design hashes were stored).
store::OpenOptions open_options(bool allow_protocol_change = false);
store::ReadOptions read_options();

}  // namespace dtlab::session
