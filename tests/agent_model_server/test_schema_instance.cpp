// Instances generated from JSON Schemas satisfy them (bounds, enums, required properties, arrays,
// $ref, allOf, anyOf); streamed text pieces rebuild the text without cutting a UTF-8 character;
// response_format json_object / json_schema shaping.
#include <gtest/gtest.h>

#include "agent/model_server/completion_json.hpp"
#include "agent/model_server/reply_shaping.hpp"
#include "agent/model_server/schema_instance.hpp"
#include "agent/tool_catalog.hpp"

namespace {

namespace ms = a3::agent::model_server;
using nlohmann::json;

TEST(SchemaInstance, SatisfiesEverySchemaOfItsKind) {
  const std::vector<std::string> schemas = {
      R"({"type":"object","properties":{"a":{"type":"number","minimum":5,"maximum":6}},"required":["a"]})",
      R"({"type":"object","properties":{"a":{"type":"integer","exclusiveMinimum":5}},"required":["a"]})",
      R"({"type":"number","maximum":-3})",
      R"({"type":"integer","minimum":7,"multipleOf":5})",
      R"({"type":"string","minLength":12})",
      R"({"type":"string","enum":["north","south"]})",
      R"({"const":42})",
      R"({"type":["null","boolean"]})",
      R"({"type":"array","items":{"type":"object","properties":{"x":{"type":"number"}},"required":["x"]},"minItems":3})",
      R"({"anyOf":[{"type":"string","format":"date-time"},{"type":"number"}]})",
      R"({"allOf":[{"type":"object","properties":{"a":{"type":"string"}},"required":["a"]},
                  {"properties":{"b":{"type":"boolean"}},"required":["b"]}]})",
      R"({"type":"object","properties":{"p":{"$ref":"#/$defs/point"}},"required":["p"],
          "$defs":{"point":{"type":"object","properties":{"x":{"type":"number","minimum":1}},"required":["x"],
                            "additionalProperties":false}}})",
      R"({"type":"object","properties":{"p":{"$ref":"#/definitions/p"}},"required":["p"],
          "definitions":{"p":{"type":"integer","minimum":2}}})",
  };
  for (const auto& text : schemas) {
    const json schema = json::parse(text);
    const json value = ms::instance_of_schema(schema);
    EXPECT_EQ(ms::schema_problems(schema, value), "") << text << " -> " << value;
  }
  EXPECT_EQ(ms::instance_of_schema(json::parse(R"({"type":"string","enum":["north","south"]})")), "north");
  EXPECT_EQ(ms::instance_of_schema(json::parse(R"({"type":"array","items":{"type":"string"},"minItems":2})")).size(), 2u);
}

TEST(SchemaInstance, SatisfiesEveryFunctionOfTheToolCatalog) {
  for (const auto& f : a3::agent::ToolCatalog::builtin().functions()) {
    const json value = ms::instance_of_schema(f.input_schema);
    EXPECT_EQ(ms::schema_problems(f.input_schema, value), "") << f.name << " -> " << value;
  }
}

TEST(SchemaInstance, ProblemsNameTheField) {
  const json schema = json::parse(R"({"type":"object","properties":{"a":{"type":"number"}},"required":["a"]})");
  EXPECT_NE(ms::schema_problems(schema, json::object()), "");
  EXPECT_NE(ms::schema_problems(schema, {{"a", "x"}}).find("a"), std::string::npos);
}

TEST(TextPieces, RebuildTheTextInSeveralPiecesWithoutCuttingACharacter) {
  std::string text;
  for (int i = 0; i < 40; ++i) text += "vol à 120 m ✈ ";
  const auto pieces = ms::text_pieces(text);
  EXPECT_GE(pieces.size(), 3u);
  EXPECT_LE(pieces.size(), ms::kMaxPieces + 1);
  std::string joined;
  for (const auto& p : pieces) {
    EXPECT_NO_THROW(json(p).dump()) << "a piece cut a UTF-8 character";
    joined += p;
  }
  EXPECT_EQ(joined, text);
  EXPECT_TRUE(ms::text_pieces("").empty());
}

TEST(ReplyShaping, FormatsAndToolChoice) {
  ms::ResponseFormat object_format{"json_object", "", nullptr};
  EXPECT_EQ(json::parse(ms::content_for_format("hi", object_format)), json({{"text", "hi"}}));
  EXPECT_EQ(ms::content_for_format("[1]", object_format), json({{"text", "[1]"}}).dump());
  const json schema = json::parse(R"({"type":"object","properties":{"n":{"type":"integer","minimum":3}},"required":["n"]})");
  ms::ResponseFormat schema_format{"json_schema", "count", schema};
  EXPECT_EQ(ms::content_for_format(R"({"n":4})", schema_format), R"({"n":4})");
  EXPECT_EQ(json::parse(ms::content_for_format(R"({"n":1})", schema_format)), json({{"n", 3}}));

  ms::ChatOptions options;
  options.functions = {json{{"name", "a"}}, json{{"name", "b"}}};
  options.tool_choice = ms::ToolChoice::kAuto;
  options.parallel_tool_calls = false;
  ms::ResponderReply reply;
  reply.tool_calls = {{"", "a", "{}"}, {"", "b", "{}"}, {"", "unknown", "{}"}};
  ms::fit_tool_calls(reply, options, "7");
  ASSERT_EQ(reply.tool_calls.size(), 1u);  // parallel_tool_calls false
  EXPECT_EQ(reply.tool_calls[0].id, "call_7_0");
  EXPECT_EQ(reply.finish_reason, "tool_calls");

  ms::ResponderReply none;
  none.tool_calls = {{"", "a", "{}"}};
  options.tool_choice = ms::ToolChoice::kNone;
  ms::fit_tool_calls(none, options, "8");
  EXPECT_TRUE(none.tool_calls.empty());
  EXPECT_EQ(none.finish_reason, "stop");
}

// Fuzz finding (model_request): a tool schema is the client's; keywords of the wrong type or
// absurd size must not throw, allocate without bound, or overflow.
TEST(SchemaInstance, HostileKeywordsGiveAnInstanceWithoutThrowing) {
  const json schema = json::parse(R"({"type":"object","required":["s","n","a","m"],"properties":{
      "s":{"type":"string","minLength":"#/$defs","format":7},
      "n":{"type":"integer","minimum":5e37,"multipleOf":3},
      "a":{"type":"array","minItems":4000000000,"items":{"type":"string","minLength":99999999}},
      "m":{"allOf":[{"$ref":5},{"properties":[1]},{"required":"x"}],"properties":{},"required":[]}}})");
  json value;
  ASSERT_NO_THROW(value = ms::instance_of_schema(schema));
  EXPECT_EQ(value["s"], "a3rig");
  EXPECT_TRUE(value["n"].is_number_integer());
  EXPECT_LE(value["a"].size(), 64u);
  EXPECT_LE(value["a"][0].get<std::string>().size(), 4096u);
}

}  // namespace
