// Process-wide malloc settings for software OpenGL (Mesa's llvmpipe).
// Guarantees: after tune_malloc_for_software_gl() a frame's time does not
// depend on what else the process rendered before it (measured, see the .cpp).
// Never: changes anything but glibc's trim threshold and top pad; a no-op on
// other C libraries.
#pragma once

namespace dtlab::platform {

// Keeps freed heap memory in the process instead of handing it back to the kernel after
// every frame. Idempotent and thread-safe; main() calls it first, and create_headless() /
// create_window() call it, so every command and test program that renders has it.
void tune_malloc_for_software_gl();

}  // namespace dtlab::platform
