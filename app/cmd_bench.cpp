// `dtlab bench [--json] [--frames K] ...`: the renderer's cost and accuracy.
// For an ABSTRACT (200 objects) and a WALKTHROUGH scene at 800x600 and
// 1280x1024: median frame time of every method as a ratio to `standard`
// measured in the same run (frames interleaved round-robin, so machine load
// hits every method alike), image error against `reference` (mean absolute
// error in 8-bit levels, share of pixels off by more than 4/255), passes run;
// then what accuracy costs: mask resolution 64/128/256/full and gradient
// width sweeps. Table on stdout (or --json), progress on stderr.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

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
  double budget_s = 4.0;  // per configuration: stop repeating a slow one after this much time
};

[[noreturn]] void fail(int code, const std::string& message) {
  std::cerr << "dtlab bench: error: " << message << "\n";
  throw CLI::RuntimeError(code);
}

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct Config {
  std::string label;          // e.g. "dt-fast", "dt-seed R=64", "dt-fast nothing occluded"
  render::FrameSettings settings;
  render::Renderer* renderer = nullptr;
  std::vector<double> wall, cpu;
  double spent_s = 0.0;
  int passes = 0;
  bool has_error = false;
  render::ImageDiff error;
  std::string note;
};

struct Row {
  std::string scene;
  int width = 0, height = 0;
  std::string method, label;
  int mask_resolution = 0;
  float gradient_px = 0.0f;
  double frame_ms = 0.0, cpu_ms = 0.0, ratio = 0.0;
  bool has_error = false;
  render::ImageDiff error;
  int passes = 0, frames = 0;
  std::string note;
};

// Targets that nothing hides under `standard`: silhouette == visible pixels.
std::vector<bool> unoccluded_targets(render::Renderer& r, const render::Camera& cam, int w, int h) {
  render::FrameSettings s;
  const auto vis = r.visibility(cam, s, w, h);
  std::map<std::uint32_t, bool> ok;
  for (const auto& v : vis) ok[v.id] = v.silhouette_pixels > 0 && v.visible_pixels == v.silhouette_pixels;
  std::vector<bool> out;
  for (const auto& o : r.scene().objects) out.push_back(o.target && ok[o.id]);
  return out;
}

