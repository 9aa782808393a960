// Images: reading PNG and JPEG (glTF's formats), 8 or 16 bits per channel, into RGBA8 (stb_image;
// its other readers are not compiled in), and writing PNG and JPEG (stb_image_write). The one image
// reader and the one image writer of pelage: glTF textures, groom maps, rendered frames, plots,
// PNG read-back in tests. Limits are checked from the file's header before a
// pixel is decoded, so a corrupt or hostile size never allocates; stb_image is compiled into this
// library (static, instrumented by the sanitizer and fuzz builds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pelage {

struct ImageLimits {
  int maxSide = 16384;                            // pixels per side
  std::size_t maxBytes = std::size_t{256} << 20;  // decoded RGBA8 bytes (256 MiB: 8192 x 8192)
};

// An RGBA8 image, top row first.
struct Rgba8Image {
  int width = 0;
  int height = 0;
  int fileChannels = 0;            // channels stored in the file: 1 grey, 2 grey + alpha, 3, 4
  std::vector<std::uint8_t> rgba;  // height x width x 4
  std::size_t bytes() const { return rgba.size(); }
  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)) *
                             4;
  }
  std::uint8_t* pixel(int x, int y) {
    return const_cast<std::uint8_t*>(static_cast<const Rgba8Image&>(*this).pixel(x, y));
  }
};

// Decodes an image held in memory; `source` names it in messages ("Fox.glb: image 0 'Texture'").
// InputError naming `source` and the problem: empty, not a supported image (stb_image's reason),
// truncated or corrupt, or larger than `limits` (with its size and the limit).
Rgba8Image decodeImage(const std::uint8_t* data, std::size_t size, const std::string& source,
                       const ImageLimits& limits = {});

// Reads and decodes an image file (MissingFileError when it does not exist).
Rgba8Image readImageFile(const std::string& path, const ImageLimits& limits = {});

// 8-bit pixels, top row first, `channels` (3: RGB, 4: RGBA) per pixel, encoded as PNG in memory
// (thread-safe).
std::vector<std::uint8_t> encodePng(const std::uint8_t* pixels, int width, int height,
                                    int channels);
// Writes a PNG (.png) or a JPEG (.jpg, .jpeg; quality 95, alpha dropped), chosen by the extension
// (any case), atomically (util/atomic_file.h): never a truncated file. InputError naming the file
// for another extension or a failed write (unwritable directory, disk full).
void writeImageFile(const std::string& path, const std::uint8_t* pixels, int width, int height,
                    int channels);

// Writes `image` as writeImageFile above: as RGB when its fileChannels is 3 (alpha dropped), else
// as RGBA.
void writeImageFile(const std::string& path, const Rgba8Image& image);

// "8192x8192 (256.0 MiB as RGBA8)".
std::string describeImageSize(long long width, long long height);

}  // namespace pelage
