// The frame graph core without GL: a recording backend stands in for OpenGL
// (the GL backend is exercised by every other render test). Checks culling
// by reference count, roots, execution order, transient lifetimes and pool
// reuse, conditional passes, frames run in stages (flush), and that misuse
// names the pass and resource.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "study/render/detail/frame_graph.h"

namespace dtlab::render {
namespace {

class RecordingBackend final : public FrameGraphBackend {
 public:
  std::vector<std::string> log;
  unsigned next = 1;
  std::vector<std::pair<TextureDesc, unsigned>> pool;
  int created = 0;
  bool query_answer = true;

  unsigned acquire_texture(const TextureDesc& d) override {
    for (auto it = pool.begin(); it != pool.end(); ++it)
      if (it->first == d) {
        const unsigned n = it->second;
        pool.erase(it);
        log.push_back("acquire " + std::to_string(n));
        return n;
      }
    ++created;
    log.push_back("create " + std::to_string(next));
    return next++;
  }
  void release_texture(const TextureDesc& d, unsigned n) override {
    log.push_back("release " + std::to_string(n));
    pool.emplace_back(d, n);
  }
  unsigned acquire_query() override { return 1000 + next++; }
  void release_query(unsigned) override {}
  unsigned framebuffer(const std::vector<unsigned>&, unsigned, TextureFormat) override { return 7; }
  void begin_condition(unsigned q) override { log.push_back("begin-condition " + std::to_string(q)); }
  void end_condition() override { log.push_back("end-condition"); }
  std::optional<bool> query_any(unsigned, bool) override { return query_answer; }
  std::vector<std::string> drain_errors() override { return {}; }
  void finish() override {}
};

const TextureDesc kDesc{16, 16, TextureFormat::rgba8, false};

struct One {
  Handle h;
};
struct Two {
  Handle a, b;
};

// A pass that writes `in` (read-modify-write) and logs its name when it runs.
Handle blend_pass(FrameGraph& fg, std::vector<std::string>& ran, const std::string& name, Handle in) {
  return fg.add_pass<One>(
               name, [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.read(in)); },
               [&ran, name](const One&, PassResources&) { ran.push_back(name); })
      .h;
}

TEST(FrameGraph, CullsPassesWhoseOutputsNothingReads) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle out = fg.import_target("output", {0, 16, 16});
  const Handle color = fg.add_pass<One>(
                            "scene", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                            [&](const One&, PassResources&) { ran.push_back("scene"); })
                           .h;
  // A chain nobody reads: both links must go.
  const Handle debug = fg.add_pass<One>(
                            "debug-a", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("debug", kDesc)); },
                            [&](const One&, PassResources&) { ran.push_back("debug-a"); })
                           .h;
  blend_pass(fg, ran, "debug-b", debug);
  fg.add_pass<Two>(
      "present",
      [&](FrameGraph::Builder& b, Two& d) {
        d.a = b.read(color);
        d.b = b.write(out);
      },
      [&](const Two&, PassResources&) { ran.push_back("present"); });
  fg.compile();
  fg.execute(be);
  EXPECT_EQ(ran, (std::vector<std::string>{"scene", "present"}));
  const FrameReport rep = fg.report(be, true);
  EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"scene", "present"}));
  ASSERT_EQ(rep.passes.size(), 4u);
  EXPECT_TRUE(rep.passes[1].culled);
  EXPECT_TRUE(rep.passes[2].culled);
  EXPECT_EQ(be.created, 1) << "the culled chain's texture must never be allocated";
}

// Profiled with a draw counter, each pass reports the draws and triangles it added to it, and
// a culled pass none; without profiling nothing is counted.
TEST(FrameGraph, ProfiledPassesReportTheirOwnDrawsAndTriangles) {
  for (const bool profile : {true, false}) {
    FrameGraph fg;
    RecordingBackend be;
    DrawCounts counts{5, 500};  // what earlier frames drew: not this frame's
    const Handle out = fg.import_target("output", {0, 16, 16});
    const Handle color = fg.add_pass<One>(
                              "scene", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                              [&](const One&, PassResources&) { counts.draws += 3, counts.triangles += 120; })
                             .h;
    fg.add_pass<One>(
        "unread", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("debug", kDesc)); },
        [&](const One&, PassResources&) { counts.draws += 100, counts.triangles += 100; });
    fg.add_pass<Two>(
        "present",
        [&](FrameGraph::Builder& b, Two& d) {
          d.a = b.read(color);
          d.b = b.write(out);
        },
        [&](const Two&, PassResources&) { counts.draws += 1, counts.triangles += 2; });
    fg.compile();
    fg.execute(be, profile, &counts);
    const FrameReport rep = fg.report(be, true);
    ASSERT_EQ(rep.passes.size(), 3u);
    EXPECT_EQ(rep.passes[0].draws, profile ? 3 : 0);
    EXPECT_EQ(rep.passes[0].triangles, profile ? 120 : 0);
    EXPECT_EQ(rep.passes[1].draws, 0) << "culled";
    EXPECT_EQ(rep.passes[2].draws, profile ? 1 : 0);
    EXPECT_EQ(rep.passes[2].triangles, profile ? 2 : 0);
  }
}