void bench_case(const BenchOptions& o, const std::string& kind_name, int w, int h, std::vector<Row>& rows) {
  const auto kind = *scene::parse_kind(kind_name);
  const auto task = kind == scene::Kind::abstract ? scene::Task::T1 : scene::Task::T3;
  auto generated = scene::generate(kind, task, o.seed);
  if (!generated) fail(kExitInvalid, generated.error().to_string());
  const scene::Scene& sc = generated.value();
  auto ctx = platform::create_headless(w, h);
  if (!ctx) fail(kExitFailure, ctx.error().to_string());
  auto made = render::Renderer::create(sc);
  if (!made) fail(kExitFailure, made.error().to_string());
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
  if (!made_quiet) fail(kExitFailure, made_quiet.error().to_string());

  render::DtSettings base;  // the protocol's defaults: aT 0.3, a0 0.1, n = 8 pixels of a 128 mask
  base.gradient_px = render::gradient_px_from_mask_pixels(8.0f, 128, w, h);
  std::vector<Config> configs;
  auto add = [&](std::string label, render::Method m, render::DtSettings dt, render::Renderer* r) {
    Config c;
    c.label = std::move(label);
    c.settings.method = m;
    c.settings.dt = dt;
    c.settings.timed = true;
    c.renderer = r;
    configs.push_back(std::move(c));
  };
  add("standard", render::Method::standard, base, &main);
  add("dt-seed", render::Method::dt_seed, base, &main);
  add("dt-fast", render::Method::dt_fast, base, &main);
  const std::string quiet_label = kept > 0 ? " nothing occluded (" + std::to_string(kept) + " targets)" : " no targets";
  add("dt-seed" + quiet_label, render::Method::dt_seed, base, made_quiet.value().get());
  add("dt-fast" + quiet_label, render::Method::dt_fast, base, made_quiet.value().get());
  if (o.sweep) {
    for (int res : {64, 256, 0}) {
      render::DtSettings dt = base;
      dt.mask_resolution = res;
      const std::string r = res == 0 ? "full" : std::to_string(res);
      add("dt-seed R=" + r, render::Method::dt_seed, dt, &main);
      add("dt-fast R=" + r, render::Method::dt_fast, dt, &main);
    }
    for (float f : {0.5f, 2.0f}) {
      render::DtSettings dt = base;
      dt.gradient_px = base.gradient_px * f;
      char buf[32];
      std::snprintf(buf, sizeof buf, "n=%.0fpx", static_cast<double>(dt.gradient_px));
      add(std::string("dt-seed ") + buf, render::Method::dt_seed, dt, &main);
      add(std::string("dt-fast ") + buf, render::Method::dt_fast, dt, &main);
    }
  }

  // Image error against the reference with the same gradient width (the mask resolution
  // does not change the reference).
  std::map<float, render::Image> refs;
  auto reference = [&](const Config& c) -> const render::Image& {
    auto it = refs.find(c.settings.dt.gradient_px);
    if (it != refs.end()) return it->second;
    render::FrameSettings s = c.settings;
    s.method = render::Method::reference;
    s.timed = false;
    c.renderer->render_offscreen(cam, s, w, h);
    return refs.emplace(c.settings.dt.gradient_px, c.renderer->read_color()).first->second;
  };
  std::cerr << "bench: " << kind_name << " " << w << "x" << h << ": reference images\n";
  for (Config& c : configs) {
    render::FrameSettings s = c.settings;
    s.timed = false;
    const render::FrameReport rep = c.renderer->render_offscreen(cam, s, w, h);
    c.passes = static_cast<int>(rep.passes_run().size());
    if (!rep.gl_errors.empty()) c.note = "GL error: " + rep.gl_errors.front();
    const render::Image img = c.renderer->read_color();
    if (c.renderer == &main) {
      c.error = render::compare(img, reference(c));
      c.has_error = true;
    }
  }
  // Timing: frames interleaved round-robin over the configurations.
  std::cerr << "bench: " << kind_name << " " << w << "x" << h << ": timing " << configs.size() << " configurations x "
            << o.frames << " frames\n";
  for (int f = 0; f < o.frames; ++f) {
    for (Config& c : configs) {
      if (f >= 3 && c.spent_s > o.budget_s) continue;
      const double c0 = cpu_ms();
      const render::FrameReport rep = c.renderer->render_offscreen(cam, c.settings, w, h);
      c.cpu.push_back(cpu_ms() - c0);
      c.wall.push_back(rep.frame_ms);
      c.spent_s += rep.frame_ms / 1000.0;
    }
    std::cerr << "." << std::flush;
  }
  std::cerr << "\n";
  const double standard_ms = median(configs.front().wall);
  for (const Config& c : configs) {
    Row r;
    r.scene = kind_name;
    r.width = w;
    r.height = h;
    r.method = std::string(render::to_string(c.settings.method));
    r.label = c.label;
    r.mask_resolution = c.settings.dt.mask_resolution;
    r.gradient_px = c.settings.dt.gradient_px;
    r.frame_ms = median(c.wall);
    r.cpu_ms = median(c.cpu);
    r.ratio = standard_ms > 0.0 ? r.frame_ms / standard_ms : 0.0;
    r.has_error = c.has_error;
    r.error = c.error;
    r.passes = c.passes;
    r.frames = static_cast<int>(c.wall.size());
    r.note = c.note;
    rows.push_back(r);
  }
}

