#include "pelage/skin/texture.h"
#include "pelage/util/color.h"

#include <array>
#include <cmath>

namespace pelage::skin {
namespace {

// x (texel units, any finite value) wrapped into [0, n) for repeat, [0, 2n) folded for mirror, or
// clamped to [-1, n] for clamp-to-edge (then the texel index is clamped).
double wrapCoordinate(double x, int n, Wrap wrap) {
  const double size = static_cast<double>(n);
  switch (wrap) {
    case Wrap::Repeat:
      return x - std::floor(x / size) * size;
    case Wrap::MirroredRepeat:
      return x - std::floor(x / (2.0 * size)) * (2.0 * size);
    case Wrap::ClampToEdge:
      return x < -1.0 ? -1.0 : (x > size ? size : x);
  }
  return 0.0;
}

// The texel index of integer position i (after wrapCoordinate) for an axis of n texels.
int wrapIndex(long long i, int n, Wrap wrap) {
  const auto size = static_cast<long long>(n);
  switch (wrap) {
    case Wrap::Repeat:
      return static_cast<int>(((i % size) + size) % size);
    case Wrap::MirroredRepeat: {
      const long long m = ((i % (2 * size)) + 2 * size) % (2 * size);
      return static_cast<int>(m < size ? m : 2 * size - 1 - m);
    }
    case Wrap::ClampToEdge:
      return static_cast<int>(i < 0 ? 0 : (i >= size ? size - 1 : i));
  }
  return 0;
}

double finiteOr0(float v) {
  if (std::isnan(v)) return 0.0;
  // Infinite coordinates land on an edge; huge finite ones keep their fractional position.
  if (std::isinf(v)) return v > 0 ? 1e30 : -1e30;
  return static_cast<double>(v);
}

}  // namespace

Texture makeTexture(Rgba8Image image, std::string name, bool srgb) {
  Texture t;
  t.name = std::move(name);
  t.width = image.width;
  t.height = image.height;
  t.rgba = std::move(image.rgba);
  t.srgb = srgb;
  return t;
}

Eigen::Vector4f Texture::texel(int i, int j) const {
  const std::uint8_t* p =
      rgba.data() + (static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(i)) *
                        4;
  const float* lut = srgb8ToLinearTable();
  const auto unorm = [](std::uint8_t v) { return static_cast<float>(v) / 255.0f; };
  if (srgb) return {lut[p[0]], lut[p[1]], lut[p[2]], unorm(p[3])};
  return {unorm(p[0]), unorm(p[1]), unorm(p[2]), unorm(p[3])};
}

Eigen::Vector2i Texture::texelAt(const Eigen::Vector2f& uv) const {
  const double x = wrapCoordinate(finiteOr0(uv.x()) * width, width, wrapS);
  const double y = wrapCoordinate(finiteOr0(uv.y()) * height, height, wrapT);
  return {wrapIndex(static_cast<long long>(std::floor(x)), width, wrapS),
          wrapIndex(static_cast<long long>(std::floor(y)), height, wrapT)};
}

Eigen::Vector4f Texture::sample(const Eigen::Vector2f& uv) const {
  if (empty()) return Eigen::Vector4f::Ones();
  if (filter == Filter::Nearest) {
    const Eigen::Vector2i t = texelAt(uv);
    return texel(t.x(), t.y());
  }
  // Bilinear between texel centres: x = u w - 1/2.
  const double x = wrapCoordinate(finiteOr0(uv.x()) * width - 0.5, width, wrapS);
  const double y = wrapCoordinate(finiteOr0(uv.y()) * height - 0.5, height, wrapT);
  const double x0 = std::floor(x), y0 = std::floor(y);
  const auto fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const auto ix = static_cast<long long>(x0), iy = static_cast<long long>(y0);
  const int i0 = wrapIndex(ix, width, wrapS), i1 = wrapIndex(ix + 1, width, wrapS);
  const int j0 = wrapIndex(iy, height, wrapT), j1 = wrapIndex(iy + 1, height, wrapT);
  const Eigen::Vector4f top = texel(i0, j0) * (1.0f - fx) + texel(i1, j0) * fx;
  const Eigen::Vector4f bottom = texel(i0, j1) * (1.0f - fx) + texel(i1, j1) * fx;
  return top * (1.0f - fy) + bottom * fy;
}

std::string_view wrapName(Wrap wrap) {
  switch (wrap) {
    case Wrap::Repeat:
      return "repeat";
    case Wrap::ClampToEdge:
      return "clamp";
    case Wrap::MirroredRepeat:
      return "mirror";
  }
  return "repeat";
}

}  // namespace pelage::skin