TEST(FrameGraph, SideEffectKeepsAPassWithoutReaders) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  fg.add_pass<One>(
      "count",
      [&](FrameGraph::Builder& b, One& d) {
        d.h = b.write(b.create("scratch", kDesc));
        b.side_effect();
      },
      [&](const One&, PassResources&) { ran.push_back("count"); });
  fg.compile();
  fg.execute(be);
  EXPECT_EQ(ran, (std::vector<std::string>{"count"}));
}

TEST(FrameGraph, WithoutARootEverythingIsCulled) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle c = fg.add_pass<One>(
                        "a", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("c", kDesc)); },
                        [&](const One&, PassResources&) { ran.push_back("a"); })
                       .h;
  blend_pass(fg, ran, "b", c);
  fg.compile();
  fg.execute(be);
  EXPECT_TRUE(ran.empty());
}

TEST(FrameGraph, StaleHandleFailsNamingPassAndResource) {
  FrameGraph fg;
  std::vector<std::string> ran;
  const Handle v1 = fg.add_pass<One>(
                         "scene", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                         [](const One&, PassResources&) {})
                        .h;
  blend_pass(fg, ran, "blend", v1);  // v1 is now stale
  try {
    blend_pass(fg, ran, "late", v1);
    FAIL() << "expected a stale-handle error";
  } catch (const std::logic_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'late'"), std::string::npos) << m;
    EXPECT_NE(m.find("'color'"), std::string::npos) << m;
    EXPECT_NE(m.find("stale"), std::string::npos) << m;
  }
}

TEST(FrameGraph, ReadBeforeAnyWriteFails) {
  FrameGraph fg;
  EXPECT_THROW(fg.add_pass<One>(
                   "reader", [&](FrameGraph::Builder& b, One& d) { d.h = b.read(b.create("empty", kDesc)); },
                   [](const One&, PassResources&) {}),
               std::logic_error);
}

TEST(FrameGraph, UndeclaredAccessInExecuteFailsNamingPassAndResource) {
  FrameGraph fg;
  RecordingBackend be;
  const Handle out = fg.import_target("output", {0, 16, 16});
  const Handle secret = fg.add_pass<One>(
                             "maker", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("secret", kDesc)); },
                             [](const One&, PassResources&) {})
                            .h;
  fg.add_pass<Two>(
      "sneaky",
      [&](FrameGraph::Builder& b, Two& d) {
        d.a = b.read(secret);
        d.b = b.write(out);
      },
      [&](const Two&, PassResources& r) {
        Handle undeclared = out;  // the pre-write version was never declared by this pass
        (void)r.framebuffer({undeclared});
      });
  fg.compile();
  try {
    fg.execute(be);
    FAIL() << "expected an undeclared-access error";
  } catch (const std::logic_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("'sneaky'"), std::string::npos) << m;
    EXPECT_NE(m.find("'output'"), std::string::npos) << m;
  }
}

TEST(FrameGraph, TransientsLiveFromFirstToLastUserAndAreReused) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle out = fg.import_target("output", {0, 16, 16});
  // Two scratch textures with disjoint lifetimes: the second must reuse the first's texture.
  Handle acc = fg.add_pass<One>(
                    "first", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("acc", kDesc)); },
                    [](const One&, PassResources&) {})
                   .h;
  for (int i = 0; i < 2; ++i) {
    acc = fg.add_pass<Two>(
                "mask" + std::to_string(i),
                [&](FrameGraph::Builder& b, Two& d) {
                  d.a = b.write(b.create("scratch" + std::to_string(i), {8, 8, TextureFormat::r16f, true}));
                  d.b = b.write(b.read(acc));
                },
                [](const Two&, PassResources&) {})
              .b;
  }
  fg.add_pass<Two>(
      "present",
      [&](FrameGraph::Builder& b, Two& d) {
        d.a = b.read(acc);
        d.b = b.write(out);
      },
      [](const Two&, PassResources&) {});
  fg.compile();
  fg.execute(be);
  EXPECT_EQ(be.created, 2) << "acc + one scratch texture shared by both mask passes";
  const std::vector<std::string> want{"create 1", "create 2", "release 2", "acquire 2", "release 2", "release 1"};
  EXPECT_EQ(be.log, want);
}

