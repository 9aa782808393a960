#include "pelage/util/image.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "pelage/util/error.h"
#include "stb_image_impl.h"

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

}  // namespace pelage
