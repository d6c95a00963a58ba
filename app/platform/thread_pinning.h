// Pins software OpenGL's rasterizer threads (Mesa llvmpipe's "llvmpipe-N")
// one per CPU, so a frame's bins are rasterized in parallel every frame.
// Guarantees: after pin_software_gl_threads(), every llvmpipe thread of the
// process that was not pinned before runs on exactly one of the CPUs the
// process may use, thread N on the (N mod count)-th; threads pinned before
// are left alone. Never: touches other threads, or does anything when the
// process may use fewer than two CPUs, when no such threads exist (a GPU
// driver), or when DTLAB_PIN_GL_THREADS=0 is set.
#pragma once

namespace dtlab::platform {

// How many threads it pinned now (0 when it did nothing). create_headless() and create_window()
// call it after making their context current and finishing one frame (llvmpipe starts its
// threads with the context, and each names itself when it first runs).
int pin_software_gl_threads();

}  // namespace dtlab::platform
