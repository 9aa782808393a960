#include "pelage/util/json_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "pelage/util/error.h"
#include "support/files.h"

namespace pelage {
namespace {

using ::testing::HasSubstr;

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(JsonReader, MalformedTextNamesFileAndLine) {
  const std::string msg =
      errorOf([] { JsonReader::parseText("{\n\"a\": 1,\n\"b\": }\n", "x.json"); });
  EXPECT_THAT(msg, HasSubstr("x.json"));
  EXPECT_THAT(msg, HasSubstr("line 3"));
}

TEST(JsonReader, MissingFile) {
  EXPECT_THAT(errorOf([] { JsonReader::parseFile("/nonexistent/creature.json"); }),
              HasSubstr("/nonexistent/creature.json: cannot open"));
}

TEST(JsonReader, FieldPathsAndRanges) {
  const nlohmann::json j =
      nlohmann::json::parse(R"({"a": {"list": [1, 2, {"v": 7}]}, "s": "str"})");
  const JsonReader r(j, "f.json");
  EXPECT_EQ(r.at("a").at("list").size(), 3u);
  EXPECT_EQ(r.at("a").at("list").at(2).integer("v", 0, 10), 7);
  EXPECT_THAT(errorOf([&] { r.at("a").at("list").at(2).integer("v", 0, 5); }),
              HasSubstr("f.json: field 'a.list[2].v': value 7 is out of range [0, 5]"));
  EXPECT_THAT(errorOf([&] { r.at("a").at("missing"); }),
              HasSubstr("missing required field 'a.missing'"));
  EXPECT_THAT(errorOf([&] { r.number("s", 0, 1); }), HasSubstr("expected a number, found string"));
  EXPECT_THAT(errorOf([&] { r.rejectUnknown({"a"}); }), HasSubstr("unknown field 's'"));
  EXPECT_DOUBLE_EQ(r.number("absent", 0.25, 0.0, 1.0), 0.25);
}

TEST(JsonReader, RejectsNonFiniteAndWrongShapes) {
  EXPECT_THAT(errorOf([] { JsonReader::parseText(R"({"big": 1e400})", "f.json"); }),
              HasSubstr("f.json: malformed JSON ("));
  const nlohmann::json j = nlohmann::json::parse(R"({"big": 1e300, "v": [1, 2], "i": 2.5})");
  const JsonReader r(j, "f.json");
  EXPECT_THAT(errorOf([&] { r.number("big", -1e30, 1e30); }), HasSubstr("out of range"));
  EXPECT_THAT(errorOf([&] { r.vec3("v"); }), HasSubstr("array of 3 numbers"));
  EXPECT_THAT(errorOf([&] { r.integer("i", 0, 10); }), HasSubstr("expected an integer"));
}

TEST(ShortestDecimal, WritesFloatsAsTypedAndReadsThemBackExactly) {
  EXPECT_EQ(nlohmann::json(shortestDecimal(0.06f)).dump(), "0.06");
  EXPECT_EQ(nlohmann::json(shortestDecimal(0.3f)).dump(), "0.3");
  EXPECT_EQ(nlohmann::json(shortestDecimal(-1.5e-7f)).dump(), "-1.5e-07");
  EXPECT_EQ(nlohmann::json(static_cast<double>(0.06f)).dump(), "0.05999999865889549");
  EXPECT_TRUE(std::isinf(shortestDecimal(std::numeric_limits<float>::infinity())));
  EXPECT_TRUE(std::isnan(shortestDecimal(std::numeric_limits<float>::quiet_NaN())));
  // Random bit patterns (every finite float alike, subnormals and extremes included): through the
  // JSON text and back to float, bit for bit.
  std::uint64_t state = 12345;
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const auto f = std::bit_cast<float>(static_cast<std::uint32_t>(state >> 32));
    if (!std::isfinite(f)) continue;
    const std::string text = nlohmann::json(shortestDecimal(f)).dump();
    const auto back = static_cast<float>(nlohmann::json::parse(text).get<double>());
    ASSERT_EQ(std::bit_cast<std::uint32_t>(back), std::bit_cast<std::uint32_t>(f)) << text;
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

}  // namespace
}  // namespace pelage
