// Bounded JSON parsing (common/json_text): depth at and beyond the limit, deep inputs that
// would overflow a recursive parser, duplicate keys with their path, invalid UTF-8 with its
// byte offset, the size limit, the ordered variant, and dumping text that is not UTF-8.
#include <gtest/gtest.h>

#include <string>

#include "common/json_text.hpp"

namespace a3::common {
namespace {

std::string nested_arrays(int depth) { return std::string(depth, '[') + std::string(depth, ']'); }

std::string nested_objects(int depth) {
  std::string text;
  for (int i = 0; i < depth; ++i) text += "{\"a\":";
  text += "1";
  return text + std::string(depth, '}');
}

// The one-line problem try_parse_json_text reports, or "" if the text was accepted.
std::string problem_with(const std::string& text, const JsonLimits& limits = {}) {
  std::string error;
  const auto value = try_parse_json_text(text, &error, limits);
  EXPECT_EQ(value.has_value(), error.empty()) << error;
  return error;
}

TEST(JsonText, DepthAtTheLimitIsAcceptedOneMoreIsRefusedWithItsPath) {
  JsonLimits limits;
  limits.max_depth = 4;
  EXPECT_EQ(problem_with(nested_arrays(4), limits), "");
  EXPECT_EQ(problem_with(nested_objects(4), limits), "");
  EXPECT_EQ(problem_with(nested_arrays(5), limits), "/0/0/0/0: nested deeper than the limit of 4 arrays/objects");
  EXPECT_EQ(problem_with(nested_objects(5), limits), "/a/a/a/a: nested deeper than the limit of 4 arrays/objects");
  EXPECT_EQ(problem_with(R"({"x": [1, 2, {"y": [[]]}]})", limits),
            "/x/2/y/0: nested deeper than the limit of 4 arrays/objects");
}

TEST(JsonText, DefaultDepthLimitIs128) {
  EXPECT_EQ(problem_with(nested_arrays(128)), "");
  EXPECT_NE(problem_with(nested_arrays(129)).find("limit of 128"), std::string::npos);
}

TEST(JsonText, HugeNestingIsRefusedWithoutOverflowingTheStack) {
  EXPECT_NE(problem_with(nested_arrays(200000)).find("nested deeper than the limit of 128"), std::string::npos);
  EXPECT_NE(problem_with(nested_objects(200000)).find("nested deeper than the limit of 128"), std::string::npos);
  // An unterminated run of '[' (the 131 KB file of the finding) as well.
  EXPECT_NE(problem_with(std::string(131072, '[')).find("limit of 128"), std::string::npos);
}

TEST(JsonText, DeepValueWithinAGenerousLimitIsBuiltAndDestroyedWithoutRecursionTrouble) {
  JsonLimits limits;
  limits.max_depth = 100000;
  std::string error;
  const auto value = try_parse_json_text(nested_arrays(100000), &error, limits);
  ASSERT_TRUE(value.has_value()) << error;
  const nlohmann::json* inner = &*value;
  int depth = 0;
  while (inner->is_array() && !inner->empty()) {
    inner = &(*inner)[0];
    ++depth;
  }
  EXPECT_EQ(depth, 99999);
}

TEST(JsonText, DuplicateKeysAreRefusedWithTheObjectsPath) {
  EXPECT_EQ(problem_with(R"({"success": false, "success": true})"), "/: duplicate key \"success\"");
  EXPECT_EQ(problem_with(R"({"dialogue": [0, 1, 2, {"success": 1, "x": 2, "success": 3}]})"),
            "/dialogue/3: duplicate key \"success\"");
  EXPECT_EQ(problem_with(R"({"a/b": {"m~n": {"k": 1, "k": 1}}})"), "/a~1b/m~0n: duplicate key \"k\"");
  // The same key in sibling objects is not a duplicate.
  EXPECT_EQ(problem_with(R"([{"k": 1}, {"k": 2}])"), "");
}

TEST(JsonText, OrderedVariantKeepsOrderAndRefusesDuplicates) {
  const auto value = parse_ordered_json_text(R"({"z": 1, "a": {"y": [1, 2]}, "m": null})", "t.json");
  EXPECT_EQ(value.dump(), R"({"z":1,"a":{"y":[1,2]},"m":null})");
  try {
    parse_ordered_json_text(R"({"z": 1, "a": 2, "z": 3})", "t.json");
    ADD_FAILURE() << "duplicate accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "t.json: /: duplicate key \"z\"");
  }
}

TEST(JsonText, InvalidUtf8IsRefusedWithItsByteOffset) {
  EXPECT_EQ(problem_with("{\"a\": \"ok\xff\"}"), "byte 9: invalid UTF-8 in a string");
  EXPECT_EQ(problem_with("[\"\xc3\"]"), "byte 3: invalid UTF-8 in a string");  // truncated sequence
  EXPECT_EQ(problem_with("{\"k\xfe\": 1}"), "byte 3: invalid UTF-8 in a string");  // in a key
}

TEST(JsonText, OverlongAndSurrogateEncodingsAreInvalidUtf8) {
  EXPECT_EQ(problem_with("[\"\xc0\xaf\"]"), "byte 2: invalid UTF-8 in a string");          // overlong '/'
  EXPECT_EQ(problem_with("[\"\xe0\x80\xaf\"]"), "byte 3: invalid UTF-8 in a string");      // overlong 3-byte
  EXPECT_EQ(problem_with("[\"\xed\xa0\x80\"]"), "byte 3: invalid UTF-8 in a string");      // U+D800 as UTF-8
  EXPECT_EQ(problem_with("[\"\xf4\x90\x80\x80\"]"), "byte 3: invalid UTF-8 in a string");  // above U+10FFFF
  // A lone escaped surrogate is refused as well (it has no UTF-8 form).
  EXPECT_NE(problem_with(R"(["\ud800"])").find("surrogate"), std::string::npos);
  // Valid multi-byte text is accepted.
  EXPECT_EQ(problem_with("[\"h\xc3\xb6he \xe2\x82\xac \xf0\x9f\x9a\x81\"]"), "");
}

TEST(JsonText, SyntaxErrorsAreOneLineWithByteOffsetAndNoRawLibraryPrefix) {
  const std::string problem = problem_with("{\"a\": 1,\n \"b\": }");
  EXPECT_EQ(problem.rfind("byte 15: not valid JSON: ", 0), 0u) << problem;
  EXPECT_EQ(problem.find('\n'), std::string::npos);
  EXPECT_EQ(problem.find("[json.exception"), std::string::npos);
  EXPECT_NE(problem_with("").find("not valid JSON"), std::string::npos);
  EXPECT_NE(problem_with("[1] x").find("not valid JSON"), std::string::npos);  // trailing text
}

TEST(JsonText, TextOverTheSizeLimitIsRefusedUnread) {
  JsonLimits limits;
  limits.max_bytes = 10;
  EXPECT_EQ(problem_with("[1,2,3,4,5]", limits), "byte 10: text is 11 bytes, more than the limit of 10");
  EXPECT_EQ(problem_with("[1,2,3,45]", limits), "");
}

TEST(JsonText, ParseJsonTextPrefixesWhere) {
  try {
    parse_json_text("[1, 2", "reply of turn 3");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("reply of turn 3: byte ", 0), 0u) << e.what();
  }
  EXPECT_EQ(parse_json_text(R"({"a": [1, 2.5, "x", true, null]})", "t").dump(), R"({"a":[1,2.5,"x",true,null]})");
}

TEST(JsonText, DumpReplacesInvalidUtf8InsteadOfThrowing) {
  nlohmann::json j = {{"file", std::string("ep\xff.json")}};
  EXPECT_THROW(j.dump(), nlohmann::json::type_error);
  EXPECT_EQ(dump_json_text(j), "{\"file\":\"ep\xef\xbf\xbd.json\"}");
  nlohmann::ordered_json o = {{"file", std::string("a\xc3")}};
  EXPECT_EQ(dump_json_text(o, 2), "{\n  \"file\": \"a\xef\xbf\xbd\"\n}");
}

}  // namespace
}  // namespace a3::common
