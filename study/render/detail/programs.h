// Internal: the renderer's GLSL programs, compiled from the embedded files in
// shaders/ (GLSL 330 core): the shared table (what several methods draw with)
// and the link step a method's own programs go through (method.h: a method
// compiles its variants in its MethodState on its first frame). Guarantees: a
// compile or link failure is an environment Error naming the shader file and
// carrying the driver's log; shared GLSL (lighting.glsl, searchlight.glsl) is
// written once and put before the code that names it; uniform locations are looked up once per
// name. Never: reads shader files at run time.
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
// are #defined in both shaders, after their #version lines; `fragment_chunks` (e.g.
// "lighting.glsl": embedded files of shared GLSL) follow them in the fragment shader, before its
// own code. #line keeps the driver's log pointing at file and line: a line of the shader's own
// file has its own number, line i of the k-th chunk 10000 k + i (the Error's message says so).
Result<Program> link_program(const char* vertex_file, const char* fragment_file, const char* defines = "",
                             const char* fragment_chunks = "");
// A method's own program, linked on its first frame (from a method's add(), inside the renderer's
// guarded public function): link_program's program, or throws GlFailure ("<method>: " and the
// Error's text: shader file, driver's log), which Renderer::render returns as an environment
// Error (boundary.h), as it does a culling shader the driver refuses.
Program link_method_program(const char* method, const char* vertex_file, const char* fragment_file,
                            const char* defines = "", const char* fragment_chunks = "");
// The text link_program hands the driver for the embedded `file`: up to its #version line,
// `defines`, the `chunks` (the k-th after `#line 10000 k + 1 k`), `#line n 0` and the rest of the
// file from its line n.
Result<std::string> shader_source(const char* file, const char* defines = "", const char* chunks = "");
// Deletes `p`'s GL program, if any, and zeroes its id (needs the context current).
void delete_program(Program& p);

// The programs several methods draw with (a method's own variants live in its MethodState).
// Variants with SEARCHLIGHT may discard; the others never do (a shader that may discard makes
// llvmpipe test depth after shading).
struct Programs {
  Program object;       // object.vert + object.frag: lit or flat colour
  Program object_sl;    // the same, cut to the searchlight (the R1 guard's repair in active mode)
  Program object_flat;  // the same with FLAT: u_flat.rgb only (weight frames; no attribute interpolated)
  Program object_flat_sl;  // FLAT and SEARCHLIGHT
  Program object_alpha; // object.vert + flat_alpha.frag: depth-only, queries, silhouettes
  Program object_alpha_sl;  // the same, cut to the searchlight (or alpha 1 outside it)
  Program quad_alpha;   // fullscreen.vert + flat_alpha.frag (SEARCHLIGHT)
  Program border;       // fullscreen.vert (TILES) + border.frag (Algorithm 3), one rectangle per mask tile
  Program shape;        // fullscreen.vert + shape.frag (circle / ellipse masks)
  Program cheb_rows;    // fullscreen.vert (TILES) + cheb_rows.frag (dt-fast distances)
  Program cheb_cols;    // fullscreen.vert (TILES) + cheb_cols.frag
  Program fast_apply;   // fullscreen.vert + fast_apply.frag (Algorithm 2, line 10, from an atlas tile)
  Program fast_apply_counter;  // the same with COUNTER (layer limit: discards where the mask is 1)
  void destroy();       // deletes every program (needs the context current)
};

// Links every program of the table (Renderer::create); the first failure's Error.
Result<Programs> compile_programs();

}  // namespace dtlab::render::detail
