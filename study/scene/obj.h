// Wavefront OBJ + MTL export of a whole scene, in world space, so a scene can
// be opened in any 3D viewer. One `o`/`g` per object (named kind_id), one
// material per distinct colour (object tint x vertex colour, 8 bits per
// channel), `v`/`vn` pairs sharing indices, faces as `f v//vn`.
// Never writes partial files silently: save_obj reports every I/O failure.
#pragma once
#include <ostream>
#include <string>
#include <string_view>

#include "study/common/error.h"
#include "study/scene/scene.h"

namespace dtlab::scene {

// Writes the OBJ text to `obj` (referring to materials file `mtl_name`) and the
// material library to `mtl`. Streams are left as they are on failure.
void write_obj(const Scene& scene, std::ostream& obj, std::ostream& mtl, std::string_view mtl_name);

// Writes `obj_path` and, beside it, the same name with extension .mtl.
// Error (file = the path at fault) when a file cannot be written.
Status save_obj(const Scene& scene, const std::string& obj_path);

}  // namespace dtlab::scene
