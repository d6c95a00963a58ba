// The simulated participant (study/sim/sim.h): deterministic for the same
// (protocol, participant, seed); traits vary between participants; and sanity
// checks that fail if the renderer did not show what the condition shows: on
// fixed seeds the agent notices at least as many targets in its first ABSTRACT
// view under dt-seed as under standard (same scene, same random numbers), and
// finds the WALKTHROUGH target in fewer views when walls turn transparent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "app/platform/gl_context.h"
#include "study/design/design.h"
#include "study/session/mapping.h"
#include "study/sim/sim.h"

namespace dtlab::sim {
namespace {

constexpr int kW = 160, kH = 120;

class Sim : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto c = platform::create_headless(kW, kH);
    ASSERT_TRUE(c.ok()) << c.error().to_string();
    ctx_ = std::move(c.value()).release();
    auto p = protocol::load_protocol(std::string(DTLAB_SOURCE_DIR) + "/protocols/elmqvist2008.toml");
    ASSERT_TRUE(p.ok());
    protocol_ = new protocol::Protocol(std::move(p.value()));
  }
  static void TearDownTestSuite() {
    delete ctx_;
    delete protocol_;
  }
  static platform::GlContext* ctx_;
  static protocol::Protocol* protocol_;

  // One trial of participant k's plan: the first trial of `task`, under rendering `rendering`
  // (0 off = standard, 1 on = dt-seed) whatever its planned condition.
  struct Trial {
    design::PlannedTrial planned;
    session::TrialSetup setup;
    scene::Scene scene;
    session::TrialSpec spec;
  };
  static std::unique_ptr<Trial> trial(int k, const std::string& task, int rendering) {
    auto t = std::make_unique<Trial>();
    const protocol::Protocol& p = *protocol_;
    for (const auto& pt : design::make_plan(p, k).trials)
      if (pt.task == task && pt.trial == 1) {
        t->planned = pt;
        break;
      }
    t->setup = session::trial_setup(p, t->planned).value();
    t->setup.rendering = &p.renderings[static_cast<std::size_t>(rendering)];
    t->planned.method = t->setup.rendering->method;
    t->scene = session::trial_scene(t->setup, t->planned).value();
    t->spec.protocol = &p;
    t->spec.enrollment_index = k;
    t->spec.planned = t->planned;
    t->spec.planned_trials = 24;
    t->spec.setup = &t->setup;
    t->spec.scene = &t->scene;
    t->spec.frame = session::frame_settings(p, *t->setup.rendering, kW, kH).value();
    t->spec.time_limit_s = 3600;
    return t;
  }
};
platform::GlContext* Sim::ctx_ = nullptr;
protocol::Protocol* Sim::protocol_ = nullptr;

std::string text(const std::optional<store::Answer>& a) {
  if (!a) return "none";
  if (const auto* c = std::get_if<store::Count>(&*a)) return "count " + std::to_string(c->n);
  if (const auto* l = std::get_if<store::Letter>(&*a)) return "letter " + l->letter;
  const auto& p = std::get<store::Position>(*a);
  return "position " + std::to_string(p.x) + "," + std::to_string(p.z);
}

SimOptions options(std::uint64_t seed = 0) {
  SimOptions o;
  o.width = kW;
  o.height = kH;
  o.seed = seed;
  return o;
}

TEST_F(Sim, SameParticipantSameSeedSameOutcome) {
  for (const char* task : {"T1", "T2", "T3", "T4"}) {
    SCOPED_TRACE(task);
    auto t = trial(1, task, 1);
    SimulatedParticipant a(options()), b(options());
    auto x = a.run_trial(t->spec);
    auto y = b.run_trial(t->spec);
    ASSERT_TRUE(x.ok() && y.ok());
    EXPECT_EQ(text(x->answer), text(y->answer));
    EXPECT_EQ(x->completion_s, y->completion_s);
    EXPECT_GT(x->completion_s, 0.0);
    ASSERT_EQ(x->poses.size(), y->poses.size());
    ASSERT_EQ(x->frame_ms.size(), x->poses.size());
    for (std::size_t i = 0; i < x->poses.size(); ++i) {
      EXPECT_EQ(x->poses[i].t_s, y->poses[i].t_s);
      EXPECT_EQ(x->poses[i].yaw, y->poses[i].yaw);
      EXPECT_EQ(x->poses[i].x, y->poses[i].x);
    }
    ASSERT_EQ(x->events.size(), y->events.size());
    for (std::size_t i = 0; i < x->events.size(); ++i) {
      EXPECT_EQ(x->events[i].t_s, y->events[i].t_s);
      EXPECT_EQ(x->events[i].detail, y->events[i].detail);
    }
    ASSERT_FALSE(x->events.empty());
    EXPECT_EQ(x->events.back().kind, store::InputEvent::Kind::answer);
    for (std::size_t i = 1; i < x->events.size(); ++i) EXPECT_LE(x->events[i - 1].t_s, x->events[i].t_s) << i;
    for (std::size_t i = 1; i < x->poses.size(); ++i) EXPECT_LE(x->poses[i - 1].t_s, x->poses[i].t_s) << i;
    // A run in between (another trial) changes nothing: no state carries over.
    auto other = trial(2, task, 0);
    ASSERT_TRUE(a.run_trial(other->spec).ok());
    auto z = a.run_trial(t->spec);
    ASSERT_TRUE(z.ok());
    EXPECT_EQ(text(z->answer), text(x->answer));
    EXPECT_EQ(z->completion_s, x->completion_s);
  }
}