TEST(FrameGraph, ConditionalPassRunsInsideTheConditionAndReportsTheAnswer) {
  for (bool answer : {true, false}) {
    FrameGraph fg;
    RecordingBackend be;
    be.query_answer = answer;
    std::vector<std::string> ran;
    const Handle out = fg.import_target("output", {0, 16, 16});
    const Handle color = fg.add_pass<One>(
                              "opaque", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                              [](const One&, PassResources&) {})
                             .h;
    const Handle q = fg.add_pass<Two>(
                          "query",
                          [&](FrameGraph::Builder& b, Two& d) {
                            d.a = b.read(color);
                            d.b = b.write(b.create_query("occluded"));
                          },
                          [](const Two&, PassResources&) {})
                         .b;
    const Handle fx = fg.add_pass<One>(
                           "effect",
                           [&](FrameGraph::Builder& b, One& d) {
                             b.condition(q);
                             d.h = b.write(b.read(color));
                           },
                           [&](const One&, PassResources&) { be.log.push_back("effect body"); })
                          .h;
    fg.add_pass<Two>(
        "present",
        [&](FrameGraph::Builder& b, Two& d) {
          d.a = b.read(fx);
          d.b = b.write(out);
        },
        [](const Two&, PassResources&) {});
    fg.compile();
    fg.execute(be);
    const auto it = std::find(be.log.begin(), be.log.end(), "effect body");
    ASSERT_NE(it, be.log.end());
    EXPECT_EQ((it - 1)->rfind("begin-condition", 0), 0u);
    EXPECT_EQ(*(it + 1), "end-condition");
    const FrameReport rep = fg.report(be, true);
    EXPECT_EQ(rep.passes[2].conditional, true);
    EXPECT_EQ(rep.passes[2].ran, answer);
    const std::vector<std::string> run = rep.passes_run();
    EXPECT_EQ(std::count(run.begin(), run.end(), "effect"), answer ? 1 : 0);
  }
}

// Regression (the dt-seed graph): `dt-clear`, conditional on the target query, overwrites the
// opaque pass's colour without reading it. When the query says no, `present` shows the opaque
// colour, so the opaque pass must survive on that dependency alone (it used to survive only
// because the query pass read its depth). Here nothing else reads the opaque pass's output.
TEST(FrameGraph, AConditionalWriteKeepsThePreviousWriterAlive) {
  FrameGraph fg;
  RecordingBackend be;
  be.query_answer = false;
  const Handle out = fg.import_target("output", {0, 16, 16});
  const Handle q = fg.add_pass<One>(
                        "query", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create_query("occluded")); },
                        [](const One&, PassResources&) {})
                       .h;
  const Handle color = fg.add_pass<One>(
                            "opaque", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                            [&](const One&, PassResources&) { be.log.push_back("opaque body"); })
                           .h;
  const Handle cleared = fg.add_pass<One>(
                              "clear",
                              [&](FrameGraph::Builder& b, One& d) {
                                b.condition(q);
                                d.h = b.write(color);  // no read: it overwrites everything
                              },
                              [](const One&, PassResources&) {})
                             .h;
  fg.add_pass<Two>(
      "present",
      [&](FrameGraph::Builder& b, Two& d) {
        d.a = b.read(cleared);
        d.b = b.write(out);
      },
      [](const Two&, PassResources&) {});
  fg.compile();
  fg.execute(be);
  EXPECT_NE(std::find(be.log.begin(), be.log.end(), "opaque body"), be.log.end());
  EXPECT_EQ(fg.answer(q, be, true), false);
  const FrameReport rep = fg.report(be, true);
  EXPECT_FALSE(rep.passes[1].culled) << "opaque";
  EXPECT_EQ(rep.passes_run(), (std::vector<std::string>{"query", "opaque", "present"}));
}

