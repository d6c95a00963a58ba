// Why (measured on llvmpipe, 2 cores): llvmpipe copies about 33 KB of state
// per draw call and frees it at the end of the frame. With glibc's default,
// dynamic trim threshold the top of the heap is returned to the kernel at
// those frees and faulted back in during the next frame: `dtlab render
// --method standard` of WALKTHROUGH T3 seed 1 took 80 000 page faults and
// 52 ms CPU per frame over 40 frames, 14 600 and 21 ms with a fixed 256 MiB
// trim threshold and 64 MiB top pad (the same as MALLOC_TRIM_THRESHOLD_ /
// MALLOC_TOP_PAD_ in the environment). How much a method suffered depended on
// the heap left by whatever the process rendered before, so standard looked
// slower than dt-fast in a standard-only process.
#include "app/platform/malloc_tuning.h"

#include <mutex>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace dtlab::platform {

void tune_malloc_for_software_gl() {
  static std::once_flag once;
  std::call_once(once, [] {
#if defined(__GLIBC__)
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    mallopt(M_TOP_PAD, 64 << 20);
#endif
  });
}

}  // namespace dtlab::platform
