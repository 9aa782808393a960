// PNG files for tests (groom maps, textures, image reading): Debian's libstb stb_image_write, the
// encoder the viewer writes frames with. 8 bits per channel, `channels` 1 to 4, top row first.
#pragma once

#include <stb_image_write.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace pelage::test {

inline std::vector<std::uint8_t> pngBytes(int w, int h, int channels,
                                          const std::vector<std::uint8_t>& pixels) {
  std::vector<std::uint8_t> out;
  stbi_write_png_to_func(
      [](void* context, void* data, int size) {
        auto* o = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* b = static_cast<const std::uint8_t*>(data);
        o->insert(o->end(), b, b + size);
      },
      &out, w, h, channels, pixels.data(), w * channels);
  return out;
}

inline void writePng(const std::string& path, int w, int h, int channels,
                     const std::vector<std::uint8_t>& pixels) {
  const std::vector<std::uint8_t> b = pngBytes(w, h, channels, pixels);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

}  // namespace pelage::test
