// Image comparison and PNG writing with Debian's libstb (stb_image_write),
// see image.h. Never throws: a size mismatch is an Error.
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "study/render/image.h"

namespace dtlab::render {

namespace {

Error compare_error(const std::string& message) {
  return Error{"", 0, 0, "image", message, ErrorKind::invalid_input};
}

Result<ImageDiff> compare_over(const Image& a, const Image& b, const std::vector<std::uint8_t>* region) {
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
    return compare_error("compare: images differ in size (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                         " and " + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  const std::size_t pixels = a.rgba.size() / 4;
  if (region != nullptr && region->size() != pixels)
    return compare_error("compare: the region is not one byte per pixel of the images");
  ImageDiff d;
  double sum = 0.0;
  std::size_t off = 0, counted = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    if (region != nullptr && (*region)[p] == 0) continue;
    ++counted;
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(static_cast<int>(a.rgba[p * 4 + c]) - static_cast<int>(b.rgba[p * 4 + c]));
      sum += diff;
      worst = std::max(worst, diff);
    }
    d.max_abs = std::max(d.max_abs, worst);
    if (worst > 4) ++off;
  }
  d.pixels = static_cast<long>(counted);
  if (counted == 0) return d;
  d.mae = sum / static_cast<double>(counted * 3);
  d.pixels_off_pct = 100.0 * static_cast<double>(off) / static_cast<double>(counted);
  return d;
}

}  // namespace

Result<ImageDiff> compare(const Image& a, const Image& b) { return compare_over(a, b, nullptr); }

Result<ImageDiff> compare_in(const Image& a, const Image& b, const std::vector<std::uint8_t>& region) {
  return compare_over(a, b, &region);
}

Status write_png(const Image& image, const std::string& path, bool keep_alpha) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4) {
    Error e;
    e.file = path;
    e.message = "image is empty or its size does not match width x height";
    return e;
  }
  std::vector<std::uint8_t> data = image.rgba;
  if (!keep_alpha)
    for (std::size_t i = 3; i < data.size(); i += 4) data[i] = 255;
  if (stbi_write_png(path.c_str(), image.width, image.height, 4, data.data(), image.width * 4) == 0) {
    Error e;
    e.file = path;
    e.message = "cannot write the PNG file (directory missing or not writable?)";
    return e;
  }
  return {};
}

}  // namespace dtlab::render