TEST_F(Sim, TraitsVaryBetweenParticipantsAndWithTheSimSeed) {
  std::vector<double> log_speed;
  for (int k = 0; k < 64; ++k) {
    const Traits t = draw_traits(agent_seed(protocol_->master_seed, k, 0));
    log_speed.push_back(std::log(t.speed));
    EXPECT_GE(t.attention, 0.8);
    EXPECT_LE(t.attention, 1.0);
    EXPECT_GE(t.patience, 2);
    EXPECT_LE(t.patience, 3);
  }
  double mean = 0, ss = 0;
  for (double v : log_speed) mean += v / 64;
  for (double v : log_speed) ss += (v - mean) * (v - mean);
  const double sd = std::sqrt(ss / 63);
  EXPECT_NEAR(sd, 0.30, 0.10) << "between-participant spread of speed (lognormal sd 0.30)";
  EXPECT_NE(agent_seed(1, 0, 0), agent_seed(1, 1, 0));
  EXPECT_NE(agent_seed(1, 0, 0), agent_seed(1, 0, 1));
  EXPECT_EQ(draw_traits(agent_seed(7, 3, 2)).speed, draw_traits(agent_seed(7, 3, 2)).speed);
}

// The renderer shows occluded targets under dt-seed, so the same agent on the same scene with the
// same random numbers notices at least as many in its first view -- and more on some seeds.
TEST_F(Sim, DynamicTransparencyShowsMoreTargetsInTheFirstView) {
  int more = 0;
  for (int k = 0; k < 4; ++k) {
    auto standard = trial(k, "T1", 0), dt = trial(k, "T1", 1);
    ASSERT_EQ(standard->scene.hash, dt->scene.hash);
    SimulatedParticipant agent(options());
    ASSERT_TRUE(agent.run_trial(standard->spec).ok());
    const TrialTrace s = agent.last_trace();
    ASSERT_TRUE(agent.run_trial(dt->spec).ok());
    const TrialTrace d = agent.last_trace();
    ASSERT_FALSE(s.noticed.empty());
    ASSERT_FALSE(d.noticed.empty());
    EXPECT_GE(d.visible[0], s.visible[0]) << "participant " << k;
    EXPECT_GE(d.noticed[0], s.noticed[0]) << "participant " << k;
    more += d.noticed[0] > s.noticed[0];
  }
  EXPECT_GE(more, 2) << "dt-seed should reveal hidden targets on most of these seeds";
}

// An active searchlight (the protocol's default radius, 0.2 of the view's height) is swept over
// every ABSTRACT view: a cursor event per spot, each spot's frames after its event (replay puts the
// searchlight there), an extra aid_spot_s per spot, and it shows at least what standard shows.
TEST_F(Sim, AnActiveSearchlightIsSweptOverEveryView) {
  int more = 0;
  for (int k = 0; k < 3; ++k) {
    auto standard = trial(k, "T1", 0), active = trial(k, "T1", 1);
    protocol::Rendering searchlight = *active->setup.rendering;
    searchlight.keys.dt.mode = "active";
    active->spec.frame = session::frame_settings(*protocol_, searchlight, kW, kH).value();
    ASSERT_EQ(active->spec.frame.dt.searchlight_radius, 24.0f) << "0.2 x 120 rows";
    SimulatedParticipant agent(options());
    ASSERT_TRUE(agent.run_trial(standard->spec).ok());
    const TrialTrace s = agent.last_trace();
    auto out = agent.run_trial(active->spec);
    ASSERT_TRUE(out.ok());
    const TrialTrace a = agent.last_trace();
    EXPECT_EQ(a.aid_spots, 12 * a.views) << "4 x 3 cells of 48 pixels on 160 x 120";
    EXPECT_EQ(s.aid_spots, 0);
    // The spots' cursor events, in sweep order, and no frame before the first of its view.
    std::vector<store::InputEvent> spots;
    for (const auto& e : out->events)
      if (e.kind == store::InputEvent::Kind::cursor) spots.push_back(e);
    ASSERT_GE(spots.size(), 12u);
    EXPECT_FLOAT_EQ(spots[0].x, 20.0f);
    EXPECT_FLOAT_EQ(spots[0].y, 20.0f);
    EXPECT_FLOAT_EQ(spots[4].x, 140.0f);
    EXPECT_FLOAT_EQ(spots[4].y, 60.0f);
    EXPECT_LE(spots[0].t_s, out->poses.front().t_s);
    EXPECT_GE(out->poses.size(), static_cast<std::size_t>(12 * a.views));
    // Eleven more spots per view, each 0.25 s times the participant's speed, at the least.
    const double speed = draw_traits(agent_seed(protocol_->master_seed, k, 0)).speed;
    EXPECT_GE(out->completion_s, a.views * 11 * 0.25 * speed);
    EXPECT_GE(a.visible[0], s.visible[0]) << "participant " << k;
    more += a.visible[0] > s.visible[0];
  }
  EXPECT_GE(more, 1) << "the sweep should reveal hidden targets on some of these seeds";
}

