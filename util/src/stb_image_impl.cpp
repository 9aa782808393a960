// stb_image (Debian's libstb-dev header), compiled here with internal linkage (STB_IMAGE_STATIC)
// and without stdio: pelage hands it bytes it has read itself. Third-party code: built without
// pelage's warnings (util/CMakeLists.txt).
#define STB_IMAGE_STATIC
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

bool imageInfo(const std::uint8_t* data, int size, int& width, int& height, int& channels) {
  return stbi_info_from_memory(data, size, &width, &height, &channels) != 0;
}

bool imageDecode(const std::uint8_t* data, int size, int width, int height,
                 std::vector<std::uint8_t>& rgba) {
  int w = 0, h = 0, channels = 0;
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
