// A study protocol as plain data, read from a TOML file (format: docs/protocol.md).
// Guarantees: a Protocol returned by load_protocol() has passed every check of
// validate_protocol_*(): factors cross, every level has its scenario and
// rendering, the ordering scheme can order what it is asked to order.
// Loading never aborts and never throws on bad input: every problem becomes a
// Diagnostic with file, line, column and field path. Nothing here knows about
// OpenGL, SQLite or the scene generator.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "study/common/error.h"
#include "study/questionnaire/instrument.h"
#include "study/questionnaire/questionnaire.h"
#include "study/technique/technique.h"

namespace dtlab::protocol {

template <class T>
struct Range {  // closed interval [min, max], min <= max
  T min{};
  T max{};
};

// --- factors and conditions ---------------------------------------------------

enum class FactorRole {
  none,       // levels are recorded but change nothing the platform controls
  scenario,   // each level names a [scenarios.<level>] table
  rendering,  // each level names a [rendering.<level>] table
};

struct Factor {
  std::string name;
  FactorRole role = FactorRole::none;
  std::vector<std::string> levels;  // unique, at least 2
  // Wording (never in the design hash), one entry per level: what participants read for the
  // level ("" = the level's name; level_label() says which), and instructions shown before the
  // level's first block ("" = none).
  std::vector<std::string> labels;
  std::vector<std::string> instructions;
};

// What participants read for level `level` of `f`: its label, or its name when it has none.
const std::string& level_label(const Factor& f, int level);

// One cell of the full factorial. Conditions are numbered with the first
// declared factor varying slowest: 2 x 2 (transparency, scenario) gives
// 0 off/abstract, 1 off/walkthrough, 2 on/abstract, 3 on/walkthrough.
struct Condition {
  std::vector<int> levels;  // level index per factor, in factor order
  int scenario = 0;         // index into Protocol::scenarios
  int rendering = 0;        // index into Protocol::renderings
  std::string name;         // levels joined by '/', e.g. "off/abstract"
};

// --- ordering (counterbalancing) ------------------------------------------------

enum class Scheme { latin_square, williams, full_permutation, random, fixed };
enum class OrderUnit {
  conditions,  // the scheme orders the cells of the full factorial
  blocks,      // the scheme orders the levels of block_factor; nested_scheme orders
               // the cells of the other factors inside every block
};

struct Ordering {
  OrderUnit unit = OrderUnit::conditions;
  Scheme scheme = Scheme::latin_square;
  int rows = 0;                 // scheme = random: number of random orders (default: participants)
  std::vector<int> fixed;       // scheme = fixed: the order (condition or block-level indices)
  int block_factor = -1;        // unit = blocks: index into Protocol::factors
  Scheme nested_scheme = Scheme::fixed;  // unit = blocks: orders the nested cells
  int nested_rows = 0;          // nested_scheme = random: number of random orders
  std::vector<int> nested_fixed;  // nested_scheme = fixed: the order of nested cells
};

// --- scenes and tasks -------------------------------------------------------------

enum class ScenarioKind { abstract, walkthrough };
enum class TaskType {
  count_targets,    // T1: count all targets (ABSTRACT)
  identify_letter,  // T2: name the letter formed by the target cones (ABSTRACT)
  find_unique,      // T3: find the unique object, mark it on the floor plan (WALKTHROUGH)
  count_kind,       // T4: count the objects of one kind (WALKTHROUGH)
};

// Everything the scene generator needs for one task, after the cascade
// task -> scenario -> built-in default (docs/protocol.md lists each default).
struct SceneParams {
  ScenarioKind kind = ScenarioKind::abstract;
  int objects = 0;                        // number of objects placed (not walls)
  double extent = 0.0;                    // ABSTRACT: edge of the cube holding the objects, world units
  int grid_width = 0, grid_height = 0;    // WALKTHROUGH: floor-plan cells
  double cell_size = 0.0;                 // WALKTHROUGH: world units per cell
  std::vector<std::string> object_kinds;  // ABSTRACT: sphere cone box torus; WALKTHROUGH: model families
                                          // pet vehicle furniture (every model of a listed family is used)
  Range<double> object_radius;            // ABSTRACT: bounding-sphere radius of one object, world units
  Range<double> target_ratio;             // fraction of objects that are targets (T1, T2)
  std::vector<std::string> letters;       // T2: letters drawn (each one of C K R X Y, 5 x 7 grid)
  Range<int> count_range;                 // T4: number of objects of the counted kind
};

struct Task {
  std::string id;  // unique in the protocol, e.g. "T1"
  TaskType type = TaskType::count_targets;
  int trials = 0;  // recorded trials per condition
  SceneParams scene;
  std::string instructions;  // shown to the participant before each task set; "" = the default of its type
};

struct Scenario {
  std::string name;         // the level of the scenario factor it belongs to
  SceneParams scene;        // scenario-level parameters (the tasks' defaults)
  std::vector<Task> tasks;  // run in this order inside every block
};

// --- rendering ----------------------------------------------------------------------

struct Rendering {
  std::string name;                 // the level of the rendering factor it belongs to
  std::string method = "standard";  // a method of the technique registry (study/technique/technique.h)
  // Every key group's keys (technique::Keys: dt, culling, guard, lens, screen_door, vdt, ...), read
  // and range-checked by the group's own code; the method reads the groups it lists. A key written
  // for a group the method does not read is a warning, and keeps its default here.
  technique::Keys keys;
};

// --- session, training, questionnaire --------------------------------------------------

struct Training {
  double time_limit_s = 300.0;  // free exploration before every task set (block x task)
  int practice_trials = 0;      // unscored trials before every task set
  bool practice_label = true;   // practice trials show a "Practice" label
  bool feedback = false;        // after each practice trial: the correct answer
};

// The session's sequence around the trials (docs/protocol.md, "The session's sequence").
// Today's order is the default: a protocol that declares none of this runs as before.
struct Consent {
  std::string title;  // wording
  std::string text;   // the text agreed to, as written in the protocol; its SHA-256 is stored
};

struct Page {  // an information page (briefing, debriefing)
  enum class When { start, end } when = When::start;  // start: after consent; end: after the last questionnaire
  std::string id;
  std::string title;  // wording
  std::string text;   // wording
};

struct Breaks {
  bool after_blocks = true;  // between blocks (today's behaviour)
  int every_trials = 0;      // also after every N recorded trials inside a block (0: never)
  double min_s = 0;          // the participant can go on after min_s (unless skippable)
  double max_s = 0;          // the break ends by itself after max_s (0: when the participant goes on)
  bool skippable = true;     // Continue from the start, ignoring min_s
};

struct Flow {
  bool trial_counter = false;    // trial screens show "Trial k of n"
  bool announce_blocks = false;  // a page before each block: "Next: <the block's levels>"
  std::string language;          // the participants' language tag ("de", "el"); informational
  std::optional<Consent> consent;  // none: no consent page
  std::vector<Page> pages;         // in file order
  Breaks breaks;
};

// [questionnaire.<id>]: the items (study/questionnaire/questionnaire.h: each item type's keys,
// checks and answers are its registration there) and the standard instruments' blocks.
using QuestionnaireItem = questionnaire::Item;

// One thing the experimenter records about a participant at enrollment (age, handedness, ...).
struct DemographicField {
  enum class Type { text, integer, choice };
  std::string id;                    // identifier, the key stored in the ledger
  std::string prompt;                // what the start screen asks
  Type type = Type::text;
  bool required = false;             // enrollment refuses an empty value
  int min = 0, max = 150;            // integer: the accepted range
  std::vector<std::string> options;  // choice: the accepted answers
};

// --- published results to compare with (optional) -------------------------------------

// One published row: a measure's mean and SD per level of the compared factor (the
// rendering factor, else the first factor), or one value for the whole study, and the
// test as printed. Quoted for comparison only: never enters a computation.
struct ReferenceResult {
  std::string measure;            // "time", "accuracy", or a questionnaire item id
  std::string scope = "overall";  // a task id, "overall", or "counting" (the counting tasks pooled)
  std::string location;           // where the source prints it, e.g. "Table III" ("" = not said)
  bool per_level = true;          // false: mean and sd hold one value for the whole study
  std::vector<double> mean, sd;   // per level of the compared factor, in its level order (or one value)
  std::string F, p;               // as printed ("" = not printed)
};

struct ReferenceResults {
  std::string source;               // the citation, e.g. "Elmqvist, Assarsson & Tsigas (2008)"
  std::string label = "published";  // the heading of its columns, e.g. "article"
  int participants = 0;             // n behind the published tests (0 = not given)
  std::vector<ReferenceResult> results;  // in file order
};

struct Protocol {
  std::string source_path;  // as given to load_protocol
  std::string source_text;  // the file's bytes, recorded by the store
  std::string sha256;       // dtlab::sha256_hex(source_text)

