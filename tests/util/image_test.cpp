// Image reading (util/image.h): exact pixels of a tiny image, and every refusal naming the source
// and the problem before any pixel is decoded.
#include "pelage/util/image.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "pelage/util/error.h"
#include "support/files.h"

namespace pelage {
namespace {

std::vector<std::uint8_t> bytes(const std::string& s) {
  return {s.begin(), s.end()};
}

// A PNG of w x h RGB pixels.
std::vector<std::uint8_t> png(int w, int h, const std::vector<std::uint8_t>& rgb) {
  return encodePng(rgb.data(), w, h, 3);
}

// A PNG signature and IHDR chunk claiming w x h RGB pixels, and nothing else (stb_image reads the
// size from the header without checking the chunk's CRC).
std::vector<std::uint8_t> pngHeader(std::uint32_t w, std::uint32_t h) {
  std::vector<std::uint8_t> out = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A,
                                   0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (const std::uint32_t v : {w, h})
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
  out.insert(out.end(), {8, 2, 0, 0, 0, 0, 0, 0, 0});  // 8 bits, RGB; CRC 0
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
  const std::vector<std::uint8_t> data = png(2, 2, rgb);
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
  const std::string wide = messageOf(pngHeader(20000, 2));
  EXPECT_NE(wide.find("20000"), std::string::npos) << wide;
  EXPECT_NE(wide.find("16384"), std::string::npos) << wide;
  // Within the sides but over a byte budget.
  ImageLimits small;
  small.maxBytes = 1024;
  const std::vector<std::uint8_t> big = png(32, 32, std::vector<std::uint8_t>(32 * 32 * 3, 7));
  const std::string budget = messageOf(big, small);
  EXPECT_NE(budget.find("32x32"), std::string::npos) << budget;
  EXPECT_EQ(messageOf(big), "");  // the default budget takes it
}

// A JPEG whose Huffman table (DHT) claims 16 x 17 = 272 codes: stb_image 2.27 would write past its
// 256-entry tables (found by fuzz_image); refused before stb reads it, naming the problem.
TEST(Image, RefusesAJpegHuffmanTableOfMoreThan256Codes) {
  std::vector<std::uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xC4};
  const int length = 2 + 17 + 272;
  jpeg.push_back(static_cast<std::uint8_t>(length >> 8));
  jpeg.push_back(static_cast<std::uint8_t>(length & 0xFF));
  jpeg.push_back(0x00);  // class 0 (DC), table 0
  for (int i = 0; i < 16; ++i) jpeg.push_back(17);
  jpeg.insert(jpeg.end(), 272, 0x01);
  jpeg.insert(jpeg.end(), {0xFF, 0xD9});
  const std::string message = messageOf(jpeg);
  EXPECT_NE(message.find("test image"), std::string::npos) << message;
  EXPECT_NE(message.find("more than 256 codes"), std::string::npos) << message;
  // Formats not compiled in are refused with the accepted list (a BMP header).
  const std::string bmp = messageOf(bytes("BM\x3e\0\0\0\0\0\0\0\x36\0\0\0(\0\0\0"));
  EXPECT_NE(bmp.find("accepted: PNG, JPEG)"), std::string::npos) << bmp;
  // Nor binary PPM (stb_image 2.27's 16-bit PNM reader overflows its buffer).
  const std::string ppm = messageOf(bytes("P6\n2 1\n255\n\x01\x02\x03\x04\x05\x06"));
  EXPECT_NE(ppm.find("accepted: PNG, JPEG)"), std::string::npos) << ppm;
}

TEST(Image, MissingFileIsAMissingFileError) {
  EXPECT_THROW(readImageFile("/nonexistent-dir/none.png"), MissingFileError);
}

// The one image writer: PNG of 3 or 4 channels reads back pixel for pixel; JPEG decodes to the
// size; another extension or an unwritable place is an InputError naming the file, and no file.
TEST(Image, WritesPngAndJpegThatReadBack) {
  test::TempDir dir;
  const std::vector<std::uint8_t> rgb = {255, 0,  0,  0,  255, 0,  0,  0,  255,
                                         10,  20, 30, 40, 50,  60, 70, 80, 90};
  const std::string a = dir.file("A.PNG");
  writeImageFile(a, rgb.data(), 3, 2, 3);
  const Rgba8Image back = readImageFile(a);
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t c = 0; c < 3; ++c) EXPECT_EQ(back.rgba[4 * i + c], rgb[3 * i + c]) << i;
    EXPECT_EQ(back.rgba[4 * i + 3], 255);
  }
  EXPECT_EQ(back.pixel(2, 1)[0], 70);
  const std::vector<std::uint8_t> rgba = {1, 2, 3, 0, 4, 5, 6, 128};
  writeImageFile(dir.file("b.png"), rgba.data(), 2, 1, 4);
  EXPECT_EQ(readImageFile(dir.file("b.png")).rgba, rgba);
  writeImageFile(dir.file("c.jpg"), rgba.data(), 2, 1, 4);
  EXPECT_EQ(readImageFile(dir.file("c.jpg")).width, 2);
  EXPECT_THROW(writeImageFile(dir.file("d.bmp"), rgb.data(), 3, 2, 3), InputError);
  EXPECT_THROW(writeImageFile(dir.file("no/such/e.png"), rgb.data(), 3, 2, 3), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir.file("d.bmp")));
}

TEST(Image, AnImageIsWrittenWithItsFileChannels) {
  test::TempDir dir;
  Rgba8Image img;
  img.width = 2;
  img.height = 1;
  img.rgba = {1, 2, 3, 40, 4, 5, 6, 128};
  img.fileChannels = 3;  // RGB: the alpha is dropped, the colours kept
  writeImageFile(dir.file("rgb.png"), img);
  const Rgba8Image rgb = readImageFile(dir.file("rgb.png"));
  EXPECT_EQ(rgb.fileChannels, 3);
  EXPECT_EQ(rgb.rgba, (std::vector<std::uint8_t>{1, 2, 3, 255, 4, 5, 6, 255}));
  const std::vector<std::uint8_t> bytes3 =
      encodePng(std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6}.data(), 2, 1, 3);
  EXPECT_EQ(test::readText(dir.file("rgb.png")), std::string(bytes3.begin(), bytes3.end()));
  img.fileChannels = 4;
  writeImageFile(dir.file("rgba.png"), img);
  EXPECT_EQ(readImageFile(dir.file("rgba.png")).rgba, img.rgba);
  EXPECT_EQ(readImageFile(dir.file("rgba.png")).fileChannels, 4);
}

}  // namespace
}  // namespace pelage
