#include "pelage/util/path.h"

#include <gtest/gtest.h>

namespace pelage {
namespace {

TEST(Path, LowerExtension) {
  EXPECT_EQ(lowerExtension("Fox.GLB"), ".glb");
  EXPECT_EQ(lowerExtension("dir.d/monkey"), "");
  EXPECT_EQ(lowerExtension("a.tar.GZ"), ".gz");
}

TEST(Path, GlobMatches) {
  EXPECT_TRUE(globMatches("Eye*", "Eye_White"));
  EXPECT_TRUE(globMatches("Eye*", "eyes_black"));
  EXPECT_TRUE(globMatches("*Horn*", "Stag_Horns"));
  EXPECT_TRUE(globMatches("Hooves", "hooves"));
  EXPECT_FALSE(globMatches("Hooves", "Hooves2"));
  EXPECT_FALSE(globMatches("Main", "Main_Light"));
  EXPECT_TRUE(globMatches("*", "anything"));
  EXPECT_TRUE(globMatches("*", ""));
  EXPECT_FALSE(globMatches("", "a"));
  EXPECT_TRUE(globMatches("a*b*c", "aXXbYc"));
  EXPECT_FALSE(globMatches("a*b*c", "aXXbY"));
  EXPECT_TRUE(globMatches("b_Tail*", "b_Tail01_012"));
  EXPECT_FALSE(globMatches("b_Tail*", "b_Head_05"));
}

}  // namespace
}  // namespace pelage
