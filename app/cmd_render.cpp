// `dtlab render (--scene KIND --task T --seed S --method M | --protocol P
// (--index K | --db FILE --participant ID) --trial N) --out FILE.png
// [--width W --height H] [--frames K] [--camera ...] [--lens-...] [--screen-door-...] [--vdt-...] [--occlusion-culling]
// [--json]`: renders one
// trial scene headless (OSMesa) with one rendering method and writes the PNG;
// --json prints the passes that ran, the median frame time, per-target
// visible pixel counts and GL errors. The protocol form renders the trial at
// position N (1-based, as `dtlab plan`) of the participant's plan
// (design::make_plan) exactly as a session would: the
// plan's seed, the task's scene parameters and the condition's [rendering]
// table (session/mapping.h); it never takes a method or mask parameter from
// the command line. Exit 1 bad scene/protocol/database input, 2 bad command
// line, 3 no GL context, database failure or PNG not written.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "app/database_arg.h"
#include "app/technique_options.h"
#include "app/platform/gl_context.h"
#include "study/design/design.h"
#include "study/protocol/protocol.h"
#include "study/render/render.h"
#include "study/scene/generate.h"
#include "study/session/mapping.h"
#include "study/store/read.h"

namespace dtlab::app {

namespace {

// --frames K > 1: untimed frames rendered first (see the loop in run()).
constexpr auto kWarmup = std::chrono::milliseconds(500);
constexpr int kMaxWarmupFrames = 200;

struct RenderOptions {
  std::string kind, task;
  std::uint64_t seed = 0;
  // Protocol form: trial `trial` (1-based position, as `dtlab plan`) of enrollment index `index`, or
  // of `participant` in `db`.
  std::string protocol, db, participant;
  std::optional<int> index;
  std::optional<int> trial;
  std::string method = "standard";
  std::string out;
  int width = 800, height = 600, frames = 1;
  std::string camera;
  bool json = false;
  // Dynamic transparency parameters (render.h DtSettings).
  float alpha_target = 0.3f, alpha_start = 0.1f, gradient = 8.0f;
  std::optional<float> gradient_px;
  int mask_res = 128, layer_limit = 0;
  std::string shape = "outline", searchlight, graphviz;
  bool r1_guard = true;  // as a session renders (protocol r1_guard); --no-r1-guard: the article as printed
  bool profile = false;
  bool occlusion_culling = false;
  // Lens parameters (render.h LensSettings); sizes in world units, unset: from the scene.
  std::string lens_shape = "sphere", lens_style = "eraser", lens_at;
  std::optional<float> lens_radius, lens_distance, lens_length;
  // Every other method's options, from the technique registry (technique_options.h).
  TechniqueOptions technique;
};

// "yaw=30,pitch=-10,distance=150,x=1,y=2,z=3,fov=60" (degrees) over the scene's start camera.
// Each key at most once; every value a finite number in the range where the view shows the
// scene: yaw -360..360, pitch -90..90, fov 1..170 degrees; distance (orbit cameras) between the
// near and far planes; x, y, z (walk cameras) within the far plane's reach of the scene's box.
scene::CameraStart apply_camera(scene::CameraStart c, const std::string& spec, const scene::Scene& sc) {
  const bool orbit = c.mode == scene::CameraStart::Mode::orbit;
  std::vector<std::string> seen;
  std::size_t begin = 0;
  while (!spec.empty() && begin <= spec.size()) {
    const std::size_t comma = spec.find(',', begin);
    const std::string item = spec.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    begin = comma == std::string::npos ? spec.size() + 1 : comma + 1;
    if (item.empty()) fail("render", kExitUsage, "--camera: empty item in '" + spec + "' (a doubled or trailing comma?)");
    const auto eq = item.find('=');
    if (eq == std::string::npos) fail("render", kExitUsage, "--camera: '" + item + "' is not key=value");
    const std::string key = item.substr(0, eq);
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      fail("render", kExitUsage, "--camera: '" + key + "' given twice");
    seen.push_back(key);
    float v = 0.0f;
    try {
      std::size_t used = 0;
      v = std::stof(item.substr(eq + 1), &used);
      if (used != item.size() - eq - 1 || !std::isfinite(v)) throw std::invalid_argument(key);
    } catch (const std::exception&) {
      fail("render", kExitUsage, "--camera: value of '" + key + "' is not a finite number");
    }
    auto in_range = [&](float lo, float hi, const std::string& unit) {
      if (!(v >= lo && v <= hi)) {
        std::ostringstream m;
        m << "--camera: " << key << " must be " << lo << ".." << hi << unit << ", got " << v;
        fail("render", kExitUsage, m.str());
      }
    };
    const float rad = v * 3.14159265358979f / 180.0f;
    const glm::vec3 reach = sc.bounds_max - sc.bounds_min + glm::vec3(c.far_plane);
    if (key == "yaw") {
      in_range(-360.0f, 360.0f, " degrees");
      c.yaw = rad;
    } else if (key == "pitch") {
      in_range(-90.0f, 90.0f, " degrees");
      c.pitch = rad;
    } else if (key == "fov") {
      in_range(1.0f, 170.0f, " degrees");
      c.fov_y = rad;
    } else if (key == "distance" || key == "x" || key == "y" || key == "z") {
      if (orbit != (key == "distance"))
        fail("render", kExitUsage, "--camera: '" + key + "' applies to " + (orbit ? "walk cameras (WALKTHROUGH)" : "orbit cameras (ABSTRACT)") +
                             "; this scene's camera " + (orbit ? "orbits: use yaw, pitch, fov, distance" :
                                                                  "walks: use yaw, pitch, fov, x, y, z"));
      if (key == "distance") {
        in_range(c.near_plane * 2.0f, c.far_plane * 0.5f, " (scene units, between the near and far planes)");
        c.distance = v;
      } else {
        const int axis = key == "x" ? 0 : key == "y" ? 1 : 2;
        in_range(sc.bounds_min[axis] - reach[axis], sc.bounds_max[axis] + reach[axis],
                 " (scene units, within sight of the scene)");
        c.position[axis] = v;
      }
    } else {
      fail("render", kExitUsage, "--camera: unknown key '" + key + "' (yaw, pitch, fov, " +
                           (orbit ? "distance" : "x, y, z") + ")");
    }
  }
  return c;
}

render::DtSettings dt_settings(const RenderOptions& o) {
  render::DtSettings dt;
  dt.alpha_target = o.alpha_target;
  dt.alpha_start = o.alpha_start;
  dt.mask_resolution = o.mask_res;
  dt.gradient_px = o.gradient_px ? *o.gradient_px
                                 : render::gradient_px_from_mask_pixels(o.gradient, o.mask_res, o.width, o.height);
  dt.shape = *render::parse_mask_shape(o.shape);
  dt.layer_limit = o.layer_limit;
  dt.r1_guard = o.r1_guard;
  if (!o.searchlight.empty()) {
    float x = 0, y = 0, r = 0;
    char c1 = 0, c2 = 0;
    std::stringstream ss(o.searchlight);
    if (!(ss >> x >> c1 >> y >> c2 >> r) || c1 != ',' || c2 != ',' || !(ss >> std::ws).eof() || !(r >= 0.0f) ||
        !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(r))
      fail("render", kExitUsage, "--searchlight: expected X,Y,R in pixels (origin top-left, R >= 0), got '" + o.searchlight + "'");
    dt.mode = render::DtMode::active;
    dt.searchlight_center = {x, y};
    dt.searchlight_radius = r;
  }
  // The renderer's checks (ranges; a mask no finer than the image can use), named by the option.
  if (const auto problem = render::check(dt, o.width, o.height)) {
    const char* option = "";
    switch (problem->field) {
      case render::DtField::alpha_target: option = "--alpha-target"; break;
      case render::DtField::alpha_start: option = "--alpha-start"; break;
      case render::DtField::gradient: option = o.gradient_px ? "--gradient-px" : "--gradient"; break;
      case render::DtField::mask_resolution: option = "--mask-res"; break;
      case render::DtField::layer_limit: option = "--layer-limit"; break;
      case render::DtField::searchlight: option = "--searchlight"; break;
    }
    std::string message = problem->message;
    if (problem->field == render::DtField::gradient && !o.gradient_px)
      message += " (--gradient is in mask pixels: " + std::to_string(o.gradient) + " of a " + std::to_string(o.mask_res) +
                 " mask over " + std::to_string(o.width) + " x " + std::to_string(o.height) + ")";
    fail("render", kExitUsage, std::string(option) + ": " + message);
  }
  return dt;
}

// The lens of the scene form: unset sizes from render::scene_lens.
render::LensSettings lens_settings(const RenderOptions& o, const scene::Scene& sc) {
  render::LensSettings l = render::scene_lens(sc, o.width, o.height);
  l.shape = *render::parse_lens_shape(o.lens_shape);
  l.style = *render::parse_lens_style(o.lens_style);
  if (!o.lens_at.empty()) {
    float x = 0, y = 0;
    char comma = 0;
    std::stringstream ss(o.lens_at);
    if (!(ss >> x >> comma >> y) || comma != ',' || !(ss >> std::ws).eof() || !std::isfinite(x) || !std::isfinite(y))
      fail("render", kExitUsage, "--lens-at: expected X,Y in pixels (origin top-left), got '" + o.lens_at + "'");
    l.center = {x, y};
  }
  l.distance = o.lens_distance.value_or(l.distance);
  l.radius = o.lens_radius.value_or(l.radius);
  l.length = o.lens_length.value_or(2.0f * l.radius);
  if (const auto problem = render::check(l)) fail("render", kExitUsage, "--lens-" + *problem);
  return l;
}

// What to render: the scene, the method's settings and the start camera, from either form.
struct Job {
  scene::Scene scene;
  render::FrameSettings settings;
  std::string method, kind, task;
  std::uint64_t seed = 0;
  nlohmann::ordered_json trial;  // protocol form: where the trial comes from (JSON output)
};

[[noreturn]] void fail_diagnostic(int code, const Error& e) {
  std::cerr << Diagnostic{Severity::error, e}.to_string() << "\n";
  throw CLI::RuntimeError(code);
}

// Protocol form: trial o.trial of the participant's plan, rendered as a session would.
Job protocol_job(const RenderOptions& o) {
  const auto p = protocol::load_protocol(o.protocol);
  if (!p.ok()) {
    std::cerr << Diagnostic{Severity::error, p.error()}.to_string() << "\n"
              << "(run `dtlab validate " << o.protocol << "` for every problem)\n";
    throw CLI::RuntimeError(kExitInvalid);
  }
  int index = o.index.value_or(0);
  design::Plan plan;
  if (!o.db.empty()) {
    auto reader = store::StudyReader::open(o.db, session::read_options());
    auto planned = reader ? session::ledger_plan(*reader, *p, o.participant) : Result<design::Plan>(reader.error());
    if (!planned.ok()) fail_diagnostic(exit_code(planned.error()), planned.error());
    plan = std::move(planned.value());
    index = plan.index;
  } else {
    plan = design::make_plan(*p, index);
  }
  const int n = *o.trial;  // 1-based, as `dtlab plan` numbers positions
  if (n < 1 || static_cast<std::size_t>(n) > plan.trials.size())
    fail("render", kExitUsage, "--trial " + std::to_string(n) + ": participant " + std::to_string(index) + "'s plan has " +
                         std::to_string(plan.trials.size()) + " trials, positions 1.." +
                         std::to_string(plan.trials.size()) + " (as `dtlab plan` numbers them)");
  const design::PlannedTrial& t = plan.trials[static_cast<std::size_t>(n - 1)];
  const auto setup = session::trial_setup(*p, t);
  if (!setup.ok()) fail_diagnostic(kExitInvalid, setup.error());
  auto sc = session::trial_scene(setup.value(), t);
  if (!sc.ok()) fail_diagnostic(kExitInvalid, sc.error());
  auto fs = session::frame_settings(*p, *setup->rendering, o.width, o.height);
  if (!fs.ok()) fail_diagnostic(kExitInvalid, fs.error());
  Job job;
  job.scene = std::move(sc.value());
  job.settings = std::move(fs.value());
  job.method = std::string(render::to_string(job.settings.method));
  job.kind = std::string(scene::kind_name(setup->kind));
  job.task = std::string(scene::task_name(setup->scene_task));
  job.seed = t.seed;
  nlohmann::ordered_json levels = nlohmann::ordered_json::object();
  for (const auto& [factor, level] : t.levels) levels[factor] = level;
  job.trial = {{"protocol", plan.protocol_id},
               {"index", plan.index},
               {"order_row", plan.order_row},
               {"trial", n},
               {"position", t.position},
               {"levels", levels},
               {"task_id", t.task},
               {"rendering", setup->rendering->name},
               {"practice", t.practice}};
  if (!o.participant.empty()) job.trial["participant"] = o.participant;
  return job;
}

// Scene form: the generator's default parameters, the method and parameters from the command line.
Job scene_job(const RenderOptions& o) {
  const auto kind = *scene::parse_kind(o.kind);
  const auto task = *scene::parse_task(o.task);
  auto generated = scene::generate(kind, task, o.seed);
  if (!generated) fail("render", kExitInvalid, generated.error().to_string());
  Job job;
  job.scene = std::move(generated.value());
  const technique::Technique& method = *technique::find(o.method);
  job.settings.method = method.id;
  job.settings.dt = dt_settings(o);
  if (method.reads(technique::Group::lens)) job.settings.lens = lens_settings(o, job.scene);
  o.technique.apply(method, o.width, o.height, job.settings);
  job.method = o.method;
  job.kind = o.kind;
  job.task = o.task;
  job.seed = o.seed;
  return job;
}

void run(const RenderOptions& o) {
  Job job = o.protocol.empty() ? scene_job(o) : protocol_job(o);
  const scene::Scene& sc = job.scene;
  render::FrameSettings& settings = job.settings;
  settings.timed = true;
  settings.profile_passes = o.profile;
  settings.occlusion_culling = settings.occlusion_culling || o.occlusion_culling;
  if (o.occlusion_culling && !sc.plan) fail("render", kExitUsage, "--occlusion-culling applies to walkthrough scenes only");
  const scene::CameraStart start = apply_camera(sc.camera, o.camera, sc);
  const render::Camera camera =
      render::camera_from_start(start, static_cast<float>(o.width) / static_cast<float>(o.height));

  auto ctx = platform::create_headless(o.width, o.height);
  if (!ctx) fail("render", kExitFailure, ctx.error().to_string());
  auto renderer = render::Renderer::create(sc);
  if (!renderer) fail("render", kExitFailure, renderer.error().to_string());
  render::Renderer& r = *renderer.value();

  std::vector<double> times, cpu_times;
  render::FrameReport report;
  std::vector<std::string> gl_errors;
  double preprocess_ms = 0.0;  // occlusion culling's occluder database, built by the first frame
  std::map<std::string, std::vector<double>> pass_ms;  // --profile: each pass's time in every frame that ran it
  // With more than one frame, untimed frames first, for half a second: a fresh process's llvmpipe
  // threads reach their steady state only after a few hundred milliseconds (before, the scheduler
  // often runs a frame's rasterizer threads one after the other: wall time = CPU time), so without
  // this a short run timed the warm-up, not the method (docs/performance.md).
  // One frame into `report`, its GL errors and preprocessing kept (warm-up frames included).
  auto render_frame = [&] {
    auto drawn = r.render_offscreen(camera, settings, o.width, o.height);
    if (!drawn) fail("render", drawn.error());
    report = std::move(drawn.value());
    gl_errors.insert(gl_errors.end(), report.gl_errors.begin(), report.gl_errors.end());
    preprocess_ms += report.culling.preprocess_ms;
  };
  if (o.frames > 1) {
    const auto w0 = std::chrono::steady_clock::now();
    for (int f = 0; f < kMaxWarmupFrames && std::chrono::steady_clock::now() - w0 < kWarmup; ++f) render_frame();
  }
  for (int f = 0; f < o.frames; ++f) {
    timespec c0{}, c1{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    render_frame();
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    times.push_back(report.frame_ms);
    cpu_times.push_back(static_cast<double>(c1.tv_sec - c0.tv_sec) * 1e3 + static_cast<double>(c1.tv_nsec - c0.tv_nsec) * 1e-6);
    for (const auto& p : report.passes)
      if (!p.culled && p.ran.value_or(true)) pass_ms[p.name].push_back(p.ms);
  }
  auto median_of = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 == 1 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  const double median = median_of(times), cpu_median = median_of(cpu_times);
  const auto image = r.read_color();
  if (!image) fail("render", image.error());
  if (Status st = render::write_png(image.value(), o.out); !st) fail("render", kExitFailure, st.error().to_string());
  if (!o.graphviz.empty()) {
    std::ofstream dot(o.graphviz);
    dot << r.last_graphviz();
    if (!dot) fail("render", kExitFailure, o.graphviz + ": cannot write the Graphviz file");
  }
  const std::vector<std::string> passes = report.passes_run();
  if (!o.json) {
    std::cout << "wrote " << o.out << " (" << o.width << "x" << o.height << ", " << job.method << ", " << job.kind
              << " " << job.task << " seed " << job.seed << ")\n"
              << "passes  ";
    for (std::size_t i = 0; i < passes.size(); ++i) std::cout << (i ? ", " : "") << passes[i];
    std::cout << "\nframe   " << median << " ms (median of " << o.frames << "; CPU time of all threads " << cpu_median
              << " ms)\n";
    if (o.profile)
      for (const auto& p : report.passes)
        if (!p.culled && p.ran.value_or(true))
          std::cout << "  " << median_of(pass_ms[p.name]) << " ms  " << p.name << " (median of " << pass_ms[p.name].size()
                    << " frames; " << p.draws << " mesh draws, " << p.triangles << " triangles)\n";
    if (const auto& c = report.culling; c.ran)
      std::cout << "culling " << c.objects_culled << " of " << c.objects_in_view << " objects in view ("
                << c.triangles_culled << " of " << c.triangles_in_view << " triangles) behind " << c.occluders
                << " occluders, " << c.ms << " ms (readback " << c.readback_ms << " ms); occluder database "
                << preprocess_ms << " ms\n";
    for (const auto& e : gl_errors) std::cout << "GL error: " << e << "\n";
    return;
  }
  settings.timed = false;
  const auto vis = r.visibility(camera, settings, o.width, o.height);
  if (!vis) fail("render", vis.error());
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const auto& v : vis.value())
    targets.push_back({{"id", v.id},
                       {"visible_pixels", v.visible_pixels},
                       {"silhouette_pixels", v.silhouette_pixels},
                       {"in_view", v.silhouette_pixels > 0}});
  nlohmann::ordered_json j{{"method", job.method},
                           {"scene", job.kind},
                           {"task", job.task},
                           {"seed", job.seed},
                           {"scene_hash", sc.hash},
                           {"width", o.width},
                           {"height", o.height},
                           {"passes", passes},
                           {"frame_ms_median", median},
                           {"cpu_ms_median", cpu_median},
                           {"frames", o.frames},
                           {"targets", targets},
                           {"gl_errors", gl_errors},
                           {"out", o.out}};
  if (!job.trial.is_null()) j["trial"] = job.trial;
  if (const auto& c = report.culling; c.ran)
    j["culling"] = {{"occluders", c.occluders},           {"objects_in_view", c.objects_in_view},
                    {"objects_culled", c.objects_culled}, {"triangles_in_view", c.triangles_in_view},
                    {"triangles_culled", c.triangles_culled}, {"ms", c.ms},
                    {"readback_ms", c.readback_ms}, {"preprocess_ms", preprocess_ms}};
  std::cout << j.dump(2) << "\n";
}

}  // namespace

CLI::Validator unsigned_integer() {
  return CLI::Validator(
      [](std::string& v) -> std::string {
        const bool digits = !v.empty() && v.size() <= 20 && v.find_first_not_of("0123456789") == std::string::npos;
        if (digits && (v.size() < 20 || v <= "18446744073709551615")) return {};
        return "'" + v + "' is not an unsigned 64-bit integer (0..18446744073709551615, no sign)";
      },
      "UINT64");
}

void add_render_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("render", "Render one trial scene headless with one method; write a PNG");
  auto o = std::make_shared<RenderOptions>();
  auto* scene_opt = cmd->add_option("--scene", o->kind, "Scene kind: abstract (tasks T1, T2) or walkthrough (T3, T4)")
                        ->check(CLI::IsMember({"abstract", "walkthrough"}));
  auto* task_opt = cmd->add_option("--task", o->task, "Task: T1, T2 (abstract), T3, T4 (walkthrough)")
                       ->check(CLI::IsMember({"T1", "T2", "T3", "T4"}));
  auto* seed_opt = cmd->add_option("--seed", o->seed, "Trial seed (unsigned 64-bit)")->check(unsigned_integer());
  std::vector<std::string> methods;
  for (const technique::Technique* t : technique::all()) methods.emplace_back(t->name);
  auto* method_opt = cmd->add_option("--method", o->method, "Rendering method: " + technique::names(" | "))
                         ->check(CLI::IsMember(methods));
  auto* protocol_opt = cmd->add_option("--protocol", o->protocol,
                                       "Protocol file: render a planned trial (with --index K or --db/--participant, "
                                       "and --trial N)");
  auto* index_opt = cmd->add_option("--index", o->index, "0-based enrollment index K (order row K mod rows)")
                        ->check(CLI::NonNegativeNumber);
  auto* db_opt = cmd->add_option("--db", o->db, std::string(kDatabaseHelp) + ": K and the order row from its participant ledger")
                     ->check(existing_database());
  auto* participant_opt = cmd->add_option("--participant", o->participant, "Participant id enrolled in --db")
      ->check(participant_id());
  auto* trial_opt = cmd->add_option("--trial", o->trial,
                                    "Position N in the participant's plan, 1-based as `dtlab plan` numbers it");
  cmd->add_option("--out", o->out, "PNG file to write")->required();
  cmd->add_option("--width", o->width, "Image width in pixels")->check(CLI::Range(1, 8192));
  cmd->add_option("--height", o->height, "Image height in pixels")->check(CLI::Range(1, 8192));
  cmd->add_option("--frames", o->frames, "Frames to time (with more than one, half a second of untimed frames first); the median frame time is reported")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--camera", o->camera,
                  "Override the start camera: key=value list, keys yaw, pitch, fov (degrees), distance (orbit), "
                  "x, y, z (walk position), e.g. yaw=40,pitch=-20");
  auto* alpha_target_opt = cmd->add_option("--alpha-target", o->alpha_target, "aT: weight of surfaces in front of a target, [0, 1)");
  auto* alpha_start_opt = cmd->add_option("--alpha-start", o->alpha_start, "a0: weight where the gradient starts, [0, 1)");
  auto* gradient_opt = cmd->add_option("--gradient", o->gradient,
                  "n: gradient width in mask pixels of the --mask-res mask (the article's unit; protocol "
                  "gradient_width)");
  auto* gradient_px_opt = cmd->add_option("--gradient-px", o->gradient_px, "n in output pixels (overrides --gradient)");
  auto* mask_res_opt = cmd->add_option("--mask-res", o->mask_res, "Mask buffer side R (R x R, the article's 128); 0 = full resolution")
      ->check(CLI::Range(0, 8192));
  auto* shape_opt = cmd->add_option("--shape", o->shape, "Mask shape: outline | circle | ellipse")
      ->check(CLI::IsMember({"outline", "circle", "ellipse"}));
  auto* searchlight_opt = cmd->add_option("--searchlight", o->searchlight,
                  "Active mode: X,Y,R in pixels (origin top-left); without it, passive mode (whole view)");
  auto* layer_limit_opt = cmd->add_option("--layer-limit", o->layer_limit, "At most this many transparent surfaces in front of a target "
                                                   "(0 = no limit)")
      ->check(CLI::Range(0, 100));
  auto* guard_opt = cmd->add_flag("--r1-guard,!--no-r1-guard", o->r1_guard,
                                  "R1 guard (docs/render.md), on by default as in a session (protocol r1_guard): targets "
                                  "never blended below aT, sort errors repaired; --no-r1-guard: the article's algorithm "
                                  "as printed");
  auto* lens_shape_opt = cmd->add_option("--lens-shape", o->lens_shape, "Lens volume: sphere | box | cylinder | cone")
                            ->check(CLI::IsMember({"sphere", "box", "cylinder", "cone"}));
  auto* lens_style_opt = cmd->add_option("--lens-style", o->lens_style, "What the lens does inside: eraser (distractors vanish) | wireframe | tint")
                            ->check(CLI::IsMember({"eraser", "wireframe", "tint"}));
  auto* lens_radius_opt = cmd->add_option("--lens-radius", o->lens_radius, "Lens radius (box: half side), world units");
  auto* lens_distance_opt =
      cmd->add_option("--lens-distance", o->lens_distance, "Eye to lens centre along the ray through --lens-at, world units");
  auto* lens_length_opt =
      cmd->add_option("--lens-length", o->lens_length, "Box, cylinder, cone: extent along the ray, world units");
  auto* lens_at_opt = cmd->add_option("--lens-at", o->lens_at, "Lens centre pixel X,Y (origin top-left; default the view's centre)");
  cmd->add_flag("--occlusion-culling", o->occlusion_culling,
                "Walkthrough: skip objects hidden behind the walls (Poon's occlusion culling; the picture is "
                "unchanged, only the cost)");
  o->technique.add_to(*cmd);
  cmd->add_option("--graphviz", o->graphviz, "Write the last frame's frame graph (dot) to FILE");
  cmd->add_flag("--profile", o->profile, "glFinish after every pass; print each pass's median CPU time (all threads) over the frames that ran it, and the scene-mesh draw calls and triangles it submitted");
  cmd->add_flag("--json", o->json,
                "Print {\"method\", \"passes\", \"frame_ms_median\", \"targets\": [{\"id\", \"visible_pixels\", "
                "\"silhouette_pixels\", \"in_view\"}], \"gl_errors\", ...} as JSON");
  cmd->footer(
      "Two forms: --scene KIND --task T --seed S --method M [mask options] renders a generated scene;\n"
      "--protocol P (--index K | --db FILE --participant ID) --trial N renders the trial at position N of that\n"
      "participant's plan (1-based, the position `dtlab plan` lists) as a session would: the plan's seed, the\n"
      "task's scene parameters, the method and mask parameters of the condition's [rendering] table. The\n"
      "forms do not mix. --seed is an unsigned 64-bit integer (no sign). --camera keys: yaw -360..360,\n"
      "pitch -90..90, fov 1..170 (degrees); distance (orbit cameras) between the scene's near and far\n"
      "planes; x, y, z (walk cameras) within sight of the scene; each key once. --mask-res: at most the\n"
      "image's longer side (or 128). --alpha-target, --alpha-start: at least 0 and below 1.\n"
      "--method lens (Ropinski & Hinrichs 2004, docs/render.md): a convex lens volume centred on the view\n"
      "ray through --lens-at at --lens-distance from the eye; the scene is drawn behind, inside (in the\n"
      "lens style) and in front of it. eraser removes the distractors inside it, wireframe draws it as\n"
      "lines, tint mixes it with orange. Defaults: distance = the orbit distance (abstract) or two cells\n"
      "(walkthrough), radius = a quarter of the view's half-height there, length = 2 x radius.\n"
      "--method vdt (Diepstraten, Weiskopf & Ertl 2002, docs/render.md): distractors transparent, targets\n"
      "and impenetrable surfaces opaque; only the nearest transparent surface is blended, over the opaque\n"
      "surface behind it unless a second transparent surface lies between; its alpha falls off from 1 at\n"
      "the object's silhouette with the distance to it (--vdt-falloff).\n"
      "--occlusion-culling (walkthrough scenes, either form): Poon's occlusion culling; the JSON gains\n"
      "\"culling\" (objects and triangles culled, its time, the occluder database's time). The image is the\n"
      "same with it on or off.\n"
      "--method screen-door (Poon 2000, docs/render.md): dt-seed's picture by sub-pixel screen-door\n"
      "transparency: each surface's alpha picks an s x s mask (--screen-door-mask, default 8) made by\n"
      "--screen-door-masks (tabular with neighbourhood compensation, default); the targets' regions are\n"
      "drawn s times enlarged and box-filtered. Slow at 32 (1024 sub-pixels a pixel).\n"
      "Visible pixels (docs/render.md): pixels where the target's own surface makes up at least 10% of\n"
      "the final colour as the method composited it, counted with the method's own passes (weight\n"
      "frames: the target flat white, everything else black). silhouette_pixels: pixels the target\n"
      "covers with every other object ignored; in_view: silhouette_pixels > 0.\n"
      "Exit status: 0 ok, 1 bad scene input, 2 bad command line, 3 no GL context or file not written.");
  const std::vector<CLI::Option*> scene_form{scene_opt, task_opt, seed_opt, method_opt};
  const std::vector<CLI::Option*> dt_options{alpha_target_opt, alpha_start_opt, gradient_opt, gradient_px_opt,
                                             mask_res_opt,     shape_opt,       searchlight_opt, layer_limit_opt,
                                             guard_opt};
  const std::vector<CLI::Option*> lens_options{lens_shape_opt,  lens_style_opt, lens_radius_opt,
                                               lens_distance_opt, lens_length_opt, lens_at_opt};
  const std::vector<CLI::Option*> protocol_form{protocol_opt, index_opt, db_opt, participant_opt, trial_opt};
  cmd->callback([o, scene_form, dt_options, lens_options, protocol_form, protocol_opt, index_opt,
                 db_opt, participant_opt, trial_opt] {
    const auto given = [](const std::vector<CLI::Option*>& opts) {
      std::string names;
      for (const CLI::Option* opt : opts)
        if (opt->count() > 0) names += (names.empty() ? "" : ", ") + opt->get_name();
      return names;
    };
    if (protocol_opt->count() > 0) {
      if (const std::string bad = given(scene_form) + given(dt_options) + given(lens_options) + o->technique.given();
          !bad.empty())
        fail("render", kExitUsage, "--protocol renders a planned trial: its scene, seed, method and mask parameters come from "
                         "the protocol; drop " + bad);
      if ((index_opt->count() > 0) == (db_opt->count() > 0 || participant_opt->count() > 0) ||
          (db_opt->count() > 0) != (participant_opt->count() > 0))
        fail("render", kExitUsage, "--protocol needs either --index K or --db FILE --participant ID");
      if (trial_opt->count() == 0) fail("render", kExitUsage, "--protocol needs --trial N (1-based position in the plan)");
    } else {
      if (const std::string bad = given(protocol_form); !bad.empty())
        fail("render", kExitUsage, bad + " belong(s) to the protocol form: give --protocol P too");
      for (const CLI::Option* opt : scene_form)
        if (opt->count() == 0)
          fail("render", kExitUsage, "give --scene KIND --task T --seed S --method M, or --protocol P --index K --trial N "
                           "(missing " + opt->get_name() + ")");
      if (const std::string bad = given(lens_options);
          !bad.empty() && !technique::find(o->method)->reads(technique::Group::lens))
        fail("render", kExitUsage, bad + " apply to --method lens only");
      if (const std::string bad = o->technique.misplaced(*technique::find(o->method)); !bad.empty())
        fail("render", kExitUsage, bad);
    }
    run(*o);
  });
}

}  // namespace dtlab::app
