// Why (measured on llvmpipe, 2 cores, `dtlab render --frames 30 --method
// standard` of ABSTRACT T1): unpinned, about one frame in four ran its two
// rasterizer threads one after the other (wall time = CPU time, 8-9 ms)
// instead of side by side (5.3-5.6 ms), most often in a process's first few
// hundred milliseconds, when the scheduler still wakes both threads on the
// CPU of the thread that queued the frame. So a method's median frame time
// depended on how long the process had run, and `standard` timed alone in a
// fresh process read up to 1.67 x its time interleaved in `dtlab bench`.
// Pinned, no frame ran serialized in 4 x 30 frames.
#include "app/platform/thread_pinning.h"

#include <sched.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace dtlab::platform {

namespace {
constexpr std::string_view kPrefix = "llvmpipe-";
}  // namespace

int pin_software_gl_threads() {
#if defined(__linux__)
  if (const char* v = std::getenv("DTLAB_PIN_GL_THREADS"); v != nullptr && std::string_view(v) == "0") return 0;
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return 0;
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
  if (cpus.size() < 2) return 0;
  int pinned = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    std::ifstream comm(entry.path() / "comm");
    std::string name;
    if (!std::getline(comm, name) || name.rfind(kPrefix, 0) != 0) continue;
    const std::string index = name.substr(kPrefix.size());
    if (index.empty() || index.find_first_not_of("0123456789") != std::string::npos || index.size() > 6) continue;
    const pid_t tid = static_cast<pid_t>(std::stol(entry.path().filename().string()));
    cpu_set_t current;
    CPU_ZERO(&current);
    if (sched_getaffinity(tid, sizeof current, &current) != 0 || !CPU_EQUAL(&current, &allowed)) continue;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpus[static_cast<std::size_t>(std::stoi(index)) % cpus.size()], &one);
    if (sched_setaffinity(tid, sizeof one, &one) == 0) ++pinned;
  }
  return pinned;
#else
  return 0;
#endif
}

}  // namespace dtlab::platform
