// Software GL's rasterizer threads pinned one per CPU (app/platform/thread_pinning.h):
// checked on the threads a real OSMesa (llvmpipe) context starts, through /proc.
#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "app/platform/gl_context.h"
#include "app/platform/thread_pinning.h"

namespace {

using dtlab::platform::create_headless;
using dtlab::platform::pin_software_gl_threads;

std::vector<int> cpus_of(pid_t tid) {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> out;
  if (sched_getaffinity(tid, sizeof set, &set) != 0) return out;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &set)) out.push_back(c);
  return out;
}

// Thread name ("llvmpipe-0", ...) -> the CPUs it may run on, for every llvmpipe thread.
std::map<std::string, std::vector<int>> llvmpipe_threads() {
  std::map<std::string, std::vector<int>> out;
  for (const auto& e : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream comm(e.path() / "comm");
    std::string name;
    if (std::getline(comm, name) && name.rfind("llvmpipe-", 0) == 0)
      out[name] = cpus_of(static_cast<pid_t>(std::stol(e.path().filename().string())));
  }
  return out;
}

// A headless context with two rasterizer threads; skips where pinning cannot apply.
std::unique_ptr<dtlab::platform::GlContext> context_or_skip() {
  if (cpus_of(0).size() < 2) return nullptr;
  auto ctx = create_headless(64, 64, 2);
  if (!ctx) return nullptr;
  return std::move(ctx.value());
}

TEST(ThreadPinning, EachRasterizerThreadRunsOnOneCpuTheFirstTwoOnDifferentOnes) {
  auto ctx = context_or_skip();
  if (!ctx) GTEST_SKIP() << "fewer than 2 CPUs or no headless context";
  ASSERT_NE(ctx->description().find("llvmpipe"), std::string::npos) << ctx->description();
  const auto threads = llvmpipe_threads();
  ASSERT_EQ(threads.count("llvmpipe-0"), 1u);
  ASSERT_EQ(threads.count("llvmpipe-1"), 1u);
  for (const auto& [name, cpus] : threads) EXPECT_EQ(cpus.size(), 1u) << name;
  EXPECT_NE(threads.at("llvmpipe-0"), threads.at("llvmpipe-1"));
  for (const auto& [name, cpus] : threads) {
    const auto allowed = cpus_of(0);
    EXPECT_NE(std::find(allowed.begin(), allowed.end(), cpus.front()), allowed.end()) << name;
  }
}

TEST(ThreadPinning, ThreadsPinnedBeforeAreLeftAlone) {
  auto ctx = context_or_skip();
  if (!ctx) GTEST_SKIP() << "fewer than 2 CPUs or no headless context";
  const auto before = llvmpipe_threads();
  EXPECT_EQ(pin_software_gl_threads(), 0);
  EXPECT_EQ(llvmpipe_threads(), before);
}

TEST(ThreadPinning, DtlabPinGlThreadsZeroTurnsItOff) {
  ::setenv("DTLAB_PIN_GL_THREADS", "0", 1);
  auto ctx = context_or_skip();
  if (!ctx) GTEST_SKIP() << "fewer than 2 CPUs or no headless context";
  const auto threads = llvmpipe_threads();
  ASSERT_FALSE(threads.empty());
  for (const auto& [name, cpus] : threads) EXPECT_EQ(cpus, cpus_of(0)) << name;
  EXPECT_EQ(pin_software_gl_threads(), 0);
  ::unsetenv("DTLAB_PIN_GL_THREADS");
  EXPECT_EQ(pin_software_gl_threads(), static_cast<int>(threads.size()));
}

}  // namespace