// A frame in two stages (occlusion culling's shape): the first stage's passes run at flush(),
// in full, before the second stage is even declared; what the first stage computed on the CPU
// decides what the second declares; the report, and the Graphviz export, hold both stages.
TEST(FrameGraph, FlushRunsTheFirstStageBeforeTheSecondIsDeclared) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle out = fg.import_target("output", {0, 16, 16});
  const Handle map = fg.add_pass<One>(
                          "cull-map", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("map", kDesc)); },
                          [&](const One& d, PassResources& r) {
                            ran.push_back("cull-map");
                            EXPECT_NE(r.texture(d.h), 0u);
                          })
                         .h;
  int hidden = -1;  // the CPU's answer, known only once the first stage ran
  fg.add_pass<One>(
      "cull-test",
      [&](FrameGraph::Builder& b, One& d) {
        d.h = b.read(map);
        b.side_effect();
      },
      [&](const One&, PassResources&) {
        ran.push_back("cull-test");
        hidden = 2;
      });
  // An unread pass of the first stage is culled there, as in any stage.
  fg.add_pass<One>(
      "orphan", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("unused", kDesc)); },
      [&](const One&, PassResources&) { ran.push_back("orphan"); });
  fg.flush(be);
  EXPECT_EQ(ran, (std::vector<std::string>{"cull-map", "cull-test"}));
  ASSERT_EQ(hidden, 2);
  const int created_first = be.created;
  // The second stage: as many passes as the first stage's answer says, then present.
  Handle color = fg.add_pass<One>(
                      "scene", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("color", kDesc)); },
                      [&](const One&, PassResources&) { ran.push_back("scene"); })
                     .h;
  for (int i = 0; i < hidden; ++i) color = blend_pass(fg, ran, "layer " + std::to_string(i), color);
  fg.add_pass<Two>(
      "present",
      [&](FrameGraph::Builder& b, Two& d) {
        d.a = b.read(color);
        d.b = b.write(out);
      },
      [&](const Two&, PassResources&) { ran.push_back("present"); });
  fg.compile();
  fg.execute(be);
  EXPECT_EQ(ran, (std::vector<std::string>{"cull-map", "cull-test", "scene", "layer 0", "layer 1", "present"}));
  EXPECT_EQ(be.created, created_first) << "the second stage reuses the first stage's freed texture (same desc)";
  const FrameReport rep = fg.report(be, true);
  EXPECT_EQ(rep.passes_run(),
            (std::vector<std::string>{"cull-map", "cull-test", "scene", "layer 0", "layer 1", "present"}));
  ASSERT_EQ(rep.passes.size(), 7u);
  EXPECT_TRUE(rep.passes[2].culled) << "orphan";
  const std::string dot = fg.graphviz();
  EXPECT_NE(dot.find("subgraph cluster_stage0"), std::string::npos);
  EXPECT_NE(dot.find("subgraph cluster_stage1"), std::string::npos);
  EXPECT_LT(dot.find("label=\"cull-test\""), dot.find("subgraph cluster_stage1"));
}

// The second stage may not touch the first stage's transients (their passes ran and their
// textures went back to the pool); imported targets carry over.
TEST(FrameGraph, AStageCannotReadAFlushedStagesTransients) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle out = fg.import_target("output", {0, 16, 16});
  const Handle map = fg.add_pass<One>(
                          "cull-map", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("map", kDesc)); },
                          [](const One&, PassResources&) {})
                         .h;
  const Handle shown = blend_pass(fg, ran, "draw-to-output", out);
  fg.add_pass<One>(
      "keep",
      [&](FrameGraph::Builder& b, One& d) {
        d.h = b.read(map);
        b.side_effect();
      },
      [](const One&, PassResources&) {});
  fg.flush(be);
  try {
    fg.add_pass<One>("late", [&](FrameGraph::Builder& b, One& d) { d.h = b.read(map); }, [](const One&, PassResources&) {});
    FAIL() << "reading a flushed stage's transient must throw";
  } catch (const std::logic_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'late'"), std::string::npos) << what;
    EXPECT_NE(what.find("'map'"), std::string::npos) << what;
    EXPECT_NE(what.find("flushed stage"), std::string::npos) << what;
  }
  // The imported output, written in the first stage, carries over.
  fg.add_pass<One>("present", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.read(shown)); },
                   [&](const One&, PassResources&) { ran.push_back("present"); });
  fg.compile();
  fg.execute(be);
  EXPECT_EQ(ran, (std::vector<std::string>{"draw-to-output", "present"}));
}

TEST(FrameGraph, GraphvizNamesPassesAndResourcesAndGreysCulledOnes) {
  FrameGraph fg;
  RecordingBackend be;
  std::vector<std::string> ran;
  const Handle out = fg.import_target("output", {0, 16, 16});
  fg.add_pass<One>(
      "orphan", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(b.create("unused", kDesc)); },
      [](const One&, PassResources&) {});
  fg.add_pass<One>(
      "present", [&](FrameGraph::Builder& b, One& d) { d.h = b.write(out); }, [](const One&, PassResources&) {});
  fg.compile();
  const std::string dot = fg.graphviz();
  EXPECT_NE(dot.find("digraph"), std::string::npos);
  EXPECT_NE(dot.find("label=\"orphan\""), std::string::npos);
  EXPECT_NE(dot.find("grey80"), std::string::npos);
  EXPECT_NE(dot.find("unused\\nv1"), std::string::npos);
}

}  // namespace
}  // namespace dtlab::render
