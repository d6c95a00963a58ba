// Icons of the WALKTHROUGH object kinds for the on-screen "find this" panel:
// each kind drawn alone by the real renderer (standard method, headlight) from
// a 3/4 view whose camera frames the model's mesh exactly, into a small RGBA
// image whose background is transparent (alpha 0); and a contact sheet of all
// kinds with their names, for eyes and docs. Guarantees: the same options give
// the same bytes (no clock, no random source); icons keep a transparent border
// of `margin`. Never: creates a GL context (the caller makes one current),
// edits the model catalogue, or draws with anything but study/render.
#pragma once
#include <span>
#include <string>
#include <vector>

#include "study/common/error.h"
#include "study/render/camera.h"
#include "study/render/image.h"
#include "study/scene/models.h"
#include "study/scene/scene.h"

namespace dtlab::icons {

inline constexpr int kMinSize = 16;    // smallest icon side in pixels
inline constexpr int kMaxSize = 1024;  // largest icon side in pixels

struct IconOptions {
  int size = 96;               // icon side in pixels, kMinSize..kMaxSize
  int supersample = 4;         // rendered at size x supersample per side, box-filtered down (1..8)
  float azimuth_deg = 50.0f;   // camera direction about the vertical: 0 = from the model's +z side, 90 = from its front (+x)
  float elevation_deg = 22.0f;  // camera above the horizon, degrees (0..80)
  float fov_deg = 30.0f;       // perspective of the view (the frustum is then fitted to the mesh), 5..90
  float margin = 0.05f;        // transparent border on every side, share of the side (0..0.3)
};
// Throws std::invalid_argument naming the field if a value is out of range.
void validate(const IconOptions& o);

// The one-object scene of `model`: its mesh at the origin, untinted, no flags set.
scene::Scene icon_scene(const scene::ModelInfo& model);

// The 3/4 view camera of `mesh` for a square image: looks at the mesh from (azimuth, elevation)
// with an off-centre frustum fitted so the projected vertices span the image minus `margin`
// exactly along the longer side, centred along the other.
render::Camera icon_camera(const scene::Mesh& mesh, const IconOptions& options);

// Renders the icon of `model`: size x size RGBA, top row first, straight (not premultiplied)
// alpha = the share of the pixel the model covers, 0 on the background. Needs a current
// GL 3.3 core context; fails (Error) if the renderer cannot be created or a frame fails.
Result<render::Image> render_icon(const scene::ModelInfo& model, const IconOptions& options = {});

// Share of the image the object covers: the mean alpha over all pixels, in [0, 1].
double coverage(const render::Image& icon);

struct Icon {
  const scene::ModelInfo* model = nullptr;  // from scene::model_catalogue()
  render::Image image;
};
// Every catalogue kind's icon, in catalogue order (pets, vehicles, furniture).
Result<std::vector<Icon>> render_all(const IconOptions& options = {});

// Where the contact sheet puts things. One row per family (catalogue order), a left gutter
// with the family's name, a title line on top; each cell holds an icon and its label under it.
struct SheetLayout {
  struct Rect { int x = 0, y = 0, w = 0, h = 0; };
  int width = 0, height = 0;   // the sheet in pixels
  int text_scale = 1;          // stb_easy_font pixels per font unit
  int columns = 0, rows = 0;   // cells per row (the largest family), families
  std::vector<Rect> icon_rects;   // per icon, in the order given: where the icon is drawn
  std::vector<Rect> label_rects;  // per icon: the label area under it
};
// The layout for `icons` (all the same size). Throws std::invalid_argument if sizes differ or
// `icons` is empty.
SheetLayout sheet_layout(std::span<const Icon> icons);

// The contact sheet: opaque RGBA, icons composited over a neutral grey cell, each kind's
// label (ModelInfo::label, wrapped at spaces) under its icon, drawn with stb_easy_font.
render::Image contact_sheet(std::span<const Icon> icons);

// Writes `image` as PNG with its alpha channel. Error naming the path if it cannot.
Status save_png(const render::Image& image, const std::string& path);

}  // namespace dtlab::icons
