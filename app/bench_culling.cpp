// Occlusion culling along walkthrough routes (see bench_culling.h).
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <numeric>

#include "app/bench_culling.h"
#include "app/commands.h"
#include "app/platform/gl_context.h"
#include "study/render/render.h"
#include "study/scene/generate.h"
#include "study/scene/route.h"

namespace dtlab::app {

namespace {

struct RouteRow {
  std::uint64_t seed = 0;
  std::string method;
  int views = 0;
  double best = 0.0, mean = 0.0, worst = 0.0;  // speed-up: frame ms off / on, per view
  double total = 0.0;                          // summed frame ms off / on over the route
  double off_ms = 0.0, on_ms = 0.0;            // mean per view of the median frame
  double culling_ms = 0.0, readback_ms = 0.0;  // mean per view (median frame's report)
  double objects_pct = 0.0, triangles_pct = 0.0;  // culled, of those in the frustum, over the route
  double preprocess_ms = 0.0;
  int occluders = 0;  // mean per view
};

RouteRow run_route(const CullingBenchOptions& o, std::uint64_t seed, const std::string& method) {
  auto generated = scene::generate(scene::Kind::walkthrough, scene::Task::T3, seed);
  if (!generated) fail("bench", kExitInvalid, generated.error().to_string());
  const scene::Scene& sc = generated.value();
  auto made = render::Renderer::create(sc);
  if (!made) fail("bench", kExitFailure, made.error().to_string());
  render::Renderer& r = *made.value();
  render::FrameSettings f;
  f.method = *render::parse_method(method);
  f.lens = render::scene_lens(sc, o.width, o.height);
  f.timed = true;
  RouteRow row;
  row.seed = seed;
  row.method = method;
  std::vector<double> speedups;
  double off_sum = 0.0, on_sum = 0.0, cull_sum = 0.0, read_sum = 0.0, occ_sum = 0.0;
  long objects = 0, objects_culled = 0, triangles = 0, triangles_culled = 0;
  for (const scene::Pose& p : scene::walkthrough_route(sc)) {
    const render::Camera cam = render::walk_camera(p.position, p.yaw, 0.0f, sc.camera.fov_y,
                                                   static_cast<float>(o.width) / static_cast<float>(o.height),
                                                   sc.camera.near_plane, sc.camera.far_plane);
    std::vector<double> off, on;
    std::vector<render::CullingReport> reports;
    for (int k = 0; k < o.frames + 1; ++k) {  // the first pair warms up (and builds the database)
      f.occlusion_culling = false;
      const double a = value_or_fail("bench", r.render_offscreen(cam, f, o.width, o.height)).frame_ms;
      f.occlusion_culling = true;
      const render::FrameReport rep = value_or_fail("bench", r.render_offscreen(cam, f, o.width, o.height));
      row.preprocess_ms += rep.culling.preprocess_ms;
      if (k == 0) continue;
      off.push_back(a);
      on.push_back(rep.frame_ms);
      reports.push_back(rep.culling);
    }
    const double m_off = median(off), m_on = median(on);
    std::vector<double> cull_ms;
    for (const auto& c : reports) cull_ms.push_back(c.ms);
    const render::CullingReport& c = reports.front();
    speedups.push_back(m_on > 0.0 ? m_off / m_on : 0.0);
    off_sum += m_off;
    on_sum += m_on;
    cull_sum += median(cull_ms);
    read_sum += c.readback_ms;
    occ_sum += c.occluders;
    objects += c.objects_in_view;
    objects_culled += c.objects_culled;
    triangles += c.triangles_in_view;
    triangles_culled += c.triangles_culled;
    std::cerr << "." << std::flush;
  }
  std::cerr << "\n";
  row.views = static_cast<int>(speedups.size());
  if (row.views == 0) return row;
  const double n = row.views;
  row.best = *std::max_element(speedups.begin(), speedups.end());
  row.worst = *std::min_element(speedups.begin(), speedups.end());
  row.mean = std::accumulate(speedups.begin(), speedups.end(), 0.0) / n;
  row.total = on_sum > 0.0 ? off_sum / on_sum : 0.0;
  row.off_ms = off_sum / n;
  row.on_ms = on_sum / n;
  row.culling_ms = cull_sum / n;
  row.readback_ms = read_sum / n;
  row.occluders = static_cast<int>(occ_sum / n + 0.5);
  row.objects_pct = objects > 0 ? 100.0 * static_cast<double>(objects_culled) / static_cast<double>(objects) : 0.0;
  row.triangles_pct =
      triangles > 0 ? 100.0 * static_cast<double>(triangles_culled) / static_cast<double>(triangles) : 0.0;
  return row;
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void bench_culling(const CullingBenchOptions& o) {
  for (const auto& m : o.methods)
    if (!render::parse_method(m)) fail("bench", kExitUsage, "--culling-methods: unknown method '" + m + "'");
  auto ctx = platform::create_headless(o.width, o.height);
  if (!ctx) fail("bench", kExitFailure, ctx.error().to_string());
  std::vector<RouteRow> rows;
  for (auto seed : o.seeds)
    for (const auto& m : o.methods) {
      std::cerr << "bench: culling route, walkthrough seed " << seed << ", " << m << " ";
      rows.push_back(run_route(o, seed, m));
    }
  if (o.json) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const RouteRow& r : rows)
      out.push_back({{"seed", r.seed},           {"method", r.method},
                     {"views", r.views},         {"speedup_best", r.best},
                     {"speedup_mean", r.mean},   {"speedup_worst", r.worst},
                     {"speedup_route", r.total}, {"frustum_only_ms", r.off_ms},
                     {"culling_on_ms", r.on_ms}, {"culling_ms", r.culling_ms},
                     {"readback_ms", r.readback_ms}, {"occluders", r.occluders},
                     {"objects_culled_pct", r.objects_pct}, {"triangles_culled_pct", r.triangles_pct},
                     {"preprocess_ms", r.preprocess_ms}});
    std::cout << nlohmann::ordered_json{{"width", o.width}, {"height", o.height}, {"frames", o.frames}, {"routes", out}}
                     .dump(2)
              << "\n";
    return;
  }
  std::printf("%-5s %-9s %5s | %6s %6s %6s %6s | %8s %8s %8s %8s | %4s %6s %6s | %9s\n", "seed", "method", "views",
              "best", "mean", "worst", "route", "off ms", "on ms", "cull ms", "read ms", "occ", "obj %", "tri %",
              "prep ms");
  for (const RouteRow& r : rows)
    std::printf("%-5llu %-9s %5d | %6.2f %6.2f %6.2f %6.2f | %8.2f %8.2f %8.3f %8.3f | %4d %6.1f %6.1f | %9.0f\n",
                static_cast<unsigned long long>(r.seed), r.method.c_str(), r.views, r.best, r.mean, r.worst, r.total,
                r.off_ms, r.on_ms, r.culling_ms, r.readback_ms, r.occluders, r.objects_pct, r.triangles_pct,
                r.preprocess_ms);
}

}  // namespace dtlab::app
