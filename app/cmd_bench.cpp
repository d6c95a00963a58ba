// `dtlab bench [--json] [--frames K] ...`: the renderer's cost and accuracy.
// For an ABSTRACT (200 objects) and a WALKTHROUGH scene at 800x600 and
// 1280x1024: median frame time of every method as a ratio to `standard`
// measured in the same run (frames interleaved round-robin, so machine load
// hits every method alike); standard timed again alone in a fresh process
// (a method's time must not depend on what else the process rendered); image
// error against `reference` over the frame and over the effect region (where
// some target's exact mask is below 1), and dt-fast against dt-seed there;
// passes run; the R1 guard both ways; the lens method (three shapes and
// styles; no error column: reference is not its yardstick); screen-door at 8 x 8, 16 x 16 and
// 32 x 32 masks (errors against reference); vdt (no error column either:
// another transparency model); then what accuracy costs: mask
// resolution 64/256/full and gradient width sweeps. With --culling, only
// occlusion culling along walkthrough routes (bench_culling.h). Table on
// stdout (or --json), progress on stderr.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "app/bench_culling.h"
#include "app/commands.h"
#include "app/platform/gl_context.h"
#include "study/render/render.h"
#include "study/scene/generate.h"

namespace dtlab::app {

namespace {

struct BenchOptions {
  bool json = false;
  int frames = 15;
  std::uint64_t seed = 1;
  std::vector<std::string> sizes{"800x600", "1280x1024"};
  std::vector<std::string> scenes{"abstract", "walkthrough"};
  bool sweep = true;
  bool alone = true;      // time standard again in a fresh process
  bool slow = true;  // the rows of slow methods (technique::Technique::bench_slow: seconds a frame)
  double budget_s = 4.0;  // per configuration: stop repeating a slow one after this much time
  bool culling = false;   // instead: occlusion culling along walkthrough routes (bench_culling.h)
  std::vector<std::string> culling_methods{"standard", "dt-fast"};
};

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// Error columns: against reference over the frame and the effect region; dt-fast against dt-seed
// with the same settings in the effect region.
struct Errors {
  bool frame = false, vs_seed = false;
  render::ImageDiff whole, effect, seed_effect;
};

struct Config {
  std::string label;          // e.g. "dt-fast", "dt-seed R=64", "dt-fast nothing occluded"
  render::FrameSettings settings;
  render::Renderer* renderer = nullptr;
  std::vector<double> wall, cpu;
  double spent_s = 0.0;
  int min_frames = 3;         // timed frames before the budget may stop it
  int passes = 0;
  Errors error;
  render::Image image;
  int frames_alone = 0;  // timed in another process: the frames it reported
  std::string note;
};

struct Row {
  std::string scene;
  int width = 0, height = 0;
  std::string method, label;
  int mask_resolution = 0;
  float gradient_px = 0.0f;
  bool r1_guard = false;
  double frame_ms = 0.0, cpu_ms = 0.0, ratio = 0.0, cpu_ratio = 0.0;
  Errors error;
  int passes = 0, frames = 0;
  std::string note;
};

// Targets that nothing hides under `standard`: silhouette == visible pixels.
std::vector<bool> unoccluded_targets(render::Renderer& r, const render::Camera& cam, int w, int h) {
  render::FrameSettings s;
  const auto vis = value_or_fail("bench", r.visibility(cam, s, w, h));
  std::map<std::uint32_t, bool> ok;
  for (const auto& v : vis) ok[v.id] = v.silhouette_pixels > 0 && v.visible_pixels == v.silhouette_pixels;
  std::vector<bool> out;
  for (const auto& o : r.scene().objects) out.push_back(o.target && ok[o.id]);
  return out;
}

// The configurations of one scene and size, from the technique registry: every method at the
// protocol's defaults and its own rows (technique::Technique::bench_rows: the R1 guard, lens
// shapes, screen-door mask sides); for the methods with target masks, nothing occluded and (with
// the sweep) mask resolution and gradient width.
std::vector<Config> configurations(const BenchOptions& o, render::Renderer& main, render::Renderer& quiet,
                                   const std::string& quiet_label, int w, int h) {
  render::DtSettings base;  // the protocol's defaults: aT 0.3, a0 0.1, n = 8 pixels of a 128 mask
  base.gradient_px = render::gradient_px_from_mask_pixels(8.0f, 128, w, h);
  std::vector<Config> configs;
  auto add = [&](std::string label, const technique::MethodSettings& m, render::Renderer* r, bool slow) {
    Config c;
    c.label = std::move(label);
    static_cast<technique::MethodSettings&>(c.settings) = m;
    c.settings.timed = true;
    c.renderer = r;
    if (slow) c.min_frames = 1;  // seconds a frame: one timed frame may exhaust the budget
    // A lens sized to the scene at the view's centre (as `dtlab render --method lens` sizes it).
    if (technique::of(m.method).reads(technique::Group::lens)) {
      render::LensSettings l = render::scene_lens(main.scene(), w, h);
      l.shape = m.lens.shape;
      l.style = m.lens.style;
      c.settings.lens = l;
    }
    configs.push_back(std::move(c));
  };
  for (const technique::Technique* t : technique::all()) {
    if (t->bench_slow && !o.slow) continue;
    technique::MethodSettings m;
    m.method = t->id;
    m.dt = base;
    if (t->bench_default) add(std::string(t->name), m, &main, t->bench_slow);
    if (t->bench_rows != nullptr)
      for (const technique::BenchRow& row : t->bench_rows(m)) add(row.label, row.settings, &main, t->bench_slow);
  }
  const auto swept = [](const technique::Technique& t) { return t.target_masks && t.bench_default; };
  for (const technique::Technique* t : technique::all()) {
    if (!swept(*t)) continue;
    technique::MethodSettings m;
    m.method = t->id;
    m.dt = base;
    add(std::string(t->name) + quiet_label, m, &quiet, false);
  }
  if (!o.sweep) return configs;
  for (int res : {64, 256, 0}) {
    for (const technique::Technique* t : technique::all()) {
      if (!swept(*t)) continue;
      technique::MethodSettings m;
      m.method = t->id;
      m.dt = base;
      m.dt.mask_resolution = res;
      add(std::string(t->name) + " R=" + (res == 0 ? "full" : std::to_string(res)), m, &main, false);
    }
  }
  for (float f : {0.5f, 2.0f}) {
    for (const technique::Technique* t : technique::all()) {
      if (!swept(*t)) continue;
      technique::MethodSettings m;
      m.method = t->id;
      m.dt = base;
      m.dt.gradient_px = base.gradient_px * f;
      char buf[32];
      std::snprintf(buf, sizeof buf, " n=%.0fpx", static_cast<double>(m.dt.gradient_px));
      add(std::string(t->name) + buf, m, &main, false);
    }
  }
  return configs;
}

bool same_mask(const render::DtSettings& a, const render::DtSettings& b) {
  return a.gradient_px == b.gradient_px && a.mask_resolution == b.mask_resolution && a.r1_guard == b.r1_guard;
}

// One untimed frame of each configuration: passes run, GL errors, and the image errors.
void measure_errors(std::vector<Config>& configs, const render::Renderer& main, const render::Camera& cam, int w, int h) {
  std::map<std::pair<float, bool>, render::Image> refs;  // by gradient width and guard
  std::map<float, std::vector<std::uint8_t>> regions;    // by gradient width
  for (Config& c : configs) {
    render::FrameSettings s = c.settings;
    s.timed = false;
    const render::FrameReport rep = value_or_fail("bench", c.renderer->render_offscreen(cam, s, w, h));
    c.passes = static_cast<int>(rep.passes_run().size());
    if (!rep.gl_errors.empty()) c.note = "GL error: " + rep.gl_errors.front();
    c.image = value_or_fail("bench", c.renderer->read_color());
    // Only dynamic transparency's picture (and standard's, the baseline) has `reference` for a
    // yardstick; the lens and vdt draw another picture.
    const technique::Technique& method = technique::of(c.settings.method);
    if (c.renderer != &main || !(method.target_masks || method.id == technique::Method::standard)) continue;
    const std::pair<float, bool> key{s.dt.gradient_px, s.dt.r1_guard};
    if (!refs.count(key)) {
      s.method = render::Method::reference;
      value_or_fail("bench", c.renderer->render_offscreen(cam, s, w, h));
      refs[key] = value_or_fail("bench", c.renderer->read_color());
    }
    if (!regions.count(key.first))
      regions[key.first] = value_or_fail("bench", c.renderer->effect_region(cam, s.dt, w, h));
    const auto& region = regions[key.first];
    c.error.frame = true;
    c.error.whole = value_or_fail("bench", render::compare(c.image, refs[key]));
    c.error.effect = value_or_fail("bench", render::compare_in(c.image, refs[key], region));
    if (!method.approximates) continue;  // a faster version of another method: compared with it
    for (const Config& seed : configs) {
      if (seed.renderer != c.renderer || seed.settings.method != *method.approximates ||
          !same_mask(seed.settings.dt, c.settings.dt) || seed.image.rgba.empty())
        continue;
      c.error.vs_seed = true;
      c.error.seed_effect = value_or_fail("bench", render::compare_in(c.image, seed.image, region));
    }
  }
}

// Frames [from, to) interleaved round-robin over the configurations.
void time_interleaved(const BenchOptions& o, std::vector<Config>& configs, const render::Camera& cam, int w, int h,
                      int from, int to) {
  for (int f = from; f < to; ++f) {
    for (Config& c : configs) {
      if (f >= c.min_frames && c.spent_s > o.budget_s) continue;
      const double c0 = cpu_ms();
      const render::FrameReport rep = value_or_fail("bench", c.renderer->render_offscreen(cam, c.settings, w, h));
      c.cpu.push_back(cpu_ms() - c0);
      c.wall.push_back(rep.frame_ms);
      c.spent_s += rep.frame_ms / 1000.0;
    }
    std::cerr << "." << std::flush;
  }
}

// `standard` timed alone in a fresh process (`dtlab render --frames K --json`): with the heap
// kept between frames (app/platform/malloc_tuning.h) it must cost what it costs interleaved.
std::optional<Config> standard_alone(const BenchOptions& o, const std::string& kind, const std::string& task, int w,
                                     int h) {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return std::nullopt;
  const std::filesystem::path png = std::filesystem::temp_directory_path() / ("dtlab-bench-" + std::to_string(::getpid()) + ".png");
  const std::string cmd = "'" + exe.string() + "' render --scene " + kind + " --task " + task + " --seed " +
                          std::to_string(o.seed) + " --method standard --width " + std::to_string(w) + " --height " +
                          std::to_string(h) + " --frames " + std::to_string(o.frames) + " --json --out '" +
                          png.string() + "' 2>/dev/null";
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[4096];
    while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
    if (::pclose(p) != 0) out.clear();
  }
  std::filesystem::remove(png, ec);
  const auto j = nlohmann::json::parse(out, nullptr, false);
  if (j.is_discarded() || !j.contains("frame_ms_median")) return std::nullopt;
  Config c;
  c.label = "standard alone in a process";
  c.wall = {j["frame_ms_median"].get<double>()};
  c.cpu = {j["cpu_ms_median"].get<double>()};
  c.passes = static_cast<int>(j["passes"].size());
  c.frames_alone = j["frames"].get<int>();
  return c;
}

void bench_case(const BenchOptions& o, const std::string& kind_name, int w, int h, std::vector<Row>& rows) {
  const auto kind = *scene::parse_kind(kind_name);
  const auto task = kind == scene::Kind::abstract ? scene::Task::T1 : scene::Task::T3;
  auto generated = scene::generate(kind, task, o.seed);
  if (!generated) fail("bench", kExitInvalid, generated.error().to_string());
  const scene::Scene& sc = generated.value();
  // Standard alone in a fresh process three times: before, halfway through and after the
  // interleaved frames (the median of the three), so that a change in the machine's load during
  // the run reads as noise on both sides instead of a difference between them.
  std::optional<Config> alone;
  auto time_alone = [&] {
    if (!o.alone) return;
    const std::optional<Config> run = standard_alone(o, kind_name, std::string(scene::task_name(task)), w, h);
    if (!run) return;
    if (!alone) {
      alone = run;
      return;
    }
    alone->wall.push_back(run->wall.front());
    alone->cpu.push_back(run->cpu.front());
    alone->frames_alone += run->frames_alone;
  };
  time_alone();
  auto ctx = platform::create_headless(w, h);
  if (!ctx) fail("bench", kExitFailure, ctx.error().to_string());
  auto made = render::Renderer::create(sc);
  if (!made) fail("bench", kExitFailure, made.error().to_string());
  render::Renderer& main = *made.value();
  const render::Camera cam = render::camera_from_start(sc.camera, static_cast<float>(w) / static_cast<float>(h));

  // The same scene with only the targets nothing occludes: transparency on, nothing to uncover.
  scene::Scene quiet = sc;
  const std::vector<bool> keep = unoccluded_targets(main, cam, w, h);
  int kept = 0;
  for (std::size_t i = 0; i < quiet.objects.size(); ++i) {
    quiet.objects[i].target = keep[i];
    kept += keep[i];
  }
  auto made_quiet = render::Renderer::create(quiet);
  if (!made_quiet) fail("bench", kExitFailure, made_quiet.error().to_string());
  const std::string quiet_label = kept > 0 ? " nothing occluded (" + std::to_string(kept) + " targets)" : " no targets";
  std::vector<Config> configs = configurations(o, main, *made_quiet.value(), quiet_label, w, h);

  std::cerr << "bench: " << kind_name << " " << w << "x" << h << ": reference images and errors\n";
  measure_errors(configs, main, cam, w, h);
  std::cerr << "bench: " << kind_name << " " << w << "x" << h << ": timing " << configs.size() << " configurations x "
            << o.frames << " frames\n";
  time_interleaved(o, configs, cam, w, h, 0, o.frames / 2);
  time_alone();
  time_interleaved(o, configs, cam, w, h, o.frames / 2, o.frames);
  std::cerr << "\n";
  time_alone();
  if (alone) configs.insert(configs.begin() + 1, *alone);
  const double standard_ms = median(configs.front().wall), standard_cpu = median(configs.front().cpu);
  for (const Config& c : configs) {
    Row r;
    r.scene = kind_name;
    r.width = w;
    r.height = h;
    r.method = std::string(render::to_string(c.settings.method));
    r.label = c.label;
    r.mask_resolution = c.settings.dt.mask_resolution;
    r.gradient_px = c.settings.dt.gradient_px;
    r.r1_guard = c.settings.dt.r1_guard;
    r.frame_ms = median(c.wall);
    r.cpu_ms = median(c.cpu);
    r.ratio = standard_ms > 0.0 ? r.frame_ms / standard_ms : 0.0;
    r.cpu_ratio = standard_cpu > 0.0 ? r.cpu_ms / standard_cpu : 0.0;
    r.error = c.error;
    r.passes = c.passes;
    r.frames = c.frames_alone > 0 ? c.frames_alone : static_cast<int>(c.wall.size());
    r.note = c.note;
    rows.push_back(r);
  }
}

nlohmann::ordered_json optional_number(bool has, double v) { return has ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

void print_json(const BenchOptions& o, const std::vector<Row>& rows) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const Row& r : rows) {
    nlohmann::ordered_json j{{"scene", r.scene},
                             {"width", r.width},
                             {"height", r.height},
                             {"method", r.method},
                             {"label", r.label},
                             {"mask_resolution", r.mask_resolution},
                             {"gradient_px", r.gradient_px},
                             {"r1_guard", r.r1_guard},
                             {"frame_ms_median", r.frame_ms},
                             {"cpu_ms_median", r.cpu_ms},
                             {"ratio_to_standard", r.ratio},
                             {"cpu_ratio_to_standard", r.cpu_ratio},
                             {"mae", optional_number(r.error.frame, r.error.whole.mae)},
                             {"pixels_off_pct", optional_number(r.error.frame, r.error.whole.pixels_off_pct)},
                             {"mae_effect", optional_number(r.error.frame, r.error.effect.mae)},
                             {"pixels_off_pct_effect", optional_number(r.error.frame, r.error.effect.pixels_off_pct)},
                             {"effect_pixels", optional_number(r.error.frame, static_cast<double>(r.error.effect.pixels))},
                             {"vs_dt_seed_mae_effect", optional_number(r.error.vs_seed, r.error.seed_effect.mae)},
                             {"vs_dt_seed_pixels_off_pct_effect",
                              optional_number(r.error.vs_seed, r.error.seed_effect.pixels_off_pct)},
                             {"passes", r.passes},
                             {"frames", r.frames}};
    if (!r.note.empty()) j["note"] = r.note;
    out.push_back(j);
  }
  std::cout << nlohmann::ordered_json{{"seed", o.seed}, {"rows", out}}.dump(2) << "\n";
}

