// One headless EGL context (with KHR_debug output) per test binary, and image statistics. The
// test creatures: support/models.h.
// GL tests never skip: without EGL/Mesa they fail with the context's error message.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>

#include "pelage/render/gl_context.h"
#include "pelage/render/gl_debug.h"
#include "pelage/render/image.h"
#include "pelage/scene/model.h"
#include "pelage/util/color.h"
#include "support/models.h"

namespace pelage::test {

struct GlEnvironment {
  std::unique_ptr<render::GlContext> context;
  std::unique_ptr<render::GlDebugLog> log;
  std::string error;  // why there is no context
};

inline GlEnvironment& glEnvironment() {
  static GlEnvironment env = [] {
    GlEnvironment e;
    try {
      render::ContextOptions o;
      o.debug = true;
      e.context = render::createHeadlessContext(o);
      e.log = std::make_unique<render::GlDebugLog>();
    } catch (const std::exception& ex) {
      e.error = ex.what();
    }
    return e;
  }();
  return env;
}

// Fixture: fails (not skips) when no GL context can be made; fails when the driver reported a GL
// error during the test.
class GlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    GlEnvironment& env = glEnvironment();
    ASSERT_TRUE(env.context) << "no headless OpenGL context: " << env.error;
    env.context->makeCurrent();
    env.log->clear();
  }
  void TearDown() override {
    GlEnvironment& env = glEnvironment();
    if (env.log) {
      EXPECT_EQ(env.log->errors(), "") << "OpenGL reported errors during the test";
    }
  }
};

// Frames are stored sRGB-encoded: the 0..255 value a linear colour channel is written as, as a
// real number (no rounding), and the linear value of a stored one.
inline float encoded255(float linear) {
  return linearToSrgb(linear) * 255.0f;
}
inline float decoded(std::uint8_t stored) {
  return srgbToLinear(stored / 255.0f);
}

// True when pixel (x, y) differs from `bg` (linear RGB) by more than `tol` (0..255) in any channel.
inline bool differsFrom(const render::Image& img, int x, int y, const float bg[3], int tol = 6) {
  const std::uint8_t* p = img.pixel(x, y);
  for (int c = 0; c < 3; ++c)
    if (std::abs(static_cast<int>(p[c]) - static_cast<int>(linearToSrgb8(bg[c]))) > tol)
      return true;
  return false;
}

// Fraction of pixels that differ from the background.
inline double coverage(const render::Image& img, const float bg[3]) {
  std::int64_t n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += differsFrom(img, x, y, bg) ? 1 : 0;
  return static_cast<double>(n) / (static_cast<double>(img.width) * img.height);
}

// Bit-identical images (or no channel more than `tolerance` codes apart); on a difference, how many
// pixels differ, by how much at most and the first one (not the pixel arrays, which would bury the
// log).
inline ::testing::AssertionResult sameImage(const render::Image& a, const render::Image& b,
                                            int tolerance = 0) {
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
    return ::testing::AssertionFailure() << "sizes differ: " << a.width << "x" << a.height << " vs "
                                         << b.width << "x" << b.height;
  std::int64_t differing = 0, first = -1;
  int maxDiff = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
    int d = 0;
    for (std::size_t c = 0; c < 4; ++c)
      d = std::max(d, std::abs(static_cast<int>(a.rgba[i + c]) - static_cast<int>(b.rgba[i + c])));
    if (d <= tolerance) continue;
    if (first < 0) first = static_cast<std::int64_t>(i / 4);
    ++differing;
    maxDiff = std::max(maxDiff, d);
  }
  if (differing == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << differing << " of " << a.rgba.size() / 4 << " pixels differ by more than " << tolerance
         << ", by up to " << maxDiff << "/255; the first at (" << first % a.width << ", "
         << first / a.width << ")";
}

}  // namespace pelage::test
