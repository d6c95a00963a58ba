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

}  // namespace dtlab::platform::detail