  int format = 1;
  std::string id;  // [a-z0-9][a-z0-9_-]*
  std::string title;
  std::string description;
  int participants = 0;         // target number of participants
  std::uint64_t master_seed = 0;
  double session_time_limit_s = 3600.0;

  std::vector<Factor> factors;  // in file order
  std::vector<Condition> conditions;  // the full factorial, first factor slowest
  Ordering order;
  Training training;
  Flow flow;                          // consent, pages, breaks, announcements, counter
  std::vector<Scenario> scenarios;    // in file order
  std::vector<Rendering> renderings;  // in file order
  std::vector<QuestionnaireItem> questionnaire;  // in file order; an instrument block's items in its place
  std::vector<questionnaire::InstrumentUse> instruments;  // the instrument blocks, in file order
  std::vector<DemographicField> demographics;    // in file order; asked at enrollment
  std::optional<ReferenceResults> reference_results;  // [reference_results]; not part of the design
  // [text]: the protocol's wording of participant-facing strings by key (study/protocol/wording.h
  // lists the keys and their English defaults); only the keys it sets. Not part of the design.
  std::vector<std::pair<std::string, std::string>> text;
};

// The design's names as the questionnaire's item types read them (factors and levels, scenarios,
// renderings, the rendering factor).
questionnaire::DesignNames design_names(const Protocol& p);

// The factor whose levels [reference_results] values are given per: the rendering factor, else the
// first factor; -1 when the protocol has no factor.
int compared_factor(const Protocol& p);

// Checks a participant's demographic answers against the protocol's fields (required ones
// present, integers in range, choices among the options, no unknown field); the Error names
// the field. Values are text as entered.
Status check_demographics(const Protocol& p, const std::vector<std::pair<std::string, std::string>>& values);

// --- loading and validation -------------------------------------------------------------

// Reads, parses and checks the file. On failure, the first error (file:line:col, field).
Result<Protocol> load_protocol(const std::string& path);
// The same from text already in memory; `source_path` is used in messages only.
Result<Protocol> load_protocol_text(std::string_view text, const std::string& source_path);

// Every error and warning in the file, in file order; empty = valid with no warnings.
std::vector<Diagnostic> validate_protocol_file(const std::string& path);
std::vector<Diagnostic> validate_protocol_text(std::string_view text, const std::string& source_path);

// True if any diagnostic is an error (warnings alone leave a protocol valid).
bool has_errors(const std::vector<Diagnostic>& diagnostics);

// Where `field` (a dotted path as diagnostics name it, e.g. "scenarios.abstract.tasks.T1.objects"
// or "factors.transparency.levels[1]") is written in p.source_text: the value of the key; for a
// task's scene key the task does not set, the scenario's key; for a key written nowhere (a
// default), the table that would hold it; line 1 for the top level. {0, 0} when p has no text.
struct SourcePos {
  int line = 0;
  int column = 0;
};
SourcePos field_position(const Protocol& p, std::string_view field);

// An Error about `field` of p, at field_position(p, field) in p.source_path.
Error error_at(const Protocol& p, std::string field, std::string message);

// --- names -------------------------------------------------------------------------------

std::string_view to_string(FactorRole role);
std::string_view to_string(Scheme scheme);       // "latin-square", "williams", ...
std::string_view to_string(OrderUnit unit);
std::string_view to_string(ScenarioKind kind);   // "abstract" | "walkthrough"
std::string_view to_string(TaskType type);       // "count-targets", ...
std::string_view to_string(DemographicField::Type type);  // "text", "integer", "choice"

// The number of rows the declared scheme yields for n items (n >= 1):
// latin-square n, williams n (even n) or 2n (odd n), full-permutation n!,
// random `random_rows`, fixed 1. Exact (n! saturates at INT64_MAX, from n = 21 on).
std::int64_t scheme_rows(Scheme scheme, int n, int random_rows);

// Rows of the protocol's ordering (for unit = blocks: outer rows x nested rows), exact
// (saturating at INT64_MAX); a loaded protocol has at most limits::kOrderRows.max.
std::int64_t declared_order_rows(const Protocol& p);

// Index of the condition with these level indices (one per factor); -1 if out of range.
int condition_index(const Protocol& p, const std::vector<int>& levels);

// Lookups by name; nullptr if p has none of that name. Valid while p is.
const Factor* find_factor(const Protocol& p, std::string_view name);
const Scenario* find_scenario(const Protocol& p, std::string_view name);
const Rendering* find_rendering(const Protocol& p, std::string_view name);
// The task of scenario `s` with this id (ids are unique within a scenario); nullptr if none. Valid while s is.
const Task* find_task(const Scenario& s, std::string_view id);
// The factor with this role (at most one per role); nullptr if none.
const Factor* factor_with_role(const Protocol& p, FactorRole role);

// --- identity ----------------------------------------------------------------------------

// SHA-256 of a canonical serialization of everything that changes what a session runs
// (factors, ordering, seeds, limits, training, scene and rendering parameters, the
// questionnaire's structure); comments, white space, key order, title, descriptions and
// prompt texts do not change it. Two protocols with equal design hashes run the same sessions.
std::string design_sha256(const Protocol& p);
// The same of a protocol text (as a study database records it); nullopt if it does not load.
std::optional<std::string> design_sha256_of_text(const std::string& text);

}  // namespace dtlab::protocol
