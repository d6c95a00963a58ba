// The settings of every rendering method (see settings.h): names of their
// choices, range checks, unit conversions.
#include "study/technique/settings.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace dtlab::technique {

std::string_view to_string(ScreenDoorMasks m) {
  switch (m) {
    case ScreenDoorMasks::tabular: return "tabular";
    case ScreenDoorMasks::pixel_tree: return "pixel-tree";
    case ScreenDoorMasks::white_noise: return "white-noise";
  }
  return "?";
}

std::optional<ScreenDoorMasks> parse_screen_door_masks(std::string_view s) {
  for (ScreenDoorMasks m : {ScreenDoorMasks::tabular, ScreenDoorMasks::pixel_tree, ScreenDoorMasks::white_noise})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

std::optional<std::string> check(const ScreenDoorSettings& s) {
  if (s.mask_side == 8 || s.mask_side == 16 || s.mask_side == 32) return std::nullopt;
  return "mask_side must be 8, 16 or 32 (got " + std::to_string(s.mask_side) + ")";
}

std::string_view to_string(LensShape s) {
  switch (s) {
    case LensShape::sphere: return "sphere";
    case LensShape::box: return "box";
    case LensShape::cylinder: return "cylinder";
    case LensShape::cone: return "cone";
  }
  return "?";
}

std::optional<LensShape> parse_lens_shape(std::string_view s) {
  for (LensShape v : {LensShape::sphere, LensShape::box, LensShape::cylinder, LensShape::cone})
    if (to_string(v) == s) return v;
  return std::nullopt;
}

std::string_view to_string(LensStyle s) {
  switch (s) {
    case LensStyle::eraser: return "eraser";
    case LensStyle::wireframe: return "wireframe";
    case LensStyle::tint: return "tint";
  }
  return "?";
}

std::optional<LensStyle> parse_lens_style(std::string_view s) {
  for (LensStyle v : {LensStyle::eraser, LensStyle::wireframe, LensStyle::tint})
    if (to_string(v) == s) return v;
  return std::nullopt;
}

std::optional<std::string> check(const LensSettings& s) {
  auto positive = [](const char* name, float v) -> std::optional<std::string> {
    if (v > 0.0f && std::isfinite(v)) return std::nullopt;
    std::ostringstream o;
    o << name << " must be finite and > 0 (got " << v << ")";
    return o.str();
  };
  if (auto p = positive("distance", s.distance)) return p;
  if (auto p = positive("radius", s.radius)) return p;
  if (auto p = positive("length", s.length)) return p;
  if (!std::isfinite(s.center.x) || !std::isfinite(s.center.y)) return std::string("center must be finite");
  if (!(s.tint_strength >= 0.0f && s.tint_strength <= 1.0f)) {
    std::ostringstream o;
    o << "tint_strength must be 0..1 (got " << s.tint_strength << ")";
    return o.str();
  }
  if (!(glm::all(glm::greaterThanEqual(s.tint, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(s.tint, glm::vec3(1.0f)))))
    return std::string("tint must be an RGB colour in 0..1");
  return std::nullopt;
}

std::string_view to_string(MaskShape s) {
  switch (s) {
    case MaskShape::outline: return "outline";
    case MaskShape::circle: return "circle";
    case MaskShape::ellipse: return "ellipse";
  }
  return "?";
}

std::optional<MaskShape> parse_mask_shape(std::string_view s) {
  for (MaskShape m : {MaskShape::outline, MaskShape::circle, MaskShape::ellipse})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

std::string_view to_string(DtField f) {
  switch (f) {
    case DtField::alpha_target: return "alpha_target";
    case DtField::alpha_start: return "alpha_start";
    case DtField::gradient: return "gradient_px";
    case DtField::mask_resolution: return "mask_resolution";
    case DtField::layer_limit: return "layer_limit";
    case DtField::searchlight: return "searchlight";
  }
  return "?";
}

int max_mask_resolution(int width, int height) { return std::max({128, width, height}); }

std::optional<SettingsProblem> check(const DtSettings& s, int width, int height) {
  auto got = [](double v) {
    std::ostringstream o;
    o << " (got " << v << ")";
    return o.str();
  };
  if (!(s.alpha_target >= 0.0f && s.alpha_target < 1.0f))
    return SettingsProblem{DtField::alpha_target, "must be at least 0 and below 1" + got(s.alpha_target)};
  if (!(s.alpha_start >= 0.0f && s.alpha_start < 1.0f))
    return SettingsProblem{DtField::alpha_start, "must be at least 0 and below 1" + got(s.alpha_start)};
  if (!(s.gradient_px >= 0.0f && s.gradient_px <= 4096.0f))
    return SettingsProblem{DtField::gradient, "must be 0..4096 output pixels" + got(s.gradient_px)};
  if (s.mask_resolution < 0)
    return SettingsProblem{DtField::mask_resolution, "must be 0 (full resolution) or positive" + got(s.mask_resolution)};
  if (width > 0 && height > 0 && s.mask_resolution > max_mask_resolution(width, height))
    return SettingsProblem{DtField::mask_resolution,
                           "must be at most " + std::to_string(max_mask_resolution(width, height)) + " for a " +
                               std::to_string(width) + " x " + std::to_string(height) +
                               " view (a mask finer than the view changes nothing but the cost; 0 = full "
                               "resolution)" + got(s.mask_resolution)};
  if (s.layer_limit < 0 || s.layer_limit > 60)
    return SettingsProblem{DtField::layer_limit, "must be 0 (no limit) or 1..60" + got(s.layer_limit)};
  if (!(s.searchlight_radius >= 0.0f) || !std::isfinite(s.searchlight_radius) || !std::isfinite(s.searchlight_center.x) ||
      !std::isfinite(s.searchlight_center.y))
    return SettingsProblem{DtField::searchlight, "radius must be finite and >= 0 and the centre finite"};
  return std::nullopt;
}

float gradient_px_from_mask_pixels(float mask_pixels, int mask_resolution, int width, int height) {
  if (mask_resolution <= 0) return mask_pixels;
  return mask_pixels * std::sqrt(static_cast<float>(width) * static_cast<float>(height)) / static_cast<float>(mask_resolution);
}

std::optional<std::string> check(const VdtSettings& s) {
  const std::pair<const char*, float> members[] = {
      {"falloff", s.falloff}, {"opaque_alpha", s.opaque_alpha}, {"background_alpha", s.background_alpha}};
  for (const auto& [name, v] : members) {
    if (v >= 0.0f && v <= 1.0f) continue;
    std::ostringstream o;
    o << name << " must be 0..1 (got " << v << ")";
    return o.str();
  }
  return std::nullopt;
}

}  // namespace dtlab::technique