// Walls turn transparent around targets under dt-seed: the unique object is found in fewer views.
TEST_F(Sim, TransparentWallsShortenTheWalkthroughSearch) {
  int standard_views = 0, dt_views = 0;
  for (int k = 0; k < 4; ++k) {
    SimulatedParticipant agent(options());
    ASSERT_TRUE(agent.run_trial(trial(k, "T3", 0)->spec).ok());
    standard_views += agent.last_trace().views;
    ASSERT_TRUE(agent.run_trial(trial(k, "T3", 1)->spec).ok());
    dt_views += agent.last_trace().views;
  }
  EXPECT_LT(dt_views * 2, standard_views) << dt_views << " views with dt-seed, " << standard_views << " standard";
}

// At every stop in a building the agent turns a full circle; its views must leave no blind sector
// (a regression: 90-degree turns with a 75-degree horizontal field of view never looked into
// four 15-degree sectors at any stop). Checked at the first stop of T4 (which always completes its
// turn), before the first walk.
TEST_F(Sim, LookingAroundAtAStopCoversTheFullCircle) {
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    auto t = trial(k, "T4", 0);
    SimulatedParticipant agent(options());
    auto out = agent.run_trial(t->spec);
    ASSERT_TRUE(out.ok());
    double first_walk = 1e300;
    for (const auto& e : out->events)
      if (e.kind == store::InputEvent::Kind::key_down) first_walk = std::min(first_walk, e.t_s);
    std::vector<double> yaws;
    for (const auto& p : out->poses)
      if (p.t_s < first_walk) yaws.push_back(std::remainder(static_cast<double>(p.yaw), 2 * M_PI) + M_PI);
    std::sort(yaws.begin(), yaws.end());
    yaws.erase(std::unique(yaws.begin(), yaws.end(), [](double a, double b) { return std::abs(a - b) < 1e-6; }),
               yaws.end());
    const double fov_x = 2 * std::atan(std::tan(0.5 * t->scene.camera.fov_y) * kW / kH);
    ASSERT_GE(yaws.size(), 2u);
    double widest = 2 * M_PI - (yaws.back() - yaws.front());
    for (std::size_t i = 1; i < yaws.size(); ++i) widest = std::max(widest, yaws[i] - yaws[i - 1]);
    EXPECT_LE(widest, fov_x + 1e-6) << yaws.size() << " views; widest turn between views " << widest
                                    << " rad, horizontal field of view " << fov_x << " rad";
  }
}

// Ratings come from the agent's own recorded times: a condition where it was twice as fast gets
// the higher rating, and the preference goes to it.
TEST_F(Sim, QuestionnaireFollowsExperience) {
  session::QuestionnaireSpec spec;
  spec.protocol = protocol_;
  spec.enrollment_index = 0;
  spec.questions = session::expand_questionnaire(*protocol_);
  // Drop the depth test here (it needs a view); keep ratings and the preference.
  std::erase_if(spec.questions, [](const session::Question& q) { return q.item->type->name == "depth-test"; });
  for (const auto& pt : design::make_plan(*protocol_, 0).trials) {
    const bool on = pt.levels[0].second == "on";
    spec.history.push_back({pt, on ? 20.0 : 40.0, true});
  }
  double on_sum = 0, off_sum = 0;
  int on_pref = 0;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    SimulatedParticipant agent(options(seed));
    auto a = agent.answer_questionnaire(spec);
    ASSERT_TRUE(a.ok());
    ASSERT_EQ(a->size(), spec.questions.size());
    for (std::size_t i = 0; i < spec.questions.size(); ++i) {
      const auto& q = spec.questions[i];
      if (q.item->type->name == "rating" && !q.levels.empty()) {
        const double r = std::get<double>((*a)[i]);
        EXPECT_GE(r, 0);
        EXPECT_LE(r, 4);
        (q.scope.find("transparency=on") != std::string::npos ? on_sum : off_sum) += r;
      }
      if (q.item->type->name == "choice") on_pref += std::get<std::string>((*a)[i]) == "on";
    }
  }
  EXPECT_GT(on_sum, off_sum + 8 * 2);  // two scenarios, eight agents: clearly higher
  EXPECT_GE(on_pref, 7);
}

}  // namespace
}  // namespace dtlab::sim
