#include "pelage/render/image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>

#include "pelage/util/atomic_file.h"
#include "pelage/util/color.h"
#include "pelage/util/error.h"
#include "pelage/util/image.h"
#include "pelage/util/path.h"

namespace pelage::render {

void makeOpaque(Image& image) {
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
}

void unblendBackground(Image& image, const Eigen::Vector3f& background) {
  const float* toLinear = srgb8ToLinearTable();
  std::array<int, 3> backgroundCode{};
  for (int c = 0; c < 3; ++c)
    backgroundCode[static_cast<std::size_t>(c)] = linearToSrgb8(background[c]);
  for (std::size_t i = 0; i + 3 < image.rgba.size(); i += 4) {
    std::uint8_t* p = image.rgba.data() + i;
    if (p[3] == 255) continue;
    // A pixel brighter than its coverage of the brightest colour (a hair's highlight above 1 in
    // linear light, or a coverage that rounded to 0) keeps its brightness with the coverage it
    // needs: a = (p - b) / (1 - b) (beyond the background's own 8-bit rounding).
    int alpha = p[3];
    for (int c = 0; c < 3; ++c) {
      const float drawn = toLinear[p[c]];
      if (background[c] >= 1.0f || p[c] <= backgroundCode[static_cast<std::size_t>(c)] + 1)
        continue;
      const float needed = (drawn - background[c]) / (1.0f - background[c]);
      alpha = std::max(alpha, static_cast<int>(std::ceil(std::min(needed, 1.0f) * 255.0f)));
    }
    p[3] = static_cast<std::uint8_t>(alpha);
    if (alpha == 0) {
      p[0] = p[1] = p[2] = 0;
      continue;
    }
    const float a = static_cast<float>(p[3]) / 255.0f;
    for (int c = 0; c < 3; ++c) {
      const float drawn = toLinear[p[c]];
      const float straight = (drawn - (1.0f - a) * background[c]) / a;
      const int nearest = linearToSrgb8(std::clamp(straight, 0.0f, 1.0f));
      // Of the 8-bit codes next to it, the one that composites back nearest to the drawn code
      // (8-bit rounding of a small a otherwise moves the composite by more than one code).
      int best = nearest, bestMiss = 256;
      for (int s = std::max(nearest - 2, 0); s <= std::min(nearest + 2, 255); ++s) {
        const float over = a * toLinear[s] + (1.0f - a) * background[c];
        const int miss = std::abs(static_cast<int>(linearToSrgb8(over)) - static_cast<int>(p[c]));
        if (miss < bestMiss ||
            (miss == bestMiss && std::abs(s - nearest) < std::abs(best - nearest))) {
          best = s;
          bestMiss = miss;
        }
      }
      p[c] = static_cast<std::uint8_t>(best);
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

}  // namespace pelage::render
