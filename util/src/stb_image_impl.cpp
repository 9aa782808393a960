// stb_image (Debian's libstb-dev header), compiled here with internal linkage (STB_IMAGE_STATIC)
// and without stdio: pelage hands it bytes it has read itself. Third-party code: built without
// pelage's warnings (util/CMakeLists.txt). Only PNG and JPEG, glTF's image formats, are compiled
// in: stb 2.27's PNM reader overflows its buffer on 16-bit files (found by fuzz_image), its GIF
// reader has known memory bugs, and BMP, TGA and PSD are not texture formats users need.
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_NO_HDR
#define STBI_NO_LINEAR
#define STBI_NO_PIC
#define STBI_MAX_DIMENSIONS (1 << 24)
#include <stb_image.h>

#include <cstring>

#include "stb_image_impl.h"

namespace pelage::detail {

// stb_image 2.27 (Debian 12) trusts a JPEG DHT segment's 16 code counts: a table with more than 256
// codes writes past its 257-entry size array and 256-entry value array (found by fuzz_image; later
// stb versions reject it). Every FF C4 in the file is read the way stb reads a DHT segment there
// (a superset of the segments stb will read: its markers are FF C4 byte pairs too, fill bytes
// only before them), and the file is refused if any table would overflow.
bool jpegHuffmanTablesFit(const std::uint8_t* data, int size) {
  if (size < 2 || data[0] != 0xFF || data[1] != 0xD8) return true;  // not a JPEG
  auto byte = [&](long long i) -> int {
    return i < size ? data[i] : 0;
  };  // stb reads 0 past the end
  for (long long m = 2; m + 1 < size; ++m) {
    if (data[m] != 0xFF || data[m + 1] != 0xC4) continue;
    long long at = m + 2;
    long long left = (byte(at) << 8 | byte(at + 1)) - 2;
    at += 2;
    while (left > 0 && at < size) {
      int codes = 0;
      for (int i = 0; i < 16; ++i) codes += byte(at + 1 + i);
      if (codes > 256) return false;
      at += 17 + codes;
      left -= 17 + codes;
    }
  }
  return true;
}

bool imageInfo(const std::uint8_t* data, int size, int& width, int& height, int& channels) {
  if (!jpegHuffmanTablesFit(data, size)) {
    stbi__g_failure_reason = "corrupt JPEG: a Huffman table with more than 256 codes";
    return false;
  }
  return stbi_info_from_memory(data, size, &width, &height, &channels) != 0;
}

bool imageDecode(const std::uint8_t* data, int size, int width, int height,
                 std::vector<std::uint8_t>& rgba) {
  int w = 0, h = 0, channels = 0;
  if (!jpegHuffmanTablesFit(data, size)) {
    stbi__g_failure_reason = "corrupt JPEG: a Huffman table with more than 256 codes";
    return false;
  }
  stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &channels, 4);
  if (!pixels) return false;
  const bool ok = w == width && h == height;
  if (ok) {
    rgba.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
    std::memcpy(rgba.data(), pixels, rgba.size());
  } else {
    stbi__g_failure_reason = "the decoded size differs from the header's";
  }
  stbi_image_free(pixels);
  return ok;
}

const char* imageFailureReason() {
  const char* r = stbi_failure_reason();
  return r ? r : "unknown reason";
}

}  // namespace pelage::detail
