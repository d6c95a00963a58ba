// validate_runnable (runnable.h): the later stages' own checks, called on
// every value a session will hand them, in protocol order: tasks' scenes,
// renderings at every checked viewport, the work of one frame per condition,
// then the questionnaire's depth tests. Each problem is reported once (one
// message at one place), at the line of the key behind it.
#include "study/session/runnable.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>

#include "study/common/text.h"
#include "study/render/render.h"
#include "study/scene/letters.h"
#include "study/session/mapping.h"

namespace dtlab::session {

namespace {

using protocol::Protocol;

class Report {
 public:
  explicit Report(std::vector<Diagnostic>& out) : out_(out) {}
  // Adds the error unless the same message was reported at the same place (tasks that inherit
  // one scenario key fail alike: the key is reported once, under the first task).
  void add(const Error& e) {
    const std::string where = e.line > 0 ? std::to_string(e.line) + ":" + std::to_string(e.column) : e.field;
    if (seen_.insert(where + '\n' + e.message).second) out_.push_back({Severity::error, e});
  }
  // True if an error was reported for `field` or a field inside it.
  bool has(const std::string& field) const {
    return std::any_of(out_.begin(), out_.end(), [&](const Diagnostic& d) {
      const std::string& f = d.where.field;
      return f.rfind(field, 0) == 0 && (f.size() == field.size() || f[field.size()] == '.' || f[field.size()] == '[');
    });
  }

