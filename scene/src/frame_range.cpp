#include "pelage/scene/frame_range.h"

#include <charconv>
#include <cstdio>
#include <string>

#include "pelage/util/error.h"

namespace pelage::scene {
namespace {
bool parseInt(std::string_view s, int& out) {
  if (s.empty()) return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}
}  // namespace

FrameRange parseFrameRange(std::string_view text, std::string_view field) {
  FrameRange r;
  const std::size_t colon = text.find(':');
  const bool parsed =
      colon == std::string_view::npos
          ? parseInt(text, r.first) && ((r.last = r.first), true)
          : parseInt(text.substr(0, colon), r.first) && parseInt(text.substr(colon + 1), r.last);
  if (!parsed)
    fieldError(std::string(field), "'", text,
               "' is not a frame range FIRST:LAST (inclusive frame numbers, e.g. 0:99) or a single "
               "frame number");
  if (r.first < 0 || r.last > kMaxFrameNumber || r.first > r.last)
    fieldError(std::string(field), r.first, ":", r.last,
               " is out of range: need 0 <= FIRST <= LAST <= ", kMaxFrameNumber);
  return r;
}

int frameOfFileName(std::string_view name, std::string_view extension) {
  constexpr std::string_view kPrefix = "frame_";
  if (name.size() <= kPrefix.size() + extension.size() ||
      name.substr(0, kPrefix.size()) != kPrefix ||
      name.substr(name.size() - extension.size()) != extension)
    return -1;
  int frame = -1;
  const std::string_view digits =
      name.substr(kPrefix.size(), name.size() - kPrefix.size() - extension.size());
  return parseInt(digits, frame) && frame >= 0 ? frame : -1;
}

std::string frameFileName(int frame, std::string_view extension) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%05d", frame);
  return std::string(buf) + std::string(extension);
}

}  // namespace pelage::scene
