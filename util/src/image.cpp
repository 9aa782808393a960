#include "pelage/util/image.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "pelage/util/atomic_file.h"
#include "pelage/util/error.h"
#include "pelage/util/path.h"
#include "stb_image_impl.h"

#include <stb_image_write.h>

namespace pelage {

std::string describeImageSize(long long width, long long height) {
  char text[96];
  std::snprintf(text, sizeof text, "%lldx%lld (%.1f MiB as RGBA8)", width, height,
                static_cast<double>(width) * static_cast<double>(height) * 4.0 / (1024.0 * 1024.0));
  return text;
}

Rgba8Image decodeImage(const std::uint8_t* data, std::size_t size, const std::string& source,
                       const ImageLimits& limits) {
  if (size == 0 || data == nullptr) inputError(source, ": the image is empty");
  if (size > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    inputError(source, ": the image is ", size, " bytes; the limit is 2 GiB");
  const int length = static_cast<int>(size);
  int w = 0, h = 0, channels = 0;
  if (!detail::imageInfo(data, length, w, h, channels))
    inputError(source, ": not an image pelage can read (", detail::imageFailureReason(),
               "; accepted: PNG, JPEG)");
  if (w <= 0 || h <= 0) inputError(source, ": the image has no pixels (", w, "x", h, ")");
  const auto bytes = static_cast<unsigned long long>(w) * static_cast<unsigned long long>(h) * 4ull;
  if (w > limits.maxSide || h > limits.maxSide)
    inputError(source, ": the image is ", describeImageSize(w, h), "; the limit is ",
               limits.maxSide, " pixels per side");
  if (bytes > limits.maxBytes)
    inputError(source, ": the image is ", describeImageSize(w, h), "; the limit is ",
               limits.maxBytes >> 20, " MiB decoded");
  Rgba8Image image;
  if (!detail::imageDecode(data, length, w, h, image.rgba))
    inputError(source, ": the image is truncated or corrupt (", detail::imageFailureReason(), ")");
  image.width = w;
  image.height = h;
  image.fileChannels = channels;
  return image;
}

Rgba8Image readImageFile(const std::string& path, const ImageLimits& limits) {
  namespace fs = std::filesystem;
  requireExistingFile(path, "image file");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) inputError(path, ": not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) inputError(path, ": cannot read the file size (", ec.message(), ")");
  // A compressed image is rarely larger than its pixels; refuse files that cannot decode within
  // the limits anyway (PNG and JPEG headers come first, so this only bounds the read).
  if (size > limits.maxBytes + (std::size_t{64} << 20))
    inputError(path, ": the file is ", size, " bytes, more than an image within the limit of ",
               limits.maxBytes >> 20, " MiB decoded can take");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in) inputError(path, ": cannot open the image (unreadable)");
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (static_cast<std::size_t>(in.gcount()) != bytes.size()) inputError(path, ": read error");
  return decodeImage(bytes.data(), bytes.size(), path, limits);
}

namespace {
void appendBytes(void* ctx, void* data, int size) {
  auto* v = static_cast<std::vector<std::uint8_t>*>(ctx);
  const auto* p = static_cast<const std::uint8_t*>(data);
  v->insert(v->end(), p, p + size);
}

// The first three channels of `count` pixels of `channels` each, packed.
std::vector<std::uint8_t> rgbOf(const std::uint8_t* pixels, std::size_t count, int channels) {
  std::vector<std::uint8_t> rgb(count * 3);
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      rgb[3 * i + c] = pixels[static_cast<std::size_t>(channels) * i + c];
  return rgb;
}
}  // namespace

std::vector<std::uint8_t> encodePng(const std::uint8_t* pixels, int width, int height,
                                    int channels) {
  PELAGE_CHECK(width > 0 && height > 0 && (channels == 3 || channels == 4) && pixels, "image ",
               width, "x", height, "x", channels);
  std::vector<std::uint8_t> out;
  stbi_write_png_to_func(appendBytes, &out, width, height, channels, pixels, width * channels);
  PELAGE_CHECK(!out.empty(), "PNG encoding failed");
  return out;
}

void writeImageFile(const std::string& path, const std::uint8_t* pixels, int width, int height,
                    int channels) {
  const std::string ext = lowerExtension(path);
  std::vector<std::uint8_t> bytes;
  if (ext == ".png") {
    bytes = encodePng(pixels, width, height, channels);
  } else if (ext == ".jpg" || ext == ".jpeg") {
    PELAGE_CHECK(width > 0 && height > 0 && (channels == 3 || channels == 4) && pixels, "image ",
                 width, "x", height, "x", channels);
    const std::vector<std::uint8_t> rgb =
        rgbOf(pixels, static_cast<std::size_t>(width) * static_cast<std::size_t>(height), channels);
    stbi_write_jpg_to_func(appendBytes, &bytes, width, height, 3, rgb.data(), 95);
    PELAGE_CHECK(!bytes.empty(), "JPEG encoding failed");
  } else {
    inputError(path, ": unsupported image format '", excerpt(ext),
               "' (accepted: .png, .jpg, .jpeg)");
  }
  AtomicFileWriter w(path);
  w.write(bytes.data(), bytes.size());
  w.commit();
}

void writeImageFile(const std::string& path, const Rgba8Image& image) {
  if (image.fileChannels != 3) {
    writeImageFile(path, image.rgba.data(), image.width, image.height, 4);
    return;
  }
  const std::vector<std::uint8_t> rgb = rgbOf(image.rgba.data(), image.rgba.size() / 4, 4);
  writeImageFile(path, rgb.data(), image.width, image.height, 3);
}

}  // namespace pelage
