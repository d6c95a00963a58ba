// Internal to dtlab_platform: which glad loader is active. glad keeps one set
// of global GL function pointers; OSMesa and GLX hand out different entry
// points, so a switch between a headless context and a window reloads them.
// Must only be called with a context of `kind` current.
#pragma once
#include "app/platform/gl_context.h"

namespace dtlab::platform::detail {

// Loads GL functions for `kind` unless they are already loaded for it.
// Returns the GL version as major * 10 + minor, or 0 when loading failed.
int load_gl_for(ContextKind kind);

// Call before making a context of `kind` current: if a context of the other kind is
// current, it is released first. OSMesa and the GLX driver share Mesa's dispatch state, and
// GLX skips a make-current it believes is a no-op, so without the release the window would
// keep drawing through the OSMesa context (a crash in swap_buffers).
void switching_to(ContextKind kind);
// A window is going away: forget that a window context is current.
void window_released();

// After a context is made current: one cleared, finished frame, then pin_software_gl_threads().
// llvmpipe names each rasterizer thread ("llvmpipe-N") when the thread first runs, which on a
// loaded machine can be milliseconds after the context exists (a pin then missed the unnamed
// thread); a finished frame waits for every rasterizer thread, so all of them have named
// themselves. Returns how many threads it pinned.
int pin_gl_threads_of_current_context();

}  // namespace dtlab::platform::detail
