#include "pelage/viewer/image.h"

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
  PELAGE_CHECK(image.rgba.size() == static_cast<std::size_t>(image.width) *
                                        static_cast<std::size_t>(image.height) * 4,
               "image ", image.width, "x", image.height, " with ", image.rgba.size(), " bytes");
  return pelage::encodePng(image.rgba.data(), image.width, image.height, 4);
}

void writePng(const std::string& path, const Image& image) {
  if (lowerExtension(path) != ".png") inputError(path, ": a PNG file must end in .png");
  writeImage(path, image);
}

void writeImage(const std::string& path, const Image& image) {
  PELAGE_CHECK(image.rgba.size() == static_cast<std::size_t>(image.width) *
                                        static_cast<std::size_t>(image.height) * 4,
               "image ", image.width, "x", image.height, " with ", image.rgba.size(), " bytes");
  writeImageFile(path, image.rgba.data(), image.width, image.height, 4);
}

Image readPng(const std::string& path) {
  return readImageFile(path);
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
