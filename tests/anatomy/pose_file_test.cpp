#include "pelage/anatomy/pose_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "pelage/util/error.h"

namespace pelage::anatomy {
namespace {

Body twoSegments() {
  std::vector<SegmentSpec> s(2);
  s[0].name = "a";
  s[1].name = "b";
  s[1].parent = "a";
  s[1].rest.translation = {1, 0, 0};
  return makeBody(s, "x");
}

TEST(PoseFile, RotatesAndTranslatesNamedSegments) {
  const Body b = twoSegments();
  const Pose p = parsePose(b, R"({"pose": {"b": {"rotate": {"axis": [0, 0, 2], "degrees": 90}},
                                          "a": {"translate": [0, 0, 1]}}})",
                           "p.json");
  EXPECT_TRUE(p.local[0].translation.isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(
      (p.local[1].rotation * Eigen::Vector3f::UnitX()).isApprox(Eigen::Vector3f::UnitY(), 1e-6f));
  EXPECT_TRUE(p.local[1].translation.isApprox(Eigen::Vector3f(1, 0, 0)));
}

TEST(PoseFile, Errors) {
  const Body b = twoSegments();
  auto err = [&](const std::string& t) {
    try {
      parsePose(b, t, "p.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_THAT(err(R"({"pose": {"zz": {}}})"), ::testing::HasSubstr("unknown segment 'zz'"));
  EXPECT_THAT(err(R"({"pose": {"a": {"rotate": {"axis": [0, 0, 0], "degrees": 9}}}})"),
              ::testing::HasSubstr("axis must be non-zero"));
  EXPECT_THAT(err(R"({"pose": {"a": {"spin": 1}}})"),
              ::testing::HasSubstr("unknown field 'pose.a.spin'"));
  EXPECT_THROW(loadPose(b, "/nonexistent/pose.json"), InputError);
}

}  // namespace
}  // namespace pelage::anatomy
