#include "pelage/anatomy/body.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pelage/util/error.h"

namespace pelage::anatomy {
namespace {

using ::testing::HasSubstr;

SegmentSpec spec(const std::string& name, const std::string& parent,
                 Eigen::Vector3f t = Eigen::Vector3f::Zero()) {
  SegmentSpec s;
  s.name = name;
  s.parent = parent;
  s.rest.translation = t;
  return s;
}

std::string errorOf(const std::vector<SegmentSpec>& specs) {
  try {
    makeBody(specs, "body.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Body, SortsParentsBeforeChildren) {
  const Body b = makeBody(
      {spec("hand", "arm"), spec("arm", "torso"), spec("torso", ""), spec("head", "torso")}, "x");
  ASSERT_EQ(b.size(), 4);
  checkBody(b);
  for (int i = 0; i < b.size(); ++i) EXPECT_LT(b.segments[static_cast<std::size_t>(i)].parent, i);
  EXPECT_EQ(b.segments[0].name, "torso");
  EXPECT_EQ(b.segments[static_cast<std::size_t>(b.find("hand"))].parent, b.find("arm"));
  EXPECT_EQ(b.find("tail"), -1);
}

TEST(Body, InverseBindUndoesRestWorld) {
  const Body b = makeBody(
      {spec("a", "", {1, 0, 0}), spec("b", "a", {0, 2, 0}), spec("c", "b", {0, 0, 3})}, "x");
  const auto world = restWorldTransforms(b);
  EXPECT_TRUE(world[2].translation().isApprox(Eigen::Vector3f(1, 2, 3)));
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE((world[static_cast<std::size_t>(i)] * b.inverseBind[static_cast<std::size_t>(i)])
                    .matrix()
                    .isIdentity(1e-6f));
}

TEST(Body, RejectsBadHierarchies) {
  EXPECT_THAT(errorOf({}), HasSubstr("no segments"));
  EXPECT_THAT(errorOf({spec("a", ""), spec("a", "")}), HasSubstr("duplicate segment name 'a'"));
  EXPECT_THAT(errorOf({spec("a", ""), spec("b", "ghost")}), HasSubstr("unknown parent 'ghost'"));
  EXPECT_THAT(errorOf({spec("r", ""), spec("a", "b"), spec("b", "c"), spec("c", "a")}),
              HasSubstr("cycle"));
  EXPECT_THAT(errorOf({spec("a", "a")}), HasSubstr("own parent"));
  auto nan = spec("n", "");
  nan.rest.translation.x() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THAT(errorOf({nan}), HasSubstr("non-finite"));
  auto zeroScale = spec("z", "");
  zeroScale.rest.scale = Eigen::Vector3f(1, 0, 1);
  EXPECT_THAT(errorOf({zeroScale}), HasSubstr("scale must be positive"));
}

}  // namespace
}  // namespace pelage::anatomy
