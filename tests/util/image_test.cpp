// Image reading (util/image.h): exact pixels of a tiny image, and every refusal naming the source
// and the problem before any pixel is decoded.
#include "pelage/util/image.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pelage/util/error.h"

namespace pelage {
namespace {

std::vector<std::uint8_t> bytes(const std::string& s) {
  return {s.begin(), s.end()};
}

// A binary PPM (P6) of w x h pixels with the given RGB bytes.
std::vector<std::uint8_t> ppm(int w, int h, const std::vector<std::uint8_t>& rgb) {
  std::vector<std::uint8_t> out =
      bytes("P6\n" + std::to_string(w) + " " + std::to_string(h) + "\n255\n");
  out.insert(out.end(), rgb.begin(), rgb.end());
  return out;
}

std::string messageOf(const std::vector<std::uint8_t>& data, const ImageLimits& limits = {}) {
  try {
    decodeImage(data.data(), data.size(), "test image", limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Image, DecodesEveryPixelToRgba8TopRowFirst) {
  const std::vector<std::uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
  const std::vector<std::uint8_t> data = ppm(2, 2, rgb);
  const Rgba8Image img = decodeImage(data.data(), data.size(), "test image");
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 2);
  EXPECT_EQ(img.fileChannels, 3);
  ASSERT_EQ(img.rgba.size(), 16u);
  for (int p = 0; p < 4; ++p) {
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(img.rgba[static_cast<std::size_t>(4 * p + c)],
                rgb[static_cast<std::size_t>(3 * p + c)]);
    EXPECT_EQ(img.rgba[static_cast<std::size_t>(4 * p + 3)], 255);
  }
}

TEST(Image, RefusesEmptyGarbageAndOversizedImagesNamingTheSource) {
  const std::string empty = messageOf({});
  EXPECT_NE(empty.find("test image"), std::string::npos) << empty;
  const std::string garbage = messageOf(bytes("this is not an image at all"));
  EXPECT_NE(garbage.find("test image"), std::string::npos) << garbage;
  // A header claiming 20000 x 2 pixels: refused from the header, the size in the message.
  const std::string wide = messageOf(ppm(20000, 2, {1, 2, 3}));
  EXPECT_NE(wide.find("20000"), std::string::npos) << wide;
  EXPECT_NE(wide.find("16384"), std::string::npos) << wide;
  // Within the sides but over a byte budget.
  ImageLimits small;
  small.maxBytes = 1024;
  const std::vector<std::uint8_t> big = ppm(32, 32, std::vector<std::uint8_t>(32 * 32 * 3, 7));
  const std::string budget = messageOf(big, small);
  EXPECT_NE(budget.find("32x32"), std::string::npos) << budget;
  EXPECT_EQ(messageOf(big), "");  // the default budget takes it
}

TEST(Image, MissingFileIsAMissingFileError) {
  EXPECT_THROW(readImageFile("/nonexistent-dir/none.png"), MissingFileError);
}

}  // namespace
}  // namespace pelage
