// The compiled schema (eval/compiled_schema.hpp) against valijson: what it refuses to compile,
// valijson's verdicts on the cases that decide episodes (and its quirks), and the same verdict on
// the fuzz corpus of the episode target. The public episodes and edits of them are compared in
// test_compiled_schema_corpus.cpp, the JSON-Schema-Test-Suite cases in test_schema_suite.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "eval/json_shape.hpp"
#include "tests/eval/schema_agreement.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace a3::eval;
using namespace a3::eval::testing;

std::string refusal_of(const std::string& schema) {
  try {
    CompiledSchema compiled_schema(schema, "test-schema");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool valid_json(const CompiledSchema& schema, const char* json) {
  rapidjson::Document d;
  d.Parse(json);
  if (d.HasParseError()) throw std::invalid_argument(std::string("test JSON: ") + json);
  return schema.is_valid(d);
}

// ---- Construction ---------------------------------------------------------------------------

TEST(CompiledSchema, CompilesTheEpisodeSchemaAndScoringUsesIt) {
  EXPECT_GT(compiled_schema().subschema_count(), 20u);
  const JsonSchemaValidator validator(episode_schema_json(), kEpisodeSchemaName);
  EXPECT_TRUE(validator.uses_compiled_schema()) << validator.compiled_schema_refusal();
  EXPECT_NO_THROW(JsonSchemaValidator(episode_schema_json(), kEpisodeSchemaName, SchemaEngine::kCompiled));
  EXPECT_FALSE(valijson_validator().uses_compiled_schema());
}

TEST(CompiledSchema, RefusesAKeywordItDoesNotSupportNamingItAndWhere) {
  const std::string why = refusal_of(R"({"properties": {"name": {"type": "string", "pattern": "^a"}}})");
  EXPECT_NE(why.find("test-schema"), std::string::npos) << why;
  EXPECT_NE(why.find("/properties/name/pattern"), std::string::npos) << why;
  EXPECT_NE(why.find("\"pattern\""), std::string::npos) << why;
}

TEST(CompiledSchema, RefusesFormsWhoseMeaningDiffersBetweenDraftsOrFromValijson) {
  EXPECT_NE(refusal_of(R"({"$ref": "#/$defs/a", "type": "object", "$defs": {"a": {}}})").find("beside $ref"),
            std::string::npos);
  EXPECT_NE(refusal_of(R"({"multipleOf": 1})").find("fraction"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"items": [{"type": "string"}]})").find("tuple"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"$ref": "http://example.com/s.json"})").find("local"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"$ref": "#/$defs/missing", "$defs": {}})").find("points to nothing"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"$ref": "#"})").find("cycle"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"if": {"$ref": "#"}})").find("if/then/else"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"type": "any"})").find("type"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"minItems": 1.5})").find("non-negative integer"), std::string::npos);
  EXPECT_NE(refusal_of(R"({"type": )").find("not valid JSON"), std::string::npos);
  EXPECT_EQ(refusal_of(R"({"$defs": {"a": {"type": "string"}}, "items": {"$ref": "#/$defs/a"}})"), "");
}

TEST(CompiledSchema, FallsBackToValijsonForASchemaItCannotCompile) {
  const std::string schema = R"({"type": "string", "maxLength": 2})";
  const JsonSchemaValidator validator(schema, "short-string");
  EXPECT_FALSE(validator.uses_compiled_schema());
  EXPECT_NE(validator.compiled_schema_refusal().find("maxLength"), std::string::npos);
  rapidjson::Document d;
  d.Parse(R"("abc")");
  EXPECT_FALSE(validator.is_valid(d));
  EXPECT_THROW(JsonSchemaValidator(schema, "short-string", SchemaEngine::kCompiled), std::invalid_argument);
}

// The verdicts that decide episodes, and valijson's quirks it must share.
TEST(CompiledSchema, GivesValijsonsVerdictsOnTheCasesThatMatter) {
  const CompiledSchema integer(R"({"type": "number", "multipleOf": 1.0, "minimum": 1})", "integer");
  EXPECT_TRUE(valid_json(integer, "8"));
  EXPECT_TRUE(valid_json(integer, "8.0"));
  EXPECT_FALSE(valid_json(integer, "1.5"));
  EXPECT_FALSE(valid_json(integer, "0"));
  EXPECT_FALSE(valid_json(integer, "\"8\""));
  // A uint64 above INT64_MAX is read by valijson through int64_t: negative, below the minimum.
  EXPECT_FALSE(valid_json(integer, "18446744073709551615"));
  const CompiledSchema flag(R"({"const": true})", "flag");
  EXPECT_TRUE(valid_json(flag, "true"));
  EXPECT_FALSE(valid_json(flag, "1"));
  const CompiledSchema closed(R"({"properties": {"a": {}}, "additionalProperties": false})", "closed");
  EXPECT_TRUE(valid_json(closed, R"({"a": 1})"));
  EXPECT_FALSE(valid_json(closed, R"({"a": 1, "b": 2})"));
  EXPECT_FALSE(valid_json(closed, R"({"a": 1, "a": 2})"));  // valijson counts distinct names
  // multipleOf reads strings that are numbers (valijson does not check the type there).
  const CompiledSchema halves(R"({"multipleOf": 0.5})", "halves");
  EXPECT_FALSE(valid_json(halves, "\"0.3\""));
  EXPECT_TRUE(valid_json(halves, "\"x\""));
}

// Properties are looked up in the schema's order, one comparison each while the document lists
// them in that order: members in another order, absent, unknown or repeated before or after the
// others must still give valijson's verdict (it checks the first member of a name).
TEST(CompiledSchema, LooksPropertiesUpAsValijsonWhateverTheMembersOrder) {
  const char* schema = R"({"properties": {"a": {"type": "number"}, "b": {"type": "string"},
                                          "c": {"type": "boolean"}}, "required": ["c"]})";
  const CompiledSchema compiled(schema, "ordered");
  const JsonSchemaValidator reference(schema, "ordered", SchemaEngine::kValijson);
  const std::vector<std::pair<const char*, bool>> cases = {
      {R"({"a": 1, "b": "x", "c": true})", true},
      {R"({"c": true, "b": "x", "a": 1})", true},
      {R"({"a": 1, "c": true})", true},
      {R"({"x": 0, "a": 1, "b": "x", "c": true})", true},
      {R"({"a": 1, "b": 2, "c": true})", false},
      {R"({"b": "x", "a": "1", "c": true})", false},
      {R"({"a": 1, "b": "x"})", false},
      {R"({"a": 1, "b": "x", "c": true, "b": 2})", true},
      {R"({"a": 1, "b": 2, "c": true, "b": "x"})", false},
      {R"({"b": "x", "a": 1, "b": 2, "c": true})", true},
      {R"({"b": 2, "a": 1, "b": "x", "c": true})", false},
      {R"({"a": "1", "a": 1, "b": "x", "c": true})", false},
      {R"({"a": 1, "a": "1", "b": "x", "c": true})", true},
  };
  for (const auto& [json, valid] : cases) {
    rapidjson::Document document;
    document.Parse(json);
    ASSERT_FALSE(document.HasParseError()) << json;
    EXPECT_EQ(reference.is_valid(document), valid) << json;
    EXPECT_EQ(compiled.is_valid(document), valid) << json;
  }
}

// ---- Differential: the fuzz corpus ---------------------------------------------------------

// The reader never validates a document nested deeper than kMaxEpisodeDepth.
bool too_deep(const rapidjson::Document& document) {
  JsonShapeChecker shape;
  Violations violations;
  shape.check(document, violations);
  for (const Violation& v : violations) {
    if (v.rule == "json-depth") return true;
  }
  return false;
}

// The episode target's seeds and regression inputs, and the corpus the fuzzer grew in
// build-fuzz/ (scripts/fuzz.sh) when there is one.
TEST(CompiledSchemaAgreement, TheEpisodeFuzzCorpus) {
  const fs::path source = a3::test::source_dir();
  std::vector<fs::path> folders = {source / "fuzz/corpus/episode", source / "tests/data/fuzz/episode"};
  const char* env = std::getenv("A3_EPISODE_FUZZ_CORPUS");
  const fs::path grown = env != nullptr && *env != '\0' ? fs::path(env) : source / "build-fuzz/corpus/episode";
  const bool have_grown = fs::is_directory(grown);
  if (have_grown) folders.push_back(grown);
  Agreement agreement;
  int unparsable = 0;
  for (const fs::path& folder : folders) {
    ASSERT_TRUE(fs::is_directory(folder)) << folder;
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (!entry.is_regular_file()) continue;
      rapidjson::Document document;
      if (!parse_like_the_reader(read_file(entry.path()), document) || too_deep(document)) {
        ++unparsable;
        continue;
      }
      agreement.compare(document, entry.path().string());
    }
  }
  std::cout << "fuzz corpus" << (have_grown ? " (with " + grown.string() + ")" : " (seeds only)") << ": "
            << agreement.compared << " compared, " << agreement.valid << " valid, " << agreement.invalid
            << " invalid, " << unparsable << " not JSON or too deep, " << agreement.disagreements << " disagreements\n";
  // fuzz/corpus/episode holds 30 inputs the fuzzer grew (fuzz-*), of both verdicts.
  EXPECT_GE(agreement.compared, 30);
  EXPECT_GT(agreement.valid, 0);
  EXPECT_GT(agreement.invalid, 0);
}

}  // namespace