void run(const BenchOptions& o) {
  std::vector<Row> rows;
  for (const auto& kind : o.scenes) {
    for (const auto& size : o.sizes) {
      int w = 0, h = 0;
      char x = 0;
      std::stringstream ss(size);
      if (!(ss >> w >> x >> h) || x != 'x' || w <= 0 || h <= 0 || w > 8192 || h > 8192)
        fail(kExitUsage, "--sizes: '" + size + "' is not WxH");
      bench_case(o, kind, w, h, rows);
    }
  }
  if (o.json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const Row& r : rows) {
      nlohmann::ordered_json j{{"scene", r.scene},
                               {"width", r.width},
                               {"height", r.height},
                               {"method", r.method},
                               {"label", r.label},
                               {"mask_resolution", r.mask_resolution},
                               {"gradient_px", r.gradient_px},
                               {"frame_ms_median", r.frame_ms},
                               {"cpu_ms_median", r.cpu_ms},
                               {"ratio_to_standard", r.ratio},
                               {"mae", r.has_error ? nlohmann::ordered_json(r.error.mae) : nlohmann::ordered_json()},
                               {"pixels_off_pct",
                                r.has_error ? nlohmann::ordered_json(r.error.pixels_off_pct) : nlohmann::ordered_json()},
                               {"passes", r.passes},
                               {"frames", r.frames}};
      if (!r.note.empty()) j["note"] = r.note;
      out.push_back(j);
    }
    std::cout << nlohmann::ordered_json{{"seed", o.seed}, {"rows", out}}.dump(2) << "\n";
    return;
  }
  std::printf("%-11s %-9s %-40s %9s %9s %7s %7s %8s %6s\n", "scene", "size", "method", "frame ms", "cpu ms", "ratio",
              "mae", ">4/255 %", "passes");
  for (const Row& r : rows) {
    char size[32], mae[16] = "-", off[16] = "-";
    std::snprintf(size, sizeof size, "%dx%d", r.width, r.height);
    if (r.has_error) {
      std::snprintf(mae, sizeof mae, "%.2f", r.error.mae);
      std::snprintf(off, sizeof off, "%.2f", r.error.pixels_off_pct);
    }
    std::printf("%-11s %-9s %-40s %9.2f %9.2f %7.2f %7s %8s %6d%s%s\n", r.scene.c_str(), size, r.label.c_str(), r.frame_ms,
                r.cpu_ms, r.ratio, mae, off, r.passes, r.note.empty() ? "" : "  ", r.note.c_str());
  }
}

}  // namespace

void add_bench_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("bench", "Frame time and image error of every rendering method (headless)");
  auto o = std::make_shared<BenchOptions>();
  cmd->add_flag("--json", o->json,
                "Print {\"seed\", \"rows\": [{\"scene\", \"width\", \"height\", \"method\", \"label\", "
                "\"frame_ms_median\", \"ratio_to_standard\", \"mae\", \"pixels_off_pct\", \"passes\", ...}]}");
  cmd->add_option("--frames", o->frames, "Timed frames per configuration (interleaved)")->check(CLI::Range(1, 1000));
  cmd->add_option("--seed", o->seed, "Scene seed (ABSTRACT T1 and WALKTHROUGH T3)");
  cmd->add_option("--sizes", o->sizes, "Viewport sizes WxH")->delimiter(',');
  cmd->add_option("--scenes", o->scenes, "Scene kinds")->delimiter(',')->check(CLI::IsMember({"abstract", "walkthrough"}));
  cmd->add_flag("!--no-sweep", o->sweep, "Skip the mask-resolution and gradient-width sweeps");
  cmd->add_option("--budget", o->budget_s, "Seconds per configuration after which a slow one stops repeating (>= 3 frames)");
  cmd->footer(
      "frame ms: wall time of a frame from graph build to glFinish, median over frames; cpu ms: process CPU\n"
      "time of the same frames (all llvmpipe threads); ratio: frame ms / standard's frame ms of the same\n"
      "scene and size. mae: mean absolute error per RGB channel in 8-bit levels against `reference` with the\n"
      "same aT, a0 and gradient width; >4/255 %: share of pixels with a channel off by more than 4.\n"
      "Defaults: aT 0.3, a0 0.1, gradient 8 pixels of a 128 x 128 mask, outline, passive. \"nothing occluded\":\n"
      "the same scene with only the targets nothing hides (transparency on, the effect not called for).");
  cmd->callback([o] { run(*o); });
}

}  // namespace dtlab::app
