#include "pelage/viewer/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstring>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"

namespace pelage::viewer {

std::vector<std::uint8_t> encodePng(const Image& image) {
  PELAGE_CHECK(image.width > 0 && image.height > 0 &&
                   image.rgba.size() == static_cast<std::size_t>(image.width) *
                                            static_cast<std::size_t>(image.height) * 4,
               "image ", image.width, "x", image.height, " with ", image.rgba.size(), " bytes");
  std::vector<std::uint8_t> out;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
        const auto* p = static_cast<const std::uint8_t*>(data);
        v->insert(v->end(), p, p + size);
      },
      &out, image.width, image.height, 4, image.rgba.data(), image.width * 4);
  PELAGE_CHECK(!out.empty(), "PNG encoding failed");
  return out;
}

void writePng(const std::string& path, const Image& image) {
  const std::vector<std::uint8_t> png = encodePng(image);
  AtomicFileWriter w(path);
  w.write(png.data(), png.size());
  w.commit();
}

Image readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!data) inputError(path, ": cannot read PNG (", stbi_failure_reason(), ")");
  Image img;
  img.width = w;
  img.height = h;
  img.rgba.assign(data, data + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  stbi_image_free(data);
  return img;
}

}  // namespace pelage::viewer