void print_table(const std::vector<Row>& rows) {
  std::printf("%-11s %-9s %-38s %9s %8s %6s %6s | %6s %6s | %6s %6s | %6s %6s | %6s\n", "scene", "size", "method",
              "frame ms", "cpu ms", "ratio", "cpu", "mae", ">4 %", "mae fx", ">4 fx", "seed", ">4", "passes");
  for (const Row& r : rows) {
    char size[32], mae[16] = "-", off[16] = "-", mfx[16] = "-", ofx[16] = "-", ms[16] = "-", os[16] = "-";
    std::snprintf(size, sizeof size, "%dx%d", r.width, r.height);
    if (r.error.frame) {
      std::snprintf(mae, sizeof mae, "%.2f", r.error.whole.mae);
      std::snprintf(off, sizeof off, "%.2f", r.error.whole.pixels_off_pct);
      std::snprintf(mfx, sizeof mfx, "%.2f", r.error.effect.mae);
      std::snprintf(ofx, sizeof ofx, "%.2f", r.error.effect.pixels_off_pct);
    }
    if (r.error.vs_seed) {
      std::snprintf(ms, sizeof ms, "%.2f", r.error.seed_effect.mae);
      std::snprintf(os, sizeof os, "%.2f", r.error.seed_effect.pixels_off_pct);
    }
    std::printf("%-11s %-9s %-38s %9.2f %8.2f %6.2f %6.2f | %6s %6s | %6s %6s | %6s %6s | %6d%s%s\n", r.scene.c_str(), size,
                r.label.c_str(), r.frame_ms, r.cpu_ms, r.ratio, r.cpu_ratio, mae, off, mfx, ofx, ms, os, r.passes,
                r.note.empty() ? "" : "  ", r.note.c_str());
  }
}

