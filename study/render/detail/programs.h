// Internal: the renderer's GLSL programs, compiled from the embedded files in
// shaders/ (GLSL 330 core). Guarantees: a compile or link failure is an Error
// naming the shader file and carrying the driver's log; uniform locations are
// looked up once per name. Never: reads shader files at run time.
#pragma once
#include <map>
#include <string>

#include "study/common/error.h"

namespace dtlab::render::detail {

class Program {
 public:
  unsigned id = 0;
  int loc(const char* name) const;  // uniform location, -1 if the program has no such active uniform
 private:
  mutable std::map<std::string, int, std::less<>> locations_;
};

// Compiles and links the embedded `vertex_file` and `fragment_file`; `defines` (e.g. "SEARCHLIGHT")
// are #defined in both shaders, after their #version lines.
Result<Program> link_program(const char* vertex_file, const char* fragment_file, const char* defines = "");

// Variants with SEARCHLIGHT may discard; the others never do (a shader that may discard makes
// llvmpipe test depth after shading).
struct Programs {
  Program object;       // object.vert + object.frag: lit or flat colour
  Program object_sl;    // the same, cut to the searchlight (the R1 guard's repair in active mode)
  Program object_flat;  // the same with FLAT: u_flat.rgb only (weight frames; no attribute interpolated)
  Program object_flat_sl;  // FLAT and SEARCHLIGHT
  Program object_lens;  // the same with LENS: the lens method's second depth test (discards)
  Program object_vdt;   // the same with VDT: alpha = the per-vertex view-dependent alpha (attribute 3)
  Program object_alpha; // object.vert + flat_alpha.frag: depth-only, queries, silhouettes
  Program object_alpha_peel;  // the same with PEEL: vdt's second-layer depth pass (discards)
  Program object_alpha_sl;  // the same, cut to the searchlight (or alpha 1 outside it)
  Program quad_alpha;   // fullscreen.vert + flat_alpha.frag (SEARCHLIGHT)
  Program border;       // fullscreen.vert (TILES) + border.frag (Algorithm 3), one rectangle per mask tile
  Program shape;        // fullscreen.vert + shape.frag (circle / ellipse masks)
  Program cheb_rows;    // fullscreen.vert (TILES) + cheb_rows.frag (dt-fast distances)
  Program cheb_cols;    // fullscreen.vert (TILES) + cheb_cols.frag
  Program fast_apply;   // fullscreen.vert + fast_apply.frag (Algorithm 2, line 10, from an atlas tile)
  Program fast_apply_counter;  // the same with COUNTER (layer limit: discards where the mask is 1)
  Program object_sd;    // object.vert + object.frag with SCREEN_DOOR: keeps the sub-pixels of its mask (discards)
  Program sd_resolve;   // fullscreen.vert + sd_resolve.frag: the enlarged buffer box-filtered to output pixels
  void destroy();       // deletes every program (needs the context current)
};

Result<Programs> compile_programs();

}  // namespace dtlab::render::detail
