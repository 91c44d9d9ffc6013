// Byte offsets of JSON values and their line:column.
#include "scene/json_positions.h"

#include <gtest/gtest.h>

namespace haif {
namespace {

TEST(JsonPositions, LineAndColumnOfOffsets) {
  const std::string text = "{\n  \"a\": 1,\n\t\"b\": 2\n}";
  EXPECT_EQ(locationOfOffset(text, 0).line, 1);
  EXPECT_EQ(locationOfOffset(text, 0).column, 1);
  const TextLocation a = locationOfOffset(text, text.find("\"a\""));
  EXPECT_EQ(a.line, 2);
  EXPECT_EQ(a.column, 3);
  const TextLocation b = locationOfOffset(text, text.find("\"b\""));
  EXPECT_EQ(b.line, 3);
  EXPECT_EQ(b.column, 2);  // a tab is one column
  const TextLocation end = locationOfOffset(text, 10000);
  EXPECT_EQ(end.line, 4);
  EXPECT_EQ(end.column, 2);
}

TEST(JsonPositions, ColumnsCountCharactersNotBytes) {
  const std::string text = "{\"name\": \"\xC3\xA9t\xC3\xA9\", \"x\": 1}";  // "été"
  EXPECT_EQ(locationOfOffset(text, text.find("\"x\"")).column, 17);
}

TEST(JsonPositions, RecordsEveryValueAndKey) {
  const std::string text = R"({"bodies": [{"shape": {"type": "box"}}, 7], "a/b": {"~": true}, "esc\"aped": null})";
  JsonPositions pos;
  std::string dup;
  ASSERT_TRUE(pos.scan(text, dup));
  EXPECT_EQ(pos.valueOffset(""), 0u);
  EXPECT_EQ(pos.valueOffset("/bodies"), text.find('['));
  EXPECT_EQ(pos.valueOffset("/bodies/0/shape/type"), text.find("\"box\""));
  EXPECT_EQ(pos.keyOffset("/bodies/0/shape/type"), text.find("\"type\""));
  EXPECT_EQ(pos.valueOffset("/bodies/1"), text.find('7'));
  EXPECT_EQ(pos.keyOffset("/bodies/1"), std::string::npos);  // array elements have no key
  EXPECT_EQ(pos.valueOffset("/a~1b/~0"), text.find("true"));
  EXPECT_EQ(pos.valueOffset("/esc\"aped"), text.find("null"));
  EXPECT_EQ(pos.valueOffset("/missing"), std::string::npos);
  EXPECT_EQ(pos.nearestValueOffset("/bodies/0/shape/radius"), text.find("{\"type\""));
}

TEST(JsonPositions, DetectsDuplicateKeys) {
  JsonPositions pos;
  std::string dup;
  EXPECT_FALSE(pos.scan(R"({"a": {"x": 1, "y": 2, "x": 3}})", dup));
  EXPECT_EQ(dup, "/a/x");
  EXPECT_TRUE(pos.scan(R"({"a": {"x": 1}, "b": {"x": 1}})", dup));
}

TEST(JsonPositions, FindsOverflowingNumbersOutsideStrings) {
  const std::string text = R"({"s": "1e999", "v": [1, 2e400]})";
  EXPECT_EQ(findOverflowingNumber(text), text.find("2e400"));
  EXPECT_EQ(findOverflowingNumber(R"({"v": 1e300})"), std::string::npos);
}

TEST(JsonPositions, TooDeepNestingIsFoundWithoutRecursion) {
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  EXPECT_EQ(findTooDeepNesting(deep), size_t(kMaxJsonDepth));
  EXPECT_EQ(findTooDeepNesting("{\"a\": [[1]], \"b\": {}}", 3), std::string::npos);
  EXPECT_EQ(findTooDeepNesting("{\"a\": [[1]]}", 2), 7u);
  EXPECT_EQ(findTooDeepNesting("[\"[[[[\\\"[[[\"]", 1), std::string::npos) << "brackets in strings do not nest";
  // The scanner refuses it too (it would recurse 20,000 deep), and says where.
  JsonPositions pos;
  std::string dup;
  EXPECT_FALSE(pos.scan(deep, dup));
  EXPECT_TRUE(dup.empty());
  EXPECT_EQ(pos.tooDeepOffset(), size_t(kMaxJsonDepth));
  EXPECT_TRUE(pos.scan("[[[]]]", dup));
  EXPECT_EQ(pos.tooDeepOffset(), std::string::npos);
}

}  // namespace
}  // namespace haif