void run(const BenchOptions& o) {
  if (o.culling) {  // three routes from --seed, at the first size
    CullingBenchOptions c;
    c.json = o.json;
    c.frames = std::min(o.frames, 5);
    c.seeds = {o.seed, o.seed + 1, o.seed + 2};
    c.methods = o.culling_methods;
    char x = 0;
    std::stringstream ss(o.sizes.front());
    if (!(ss >> c.width >> x >> c.height) || x != 'x' || c.width <= 0 || c.height <= 0 || c.width > 8192 || c.height > 8192)
      fail("bench", kExitUsage, "--sizes: '" + o.sizes.front() + "' is not WxH");
    bench_culling(c);
    return;
  }
  std::vector<Row> rows;
  for (const auto& kind : o.scenes) {
    for (const auto& size : o.sizes) {
      int w = 0, h = 0;
      char x = 0;
      std::stringstream ss(size);
      if (!(ss >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0 || w > 8192 || h > 8192)
        fail("bench", kExitUsage, "--sizes: '" + size + "' is not WxH");
      bench_case(o, kind, w, h, rows);
    }
  }
  o.json ? print_json(o, rows) : print_table(rows);
}

}  // namespace

void add_bench_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("bench", "Frame time and image error of every rendering method (headless)");
  auto o = std::make_shared<BenchOptions>();
  cmd->add_flag("--json", o->json,
                "Print {\"seed\", \"rows\": [{\"scene\", \"width\", \"height\", \"method\", \"label\", "
                "\"frame_ms_median\", \"ratio_to_standard\", \"mae\", \"mae_effect\", \"vs_dt_seed_mae_effect\", "
                "\"passes\", ...}]}");
  cmd->add_option("--frames", o->frames, "Timed frames per configuration (interleaved)")->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", o->seed, "Scene seed (ABSTRACT T1 and WALKTHROUGH T3)")->check(unsigned_integer());
  cmd->add_option("--sizes", o->sizes, "Viewport sizes WxH")->delimiter(',');
  cmd->add_option("--scenes", o->scenes, "Scene kinds")->delimiter(',')->check(CLI::IsMember({"abstract", "walkthrough"}));
  cmd->add_flag("!--no-sweep", o->sweep, "Skip the mask-resolution and gradient-width sweeps");
  cmd->add_flag("!--no-alone", o->alone, "Skip timing standard alone in fresh processes");
  cmd->add_flag("--culling", o->culling,
                "Instead: occlusion culling along walkthrough routes (seeds --seed, +1, +2; the first --sizes; "
                "at most 5 frames per view)");
  std::vector<std::string> cullable;  // methods culling can help (not the slow ones)
  for (const technique::Technique* t : technique::all())
    if (t->cullable && !t->bench_slow) cullable.emplace_back(t->name);
  cmd->add_option("--culling-methods", o->culling_methods, "Methods of the --culling routes")
      ->delimiter(',')
      ->check(CLI::IsMember(cullable));
  std::string slow;
  for (const technique::Technique* t : technique::all())
    if (t->bench_slow) slow += (slow.empty() ? "" : ", ") + std::string(t->name);
  cmd->add_flag("!--no-slow,!--no-screen-door", o->slow,
                "Skip the rows of the slow methods (" + slow + ": seconds a frame each on llvmpipe)");
  cmd->add_option("--budget", o->budget_s, "Seconds per configuration after which a slow one stops repeating (>= 3 frames)");
  cmd->footer(
      "frame ms: wall time of a frame from graph build to glFinish, median over frames; cpu ms: process CPU\n"
      "time of the same frames (all llvmpipe threads); ratio, cpu: frame ms and cpu ms over standard's of the\n"
      "same scene and size. \"standard alone in a process\": `dtlab render --method standard` in a fresh\n"
      "process before, halfway through and after the interleaved frames (the median of the three), compared\n"
      "with standard interleaved here (they must agree). mae, >4 %: mean absolute error per\n"
      "RGB channel in 8-bit levels against `reference` with the same aT, a0, gradient width and R1 guard, and\n"
      "the share of pixels with a channel off by more than 4, over the frame; fx: the same over the effect\n"
      "region (pixels where some target's exact mask is below 1); seed: dt-fast against dt-seed with the same\n"
      "settings in the effect region. Defaults: aT 0.3, a0 0.1, gradient 8 pixels of a 128 x 128 mask,\n"
      "outline, passive, R1 guard off (the article as printed). \"nothing occluded\": the same scene with\n"
      "only the targets nothing hides (transparency on, the effect not called for). lens rows: the lens\n"
      "method at the view's centre (sized as `dtlab render --method lens` sizes it), no error columns.\n"
      "screen-door rows: Poon's (2000) sub-pixel screen door (tabular masks) at mask sides 8, 16, 32.\n"
      "vdt: view-dependent transparency (docs/render.md), default k and weights, no error columns (its\n"
      "model makes every distractor transparent: reference's picture is not what it aims at).\n"
      "--culling: per route (the eye walking cell by cell from the start cell to the farthest one, looking\n"
      "ahead, and standing in each doorway), the speed-up of occlusion culling over frustum culling alone\n"
      "(frame ms off / on, culling's own time included) at the best, mean and worst view, and over the\n"
      "whole route; cull ms: occluder render, reduction, readback, maps and tree test; obj %, tri %: share of\n"
      "the objects and triangles in the frustum it culled; prep ms: the occluder database (once per scene).");
  cmd->callback([o] { run(*o); });
}

}  // namespace dtlab::app
