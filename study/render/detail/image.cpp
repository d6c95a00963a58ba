// PNG writing with Debian's libstb (stb_image_write), see image.h.
#include <stb/stb_image_write.h>

#include "study/render/image.h"

namespace dtlab::render {

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
