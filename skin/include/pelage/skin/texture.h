// A colour image on the skin's UV layout (a glTF base-colour texture, a groom map) and how it is
// sampled: a wrap mode per axis, bilinear or nearest filtering, sRGB or linear encoding. UV (0, 0)
// is the image's top-left corner, u to the right, v down (glTF's convention); texel (i, j) covers
// [i, i + 1) / width x [j, j + 1) / height.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "pelage/util/image.h"

namespace pelage::skin {

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
enum class Filter { Linear, Nearest };

struct Texture {
  std::string name;  // where it came from, for messages ("Fox.glb image 0")
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // height x width x 4, top row first
  Wrap wrapS = Wrap::Repeat;
  Wrap wrapT = Wrap::Repeat;
  Filter filter = Filter::Linear;
  bool srgb = true;  // colour stored sRGB-encoded (base colour, colour maps); false: linear data

  bool empty() const { return width == 0 || height == 0; }
  std::size_t bytes() const { return rgba.size(); }
  // The texel containing texture coordinates `uv` after wrapping: (i, j).
  Eigen::Vector2i texelAt(const Eigen::Vector2f& uv) const;
  // Linear RGBA at `uv`: nearest texel or bilinear between the four nearest texel centres (sRGB
  // texels decoded first, as a GPU samples an sRGB texture); alpha is always linear. Finite for any
  // finite or infinite uv (NaN samples texel (0, 0)).
  Eigen::Vector4f sample(const Eigen::Vector2f& uv) const;
  // Linear RGBA of texel (i, j) (0 <= i < width, 0 <= j < height).
  Eigen::Vector4f texel(int i, int j) const;
};

// A texture from a decoded image.
Texture makeTexture(Rgba8Image image, std::string name, bool srgb);

// "repeat", "clamp", "mirror".
std::string_view wrapName(Wrap wrap);

}  // namespace pelage::skin