 private:
  std::vector<Diagnostic>& out_;
  std::set<std::string> seen_;
};

std::string task_field(const protocol::Scenario& s, const protocol::Task& t) {
  return "scenarios." + s.name + ".tasks." + t.id;
}

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// A task a rendering meets: in a condition, or as the depth test's scene.
struct Meeting {
  const protocol::Scenario* scenario;
  const protocol::Task* task;
};

// The work of one frame of `r` on the task with the most targets it meets, against the bounds
// of runnable.h (one error per key, naming that task).
void check_work(const Protocol& p, const protocol::Rendering& r, const std::vector<Meeting>& meets, Report& report) {
  const technique::Technique* method = technique::find(r.method);
  if (method == nullptr || method->mask_texels == nullptr || meets.empty()) return;
  const Meeting* worst = &meets.front();
  for (const Meeting& m : meets)
    if (max_targets(*m.task) > max_targets(*worst->task)) worst = &m;
  const long long targets = max_targets(*worst->task);
  const double texels = method->mask_texels(r.keys, targets);
  const std::string what = "method = \"" + r.method + "\" on task " + worst->task->id + " of scenario '" +
                           worst->scenario->name + "' (up to " + count(targets, "target") + ")";
  if (texels > static_cast<double>(kMaxMaskTexelsPerFrame))
    report.add(protocol::error_at(
        p, "rendering." + r.name + ".mask_resolution",
        what + " needs " + sci(texels) + " mask texel writes per frame (targets x (gradient_width + 2) x mask_resolution^2); at most " +
            sci(static_cast<double>(kMaxMaskTexelsPerFrame)) +
            ": lower mask_resolution or gradient_width, or use method = \"dt-fast\""));
}

bool is_depth_test(const protocol::QuestionnaireItem& item) { return item.type && item.type->name == "depth-test"; }

// The depth test of `item`: enough objects for its pairs, the work of its view, and the view
// and pairs themselves for the first participants.
void check_depth_test(const Protocol& p, const protocol::QuestionnaireItem& item, Report& report) {
  const std::string field = "questionnaire." + item.id;
  const protocol::Scenario* s = find_scenario(p, item.text("scenario"));
  const protocol::Rendering* r = find_rendering(p, item.text("rendering"));
  const int pairs = static_cast<int>(item.integer("pairs"));
  if (!s || !r || s->tasks.empty()) return;  // load_protocol reports these
  const protocol::Task& shown = s->tasks.front();  // depth_test_view's scene
  if (report.has(task_field(*s, shown)) || report.has("rendering." + r->name)) return;  // reported already
  if (s->scene.kind == protocol::ScenarioKind::walkthrough && 2 * pairs > shown.scene.objects) {
    report.add(protocol::error_at(p, field + ".pairs",
                                  "pairs = " + std::to_string(pairs) + " needs " + std::to_string(2 * pairs) +
                                      " distinct objects; the depth test's scene (task " + shown.id + " of scenario '" +
                                      s->name + "') places " + std::to_string(shown.scene.objects)));
    return;
  }
  std::vector<Question> questions = questionnaire::expand(item, protocol::design_names(p));
  const int indexes = std::min(p.participants, kDepthTestIndexesChecked);
  for (int k = 0; k < indexes; ++k) {
    for (const Viewport vp : {Viewport{160, 120}, Viewport{1920, 1080}}) {
      auto view = depth_test_view(p, item, k, vp, questions);
      if (!view) {
        Error e = view.error();
        if (e.field == field + ".pairs")  // the one outcome that depends on the participant's scene
          e.message += " (participant with enrollment index " + std::to_string(k) + ", " + std::to_string(vp.width) +
                       "x" + std::to_string(vp.height) + " viewport)";
        report.add(e);
        return;
      }
    }
  }
}

}  // namespace

std::vector<Viewport> checked_viewports() {
  return {{kMinViewportSide, kMinViewportSide}, {160, 120}, {800, 600}, {1920, 1080},
          {kMaxViewportSide, kMaxViewportSide}};
}

int max_targets(const protocol::Task& task) {
  const protocol::SceneParams& sc = task.scene;
  switch (task.type) {
    case protocol::TaskType::count_targets:
      return static_cast<int>(std::floor(sc.target_ratio.max * sc.objects + 1e-9));
    case protocol::TaskType::identify_letter: {
      int most = 0;
      for (const std::string& l : sc.letters)
        if (const scene::LetterBitmap* b = l.size() == 1 ? scene::find_letter(l[0]) : nullptr)
          most = std::max(most, b->lit());
      return most;
    }
    case protocol::TaskType::find_unique:
    case protocol::TaskType::count_kind: break;
  }
  return sc.objects;
}

std::vector<Diagnostic> validate_runnable(const Protocol& p, const std::vector<Viewport>& also) {
  std::vector<Diagnostic> out;
  Report report(out);
  for (const protocol::Scenario& s : p.scenarios)
    for (const protocol::Task& t : s.tasks) {
      if (auto params = scene_params(p, s, t); !params) {
        report.add(params.error());
        continue;
      }
      if (const int targets = max_targets(t); targets > kMaxTargets) {
        const bool by_ratio = t.type == protocol::TaskType::count_targets;
        report.add(protocol::error_at(
            p, task_field(s, t) + (by_ratio ? ".target_ratio" : ".objects"),
            "a trial may have " + std::to_string(targets) + " targets (" +
                (by_ratio ? "target_ratio max x objects" : "every object is a target") + "); at most " +
                std::to_string(kMaxTargets) + ", the most a simulated participant can count in every view"));
      }
    }

  std::vector<Viewport> viewports = checked_viewports();
  viewports.insert(viewports.end(), also.begin(), also.end());
  for (const protocol::Rendering& r : p.renderings)
    for (const Viewport& vp : viewports)
      if (auto f = frame_settings(p, r, vp.width, vp.height); !f) {
        report.add(f.error());
        break;  // one viewport is enough to say what is wrong
      }

  // Per rendering, every task it meets: the tasks of its conditions' scenarios, the depth tests' scenes.
  for (std::size_t ri = 0; ri < p.renderings.size(); ++ri) {
    std::vector<Meeting> meets;
    std::set<int> scenarios;
    for (const protocol::Condition& c : p.conditions)
      if (c.rendering == static_cast<int>(ri)) scenarios.insert(c.scenario);
    for (int si : scenarios)
      for (const protocol::Task& t : p.scenarios[static_cast<std::size_t>(si)].tasks)
        meets.push_back({&p.scenarios[static_cast<std::size_t>(si)], &t});
    for (const protocol::QuestionnaireItem& item : p.questionnaire) {
      if (!is_depth_test(item)) continue;
      const protocol::Scenario* s = find_scenario(p, item.text("scenario"));
      if (item.text("rendering") == p.renderings[ri].name && s && !s->tasks.empty()) meets.push_back({s, &s->tasks.front()});
    }
    check_work(p, p.renderings[ri], meets, report);
  }

  for (const protocol::QuestionnaireItem& item : p.questionnaire)
    if (is_depth_test(item)) check_depth_test(p, item, report);

  std::stable_sort(out.begin(), out.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return std::pair(a.where.line, a.where.column) < std::pair(b.where.line, b.where.column);
  });
  return out;
}

}  // namespace dtlab::session
