// The three calls pelage makes into stb_image (compiled in stb_image_impl.cpp with internal
// linkage, so it cannot clash with another copy of stb in the program).
#pragma once

#include <cstdint>
#include <vector>

namespace pelage::detail {

// Width, height and channels from the header; false when the format is not recognised.
bool imageInfo(const std::uint8_t* data, int size, int& width, int& height, int& channels);
// Decodes to RGBA8 (16-bit channels are reduced to 8); false on failure. `width`, `height`: the
// header's, checked against the decoded size.
bool imageDecode(const std::uint8_t* data, int size, int width, int height,
                 std::vector<std::uint8_t>& rgba);
// stb_image's reason for the last failure on this thread.
const char* imageFailureReason();

}  // namespace pelage::detail
