// What GL the current context is: for the record of a session's display (a
// result can be traced to the renderer that drew it). Needs a current GL 3.3
// core context; reads two strings, changes no state.
#pragma once
#include <string>

namespace dtlab::render {

// "GL_VERSION / GL_RENDERER" of the current context, e.g. "4.5 (Core Profile) Mesa 22.3.6 / llvmpipe ...";
// "?" parts when no context is current, "no GL loaded" before any context was made.
std::string current_gl_description();

}  // namespace dtlab::render
