#include "pelage/anatomy/creature.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pelage/models/builtin.h"
#include "pelage/util/error.h"

namespace pelage::anatomy {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
  try {
    parseCreature(text, "c.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kMinimal = R"({
  "segments": [ { "name": "body", "joint": [0, 0, 0], "direction": [-2, 0, 0] },
                { "name": "tail", "parent": "body", "joint": [-1, 0, 0] } ],
  "shapes": [ { "segment": "body", "type": "ellipsoid", "center": [0, 0, 0], "radii": [1, 0.5, 0.5] },
              { "segment": "tail", "type": "capsule", "from": [-1, 0, 0], "to": [-2, 0, 0], "radius": 0.1 } ],
  "regions": [ { "name": "tip", "lengthScale": 0.5, "segments": ["tail"] } ]
})";

TEST(Creature, ParsesAMinimalCreature) {
  const Creature c = parseCreature(kMinimal, "c.json");
  ASSERT_EQ(c.body.size(), 2);
  EXPECT_TRUE(c.body.segments[1].rest.translation.isApprox(Eigen::Vector3f(-1, 0, 0)));
  EXPECT_TRUE(c.body.segments[0].direction.isApprox(Eigen::Vector3f(-1, 0, 0)));  // normalised
  ASSERT_EQ(c.shapes.size(), 2u);
  EXPECT_EQ(c.shapes[1].kind, Shape::Kind::Capsule);
  EXPECT_FLOAT_EQ(c.shapes[1].rTo, 0.1f);  // radiusTo defaults to radius
  ASSERT_EQ(c.regions.size(), 1u);
  EXPECT_EQ(c.regions[0].segments, std::vector<int>{1});
}

TEST(Creature, TheBuiltInMonkeyIsComplete) {
  const auto text = models::builtinFile("monkey.json");
  ASSERT_TRUE(text);
  const Creature c = parseCreature(std::string(*text), "built-in monkey");
  // A monkey: torso, head with face, two arms with hands, two legs with feet, a tail.
  for (const char* name : {"pelvis", "chest", "head", "l_upperarm", "l_hand", "r_hand", "l_thigh",
                           "l_foot", "r_foot", "tail1", "tail5"})
    EXPECT_GE(c.body.find(name), 0) << name;
  std::vector<std::string> regions;
  for (const auto& r : c.regions) regions.push_back(r.name);
  EXPECT_THAT(regions, ::testing::IsSupersetOf({"face", "hands", "feet"}));
  for (const auto& r : c.regions)
    EXPECT_LT(r.lengthScale, 1.0f) << r.name << " should have shorter fur";
  // Every segment owns at least one body shape (otherwise it could never hold skin).
  std::vector<int> owned(static_cast<std::size_t>(c.body.size()), 0);
  for (const auto& s : c.shapes) ++owned[static_cast<std::size_t>(s.segment)];
  for (int i = 0; i < c.body.size(); ++i)
    EXPECT_GT(owned[static_cast<std::size_t>(i)], 0)
        << c.body.segments[static_cast<std::size_t>(i)].name;
}

TEST(Creature, MalformedFilesGiveFieldPaths) {
  EXPECT_THAT(errorOf("{ \"segments\": [ }"), HasSubstr("malformed JSON near line 1"));
  EXPECT_THAT(errorOf("[1, 2]"), HasSubstr("must be a JSON object"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0, 0, NaN]}], "shapes": []})"),
              HasSubstr("malformed JSON"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0, 0, 1e999]}], "shapes": []})"),
              HasSubstr("number overflow"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0, 0, 1e9]}], "shapes": []})"),
              HasSubstr("field 'segments[0].joint'"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0, 0]}], "shapes": []})"),
              HasSubstr("field 'segments[0].joint': expected an array of 3 numbers"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "parent": "b", "joint": [0,0,0]},
                                       {"name": "b", "parent": "a", "joint": [0,0,0]}],
                        "shapes": [{"segment": "a", "type": "capsule", "from": [0,0,0], "to": [1,0,0], "radius": 1}]})"),
              HasSubstr("cycle"));
  EXPECT_THAT(
      errorOf(R"({"segments": [{"name": "a", "parent": "zz", "joint": [0,0,0]}], "shapes": []})"),
      HasSubstr("unknown parent 'zz'"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0,0,0]}],
                        "shapes": [{"segment": "a", "type": "ellipsoid", "center": [0,0,0], "radii": [1, 0, 1]}]})"),
              HasSubstr("zero-size shape"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0,0,0]}],
                        "shapes": [{"segment": "b", "type": "ellipsoid", "center": [0,0,0], "radii": [1, 1, 1]}]})"),
              HasSubstr("field 'shapes[0].segment': unknown segment 'b'"));
  EXPECT_THAT(errorOf(R"({"segments": [{"name": "a", "joint": [0,0,0]}],
                        "shapes": [{"segment": "a", "type": "cube", "center": [0,0,0]}]})"),
              HasSubstr("unknown shape type 'cube'"));
  EXPECT_THAT(
      errorOf(R"({"segments": [{"name": "a", "joint": [0,0,0], "stifness": 1}], "shapes": []})"),
      HasSubstr("unknown field 'segments[0].stifness'"));
  EXPECT_THAT(
      errorOf(R"({"furLength": -1, "segments": [{"name": "a", "joint": [0,0,0]}], "shapes": []})"),
      HasSubstr("out of range [0, 10]"));
}

}  // namespace
}  // namespace pelage::anatomy
