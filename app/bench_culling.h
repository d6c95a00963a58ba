// `dtlab bench --culling`: Poon's occlusion culling timed along WALKTHROUGH
// routes (study/scene/route.h), as the thesis reports it (ch. 5.1): per route,
// the speed-up over frustum culling alone at the best, average and worst view
// (culling's own time included), and the share of objects and triangles in
// the frustum that it culled. Deterministic routes; frames interleaved (off,
// on) per view so machine load hits both alike. Never: asserts a speed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dtlab::app {

struct CullingBenchOptions {
  bool json = false;
  int frames = 5;                   // timed frames per view and setting (median)
  std::vector<std::uint64_t> seeds;  // one route per seed (WALKTHROUGH T3)
  std::vector<std::string> methods;  // e.g. "standard", "dt-fast"
  int width = 800, height = 600;
};

// The median of `v` (0 when empty); the bench's summary of timed frames.
double median(std::vector<double> v);

// Runs the routes and prints the table (or JSON) on stdout, progress on stderr. Throws
// CLI::RuntimeError with the exit code on failure (no GL context: 3).
void bench_culling(const CullingBenchOptions& o);

}  // namespace dtlab::app
