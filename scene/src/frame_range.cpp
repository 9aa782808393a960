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

void validateFrameRange(const FrameRange& r, std::string_view field) {
  if (r.first < 0 || r.last > kMaxFrameNumber || r.first > r.last)
    fieldError(std::string(field), r.first, ":", r.last,
               " is out of range: need 0 <= FIRST <= LAST <= ", kMaxFrameNumber);
  if (r.step < 1 || r.step > kMaxFrameNumber)
    fieldError(std::string(field), "step ", r.step, " is out of range [1, ", kMaxFrameNumber, "]");
  if ((r.last - r.first) % r.step != 0)
    fieldError(std::string(field), r.first, ":", r.last, ":", r.step, ": the last frame ", r.last,
               " is not on the step");
}

FrameRange parseFrameRange(std::string_view text, std::string_view field) {
  FrameRange r;
  const std::size_t colon = text.find(':');
  const std::size_t colon2 =
      colon == std::string_view::npos ? std::string_view::npos : text.find(':', colon + 1);
  bool parsed = false;
  if (colon == std::string_view::npos) {
    parsed = parseInt(text, r.first);
    r.last = r.first;
  } else if (colon2 == std::string_view::npos) {
    parsed = parseInt(text.substr(0, colon), r.first) && parseInt(text.substr(colon + 1), r.last);
  } else {
    parsed = parseInt(text.substr(0, colon), r.first) &&
             parseInt(text.substr(colon + 1, colon2 - colon - 1), r.last) &&
             parseInt(text.substr(colon2 + 1), r.step);
  }
  if (!parsed)
    fieldError(std::string(field), "'", excerpt(text),
               "' is not a frame range FIRST:LAST (inclusive frame numbers, e.g. 0:99), "
               "FIRST:LAST:STEP or a single frame number");
  if (r.step >= 1 && r.last >= r.first) r.last -= (r.last - r.first) % r.step;
  validateFrameRange(r, field);
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
