#include "pelage/viewer/image.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "pelage/util/atomic_file.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/path.h"

namespace pelage::viewer {

void makeOpaque(Image& image) {
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
}

void unblendBackground(Image& image, const Eigen::Vector3f& background) {
  const float* toLinear = srgb8ToLinearTable();
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    std::uint8_t* p = image.rgba.data() + i;
    if (p[3] == 255) continue;
    if (p[3] == 0) {
      p[0] = p[1] = p[2] = 0;
      continue;
    }
    const float a = static_cast<float>(p[3]) / 255.0f;
    for (int c = 0; c < 3; ++c) {
      const float drawn = toLinear[p[c]];
      const float straight = (drawn - (1.0f - a) * background[c]) / a;
      p[c] = linearToSrgb8(std::clamp(straight, 0.0f, 1.0f));
    }
  }
}

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

void writeImage(const std::string& path, const Image& image) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") {
    writePng(path, image);
    return;
  }
  if (ext != ".jpg" && ext != ".jpeg")
    inputError(path, ": unsupported image format '", ext, "' (accepted: .png, .jpg, .jpeg)");
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(image.width) *
                                static_cast<std::size_t>(image.height) * 3);
  for (std::size_t i = 0, n = rgb.size() / 3; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      rgb[3 * i + static_cast<std::size_t>(c)] = image.rgba[4 * i + static_cast<std::size_t>(c)];
  std::vector<std::uint8_t> out;
  stbi_write_jpg_to_func(
      [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
        const auto* p = static_cast<const std::uint8_t*>(data);
        v->insert(v->end(), p, p + size);
      },
      &out, image.width, image.height, 3, rgb.data(), 95);
  PELAGE_CHECK(!out.empty(), "JPEG encoding failed");
  AtomicFileWriter w(path);
  w.write(out.data(), out.size());
  w.commit();
}

Image readPng(const std::string& path) {
  Rgba8Image decoded = readImageFile(path);
  Image img;
  img.width = decoded.width;
  img.height = decoded.height;
  img.rgba = std::move(decoded.rgba);
  return img;
}

bool isCompletePng(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  unsigned char head[16] = {};
  if (!in.read(reinterpret_cast<char*>(head), 16)) return false;
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::memcmp(head, sig, 8) != 0 || std::memcmp(head + 12, "IHDR", 4) != 0) return false;
  in.seekg(-12, std::ios::end);
  unsigned char tail[12] = {};
  if (!in.read(reinterpret_cast<char*>(tail), 12)) return false;
  static const unsigned char iend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
  return std::memcmp(tail, iend, 12) == 0;
}

}  // namespace pelage::viewer
