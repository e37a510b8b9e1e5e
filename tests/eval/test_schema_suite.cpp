// JsonSchemaValidator (valijson, draft 7) against the official JSON-Schema-Test-Suite cases for
// exactly the keywords eval/schema/episode.schema.json uses, and against Python's
// jsonschema.Draft202012Validator on the shared corpus (the schema claims both agree on it).
// The compiled schema (eval/compiled_schema.hpp) must give valijson's verdict on every suite
// case whose schema it compiles.
#include <gtest/gtest.h>

#include "eval/json_schema_validator.hpp"
#include "eval/compiled_schema.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "eval/episode_schema.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using a3::eval::CompiledSchema;
using a3::eval::JsonSchemaValidator;
using a3::eval::SchemaEngine;
using nlohmann::json;

fs::path episode_schema_path() { return fs::path(A3_SOURCE_DIR) / "eval/schema/episode.schema.json"; }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// ---- Which keywords the episode schema uses ---------------------------------------------------

// Keywords whose value is a map from names to subschemas, a single subschema, or a list of them;
// the walker descends only through these, so property names are never taken for keywords.
const std::set<std::string> kSchemaMapKeywords = {"properties", "patternProperties", "$defs",
                                                   "definitions"};
const std::set<std::string> kSubschemaKeywords = {"items",         "additionalItems", "additionalProperties",
                                                  "if",            "then",            "else",
                                                  "not",           "contains",        "propertyNames"};
const std::set<std::string> kSchemaListKeywords = {"allOf", "anyOf", "oneOf"};

// Calls visit(schema, json_pointer) for every schema in the tree, boolean schemas included.
template <typename Visit>
void for_each_schema(const json& schema, const std::string& pointer, Visit&& visit) {
  visit(schema, pointer);
  if (!schema.is_object()) return;
  for (const auto& [keyword, value] : schema.items()) {
    const std::string here = pointer + "/" + keyword;
    if (kSchemaMapKeywords.count(keyword) != 0 && value.is_object()) {
      for (const auto& [name, subschema] : value.items()) for_each_schema(subschema, here + "/" + name, visit);
    } else if ((kSubschemaKeywords.count(keyword) != 0 || kSchemaListKeywords.count(keyword) != 0) &&
               value.is_array()) {
      for (std::size_t i = 0; i < value.size(); ++i) {
        for_each_schema(value[i], here + "/" + std::to_string(i), visit);
      }
    } else if (kSubschemaKeywords.count(keyword) != 0) {
      for_each_schema(value, here, visit);
    }
  }
}

std::set<std::string> collect_keywords(const json& schema) {
  std::set<std::string> keywords;
  for_each_schema(schema, "", [&](const json& s, const std::string&) {
    if (!s.is_object()) return;  // boolean schemas have no keywords
    for (const auto& item : s.items()) keywords.insert(item.key());
  });
  return keywords;
}

bool has_false_schema(const json& schema) {
  bool found = false;
  for_each_schema(schema, "", [&](const json& s, const std::string&) { found |= s.is_boolean() && !s.get<bool>(); });
  return found;
}

json load_episode_schema() { return json::parse(read_file(episode_schema_path())); }

// Keywords that do not change a verdict, so they have no suite file.
const std::set<std::string> kAnnotationKeywords = {"$schema", "title", "description", "$comment"};

// Each keyword the episode schema uses and the draft7 suite files that test it. A keyword the
// schema starts using must be added here on purpose (test EveryKeywordHasSuiteFiles).
const std::map<std::string, std::vector<std::string>> kSuiteFilesByKeyword = {
    // The optional file holds "1.0 is an integer", which later suite releases made mandatory for
    // draft 7 and valijson 1.0 fails (see kExclusions): our schema therefore writes integers as
    // {"type": "number", "multipleOf": 1.0} (test NoIntegerType).
    {"type", {"type.json", "optional/zeroTerminatedFloats.json"}},
    {"multipleOf", {"multipleOf.json"}},
    {"required", {"required.json"}},
    {"properties", {"properties.json"}},
    {"additionalProperties", {"additionalProperties.json"}},
    {"items", {"items.json"}},
    {"minItems", {"minItems.json"}},
    {"maxItems", {"maxItems.json"}},
    {"enum", {"enum.json"}},
    {"const", {"const.json"}},
    {"minimum", {"minimum.json"}},
    {"maximum", {"maximum.json"}},
    {"if", {"if-then-else.json"}},
    {"then", {"if-then-else.json"}},
    {"else", {"if-then-else.json"}},
    {"$ref", {"ref.json"}},
    // Not a draft-7 keyword: its subschemas only take effect through "$ref": "#/$defs/..."
    // JSON Pointers, which ref.json tests (definitions.json only checks the draft-7
    // `definitions` keyword against the remote draft-07 meta-schema).
    {"$defs", {"ref.json"}},
};

// valijson 1.0 takes "integer" to mean "written without a fraction or exponent", draft 2020-12
// means "a number whose fractional part is zero": the schema must not say "integer".
TEST(EpisodeSchemaKeywords, NoIntegerType) {
  const std::string text = read_file(episode_schema_path());
  EXPECT_EQ(text.find("\"integer\""), std::string::npos);
}

TEST(EpisodeSchemaKeywords, EveryKeywordHasSuiteFiles) {
  const std::set<std::string> keywords = collect_keywords(load_episode_schema());
  // Keywords that sit only deep in the tree: if these are missing, the walker stopped early and
  // the check below would pass for the wrong reason.
  for (const char* deep : {"maximum", "additionalProperties", "enum", "maxItems", "$ref"}) {
    EXPECT_EQ(keywords.count(deep), 1u) << "walker did not reach keyword " << deep;
  }
  for (const std::string& keyword : keywords) {
    if (kAnnotationKeywords.count(keyword) != 0) continue;
    EXPECT_EQ(kSuiteFilesByKeyword.count(keyword), 1u)
        << "episode.schema.json uses keyword \"" << keyword
        << "\", which has no JSON-Schema-Test-Suite file in kSuiteFilesByKeyword; check that "
           "valijson (draft 7) and draft 2020-12 give it the same meaning, then map it";
  }
}

// The forms whose meaning differs between draft 7 (valijson) and draft 2020-12 (the declared
// dialect), which the schema promises not to use.
TEST(EpisodeSchemaKeywords, UsesOnlyFormsWithTheSameMeaningInDraft7And202012) {
  int refs = 0;
  for_each_schema(load_episode_schema(), "", [&](const json& schema, const std::string& pointer) {
    if (!schema.is_object()) return;
    if (schema.contains("$ref")) {
      ++refs;
      // Draft 7 ignores every keyword beside $ref; 2020-12 applies them.
      EXPECT_EQ(schema.size(), 1u) << pointer << ": keywords beside $ref";
      // Our validator fetches nothing: every reference must stay inside the schema.
      const json& ref = schema["$ref"];
      EXPECT_TRUE(ref.is_string() && ref.get<std::string>().rfind("#/", 0) == 0)
          << pointer << ": $ref " << ref.dump() << " is not a local JSON Pointer";
    }
    // An array under items is a tuple in draft 7 and an error in 2020-12 (prefixItems).
    if (schema.contains("items")) {
      EXPECT_TRUE(schema["items"].is_object()) << pointer << "/items";
    }
  });
  EXPECT_GT(refs, 10);
}

TEST(EpisodeSchema, ParsesWithJsonSchemaValidator) {
  const std::string text = read_file(episode_schema_path());
  EXPECT_NO_THROW(JsonSchemaValidator(text, "episode.schema.json"));
  // The copy compiled into a3_eval (what `a3rig` uses) is the file in the source tree.
  EXPECT_EQ(a3::eval::episode_schema_json(), text);

  const JsonSchemaValidator validator(text, "episode.schema.json");
  rapidjson::Document empty_object;
  empty_object.Parse("{}");
  EXPECT_FALSE(validator.is_valid(empty_object));
  EXPECT_FALSE(validator.violations(empty_object).empty());
}

TEST(JsonSchemaValidatorConstruction, RejectsTextThatIsNotAUsableSchema) {
  EXPECT_THROW(JsonSchemaValidator("{\"type\": ", "truncated"), std::invalid_argument);
  // No fetch callback: a remote reference cannot be resolved.
  EXPECT_THROW(JsonSchemaValidator(R"({"$ref": "http://localhost:1234/integer.json"})", "remote"),
               std::invalid_argument);
  try {
    JsonSchemaValidator("[1,", "named-schema");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("named-schema"), std::string::npos) << e.what();
  }
}

// ---- The JSON-Schema-Test-Suite ---------------------------------------------------------------

std::optional<fs::path> suite_dir() {
  if (const char* env = std::getenv("A3_JSON_SCHEMA_TEST_SUITE"); env != nullptr && *env != '\0') {
    const fs::path root = env;
    // Either the suite's root or its tests/draft7 folder.
    if (fs::is_directory(root / "tests/draft7")) return root / "tests/draft7";
    if (fs::is_directory(root)) return root;
    return std::nullopt;
  }
  const fs::path debian = "/usr/share/json-schema-test-suite/tests/draft7";
  if (fs::is_directory(debian)) return debian;
  return std::nullopt;
}

// Cases our validator gets wrong, each with why. A group is named by its description; an empty
// case means every case of the group. Each listed case must still fail, so the list stays honest.
struct Exclusion {
  std::string file, group, test_case, reason;
};
const std::vector<Exclusion> kExclusions = {
    {"ref.json", "remote ref, containing refs itself", "",
     "needs the draft-07 meta-schema from http://json-schema.org/draft-07/schema (remote ref); "
     "JsonSchemaValidator fetches no documents, and the suite's remotes/ folder does not hold it"},
    {"ref.json", "Recursive references between schemas", "",
     "valijson 1.0 does not index subschemas by their embedded $id: it resolves \"$ref\": "
     "\"node\" to http://localhost:1234/node and tries to fetch it (our schema has no $id)"},
    {"optional/zeroTerminatedFloats.json", "some languages do not distinguish between different "
     "types of numeric value", "a float without fractional part is an integer",
     "valijson 1.0 takes \"integer\" as RapidJSON's IsInt/IsInt64/IsUint/IsUint64, so 1.0 is "
     "rejected; drafts 6+ (and jsonschema.Draft202012Validator) accept it"},
};

const Exclusion* find_exclusion(const std::string& file, const std::string& group,
                                const std::string& test_case) {
  for (const Exclusion& e : kExclusions) {
    if (e.file == file && e.group == group && (e.test_case.empty() || e.test_case == test_case)) {
      return &e;
    }
  }
  return nullptr;
}

TEST(JsonSchemaTestSuite, CasesForTheKeywordsOfOurSchema) {
  const auto dir = suite_dir();
  if (!dir) {
    GTEST_SKIP() << "needs the JSON-Schema-Test-Suite draft7 cases in "
                    "/usr/share/json-schema-test-suite/tests/draft7: apt-get install "
                    "json-schema-test-suite (or set A3_JSON_SCHEMA_TEST_SUITE)";
  }
  const std::set<std::string> keywords = collect_keywords(load_episode_schema());
  std::set<std::string> files;
  for (const std::string& keyword : keywords) {
    if (auto it = kSuiteFilesByKeyword.find(keyword); it != kSuiteFilesByKeyword.end()) {
      files.insert(it->second.begin(), it->second.end());
    }
  }
  ASSERT_GE(files.size(), 10u);

  int run = 0, passed = 0, excluded = 0, unexplained = 0;
  int compiled_groups = 0, refused_groups = 0, compiled_cases = 0;
  std::string refusals;
  std::set<const Exclusion*> exclusions_used;
  for (const std::string& file : files) {
    const fs::path path = *dir / file;
    ASSERT_TRUE(fs::exists(path)) << path << " is missing from the suite";
    const json groups = json::parse(read_file(path));
    ASSERT_TRUE(groups.is_array() && !groups.empty()) << path;
    for (const json& group : groups) {
      const std::string group_name = group.at("description").get<std::string>();
      std::optional<JsonSchemaValidator> validator;
      std::string construction_error;
      try {
        validator.emplace(group.at("schema").dump(), file + ": " + group_name, SchemaEngine::kValijson);
      } catch (const std::invalid_argument& e) {
        construction_error = e.what();
      }
      // The compiled schema may refuse a schema (a keyword or form it does not support); when it
      // compiles one, valijson must have accepted it too.
      std::optional<CompiledSchema> compiled;
      try {
        compiled.emplace(group.at("schema").dump(), file + ": " + group_name);
        ++compiled_groups;
        EXPECT_TRUE(validator.has_value()) << file << " / " << group_name << ": compiled, but valijson refused: "
                                           << construction_error;
      } catch (const std::invalid_argument& e) {
        ++refused_groups;
        refusals += std::string("  refused: ") + e.what() + "\n";
      }
      for (const json& test_case : group.at("tests")) {
        ++run;
        const std::string case_name = test_case.at("description").get<std::string>();
        const bool expected = test_case.at("valid").get<bool>();
        const std::string where = file + " / " + group_name + " / " + case_name;
        rapidjson::Document data;
        data.Parse(test_case.at("data").dump().c_str());
        ASSERT_FALSE(data.HasParseError()) << where;

        std::string outcome;
        bool correct = false;
        if (!validator) {
          outcome = "schema rejected: " + construction_error;
        } else {
          const bool valid = validator->is_valid(data);
          correct = valid == expected;
          if (compiled) {
            ++compiled_cases;
            EXPECT_EQ(compiled->is_valid(data), valid) << where << ": the compiled schema disagrees with valijson";
          }
          outcome = std::string("verdict ") + (valid ? "valid" : "invalid") + ", expected " +
                    (expected ? "valid" : "invalid");
          // violations() explains every failure and reports nothing for a valid document, except
          // that valijson records no error when a `false` schema rejects.
          const bool explained = !validator->violations(data).empty();
          if (valid) {
            EXPECT_FALSE(explained) << where;
          } else if (!explained) {
            ++unexplained;
            EXPECT_TRUE(has_false_schema(group.at("schema"))) << where << ": invalid, but no violation";
          }
        }

        if (const Exclusion* exclusion = find_exclusion(file, group_name, case_name)) {
          ++excluded;
          exclusions_used.insert(exclusion);
          EXPECT_FALSE(correct) << where << ": listed in kExclusions (" << exclusion->reason
                                << ") but now passes; remove it from the list";
          continue;
        }
        if (correct) {
          ++passed;
        } else {
          ADD_FAILURE() << where << ": " << outcome;
        }
      }
    }
  }
  for (const Exclusion& e : kExclusions) {
    if (files.count(e.file) == 0) continue;  // a file our schema no longer needs
    EXPECT_EQ(exclusions_used.count(&e), 1u)
        << "kExclusions names " << e.file << " / " << e.group << ", which no case matches";
  }
  RecordProperty("suite_cases_run", run);
  RecordProperty("suite_cases_passed", passed);
  RecordProperty("suite_cases_excluded", excluded);
  std::cout << "JSON-Schema-Test-Suite draft7, " << files.size() << " files: " << run
            << " cases run, " << passed << " passed, " << excluded << " excluded ("
            << unexplained << " invalid verdicts with no violation, all from `false` schemas)\n";
  std::cout << "compiled schema: " << compiled_groups << " groups compiled (" << compiled_cases
            << " cases, each with valijson's verdict), " << refused_groups << " groups refused\n" << refusals;
  RecordProperty("suite_cases_compiled", compiled_cases);
  EXPECT_EQ(passed + excluded, run);
  EXPECT_GT(run, 150);
  EXPECT_GT(compiled_cases, 150);
}

// ---- Agreement with Python's jsonschema.Draft202012Validator -----------------------------------

std::string shell_quote(const std::string& s) {
  std::string quoted = "'";
  for (char c : s) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// Prints "valid|invalid|unparsable<TAB>path" for every .json file under each folder, after a
// first line "schema-ok" once the schema passes the 2020-12 meta-schema.
constexpr const char* kPythonVerdicts = R"py(
import json, os, sys
try:
    import jsonschema
except ImportError:
    print("no-jsonschema")
    sys.exit(0)
schema = json.load(open(sys.argv[1], encoding="utf-8"))
jsonschema.Draft202012Validator.check_schema(schema)
print("schema-ok")
validator = jsonschema.Draft202012Validator(schema)
for root in sys.argv[2:]:
    for folder, _, names in os.walk(root):
        for name in names:
            if not name.endswith(".json"):
                continue
            path = os.path.join(folder, name)
            try:
                with open(path, encoding="utf-8") as f:
                    document = json.load(f)
            except ValueError:
                print("unparsable\t" + path)
                continue
            print(("valid" if validator.is_valid(document) else "invalid") + "\t" + path)
)py";

struct PythonVerdicts {
  bool have_jsonschema = true;
  std::map<std::string, std::string> by_path;
};

PythonVerdicts python_verdicts(const std::vector<fs::path>& folders) {
  std::string command = "/usr/bin/python3 -c ";
  command += shell_quote(kPythonVerdicts);
  for (const fs::path& argument : {episode_schema_path(), folders[0], folders[1]}) {
    command += ' ';
    command += shell_quote(argument.string());
  }
  command += " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot run " + command);
  std::string output;
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) output.append(buffer.data(), n);
  const int status = pclose(pipe);
  if (status != 0) throw std::runtime_error("python3 failed (status " + std::to_string(status) + "):\n" + output);

  PythonVerdicts verdicts;
  std::istringstream lines(output);
  std::string line;
  std::getline(lines, line);
  if (line == "no-jsonschema") {
    verdicts.have_jsonschema = false;
    return verdicts;
  }
  if (line != "schema-ok") throw std::runtime_error("python3 said:\n" + output);
  while (std::getline(lines, line)) {
    const auto tab = line.find('\t');
    if (tab == std::string::npos) throw std::runtime_error("python3 printed: " + line);
    verdicts.by_path[line.substr(tab + 1)] = line.substr(0, tab);
  }
  return verdicts;
}

std::string valijson_verdict(const JsonSchemaValidator& validator, const fs::path& path) {
  const std::string text = read_file(path);
  rapidjson::Document document;
  document.Parse(text.data(), text.size());
  if (document.HasParseError()) return "unparsable";
  return validator.is_valid(document) ? "valid" : "invalid";
}

std::map<std::string, std::string> valijson_verdicts(const std::vector<fs::path>& folders) {
  const JsonSchemaValidator validator(read_file(episode_schema_path()), "episode.schema.json",
                                      SchemaEngine::kValijson);
  std::map<std::string, std::string> verdicts;
  for (const fs::path& folder : folders) {
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
      if (entry.is_regular_file() && entry.path().extension() == ".json") {
        verdicts[entry.path().string()] = valijson_verdict(validator, entry.path());
      }
    }
  }
  return verdicts;
}

// Temporary folder, removed with its contents.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "a3-schema-suite-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

struct Mutation {
  std::string name;
  bool from_stub;
  std::function<void(json&)> apply;
};

// Edits of a real episode and a real failure stub, so the comparison also covers invalid files
// (every published file is valid) and each branch of the schema.
std::vector<Mutation> mutations() {
  auto set = [](const char* pointer, json value) {
    return [p = json::json_pointer(pointer), value](json& doc) { doc[p] = value; };
  };
  auto erase = [](const char* parent, const char* key) {
    return [p = json::json_pointer(parent), key = std::string(key)](json& doc) { doc[p].erase(key); };
  };
  return {
      {"episode-unchanged", false, [](json&) {}},
      {"episode-no-success", false, erase("", "success")},
      {"episode-loss-100", false, set("/dialogue/0/net/loss_pct", 100)},
      {"episode-loss-over-100", false, set("/dialogue/0/net/loss_pct", 100.5)},
      {"episode-edge-load-negative", false, set("/dialogue/0/net/edge_load", -0.01)},
      {"episode-unknown-slice", false, set("/dialogue/0/net/slice", "urllc")},
      {"episode-unknown-action-type", false, set("/dialogue/0/actions/0/type", "rpc")},
      {"episode-turn-zero", false, set("/dialogue/0/turn", 0)},
      {"episode-turn-string", false, set("/dialogue/0/turn", "1")},
      {"episode-three-bounds", false, set("/initial_state/airspace/alt_bounds", json::array({0, 50, 120}))},
      {"episode-sensor-number", false, set("/initial_state/uav/sensors/a3_test", 5)},
      {"episode-attempts-float", false, set("/_meta/attempts_used", 2.0)},
      {"episode-attempts-fraction", false, set("/_meta/attempts_used", 1.5)},
      {"episode-tokens-float", false, set("/_meta/usage/total_tokens", 4032.0)},
      {"episode-extra-field", false, set("/_meta/a3_extra", "kept")},
      {"episode-says-failed", false, set("/_meta/generation_failed", true)},
      {"episode-says-not-failed", false, set("/_meta/generation_failed", false)},
      {"episode-no-usage", false, erase("/_meta", "usage")},
      {"episode-as-array", false, [](json& doc) { doc = json::array({doc}); }},
      {"stub-unchanged", true, [](json&) {}},
      {"stub-with-turn", true, set("/dialogue", json::array({json::object()}))},
      {"stub-success", true, set("/success", true)},
      {"stub-no-error", true, erase("/_meta", "error")},
      {"stub-not-failed", true, erase("/_meta", "generation_failed")},
  };
}

// Edits on which the two are known to disagree, with why; each must still disagree.
// (None: "attempts_used": 2.0 was one while the schema said "type": "integer".)
const std::map<std::string, std::string> kKnownDisagreements = {};

TEST(EpisodeSchemaAgreement, ValijsonMatchesPythonDraft202012OnTheCorpus) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  if (!fs::exists("/usr/bin/python3")) GTEST_SKIP() << "needs /usr/bin/python3";

  // A real episode with an action in its first turn, and a real failure stub, as the bases.
  std::optional<json> episode, stub;
  std::vector<fs::path> corpus_files;
  for (const auto& entry : fs::recursive_directory_iterator(corpus)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") corpus_files.push_back(entry.path());
  }
  std::sort(corpus_files.begin(), corpus_files.end());
  for (const fs::path& path : corpus_files) {
    const json doc = json::parse(read_file(path));
    const bool failed = doc.value(json::json_pointer("/_meta/generation_failed"), false);
    if (failed && !stub) stub = doc;
    if (!failed && !episode && !doc["dialogue"].empty() && !doc["dialogue"][0]["actions"].empty()) {
      episode = doc;
    }
  }
  ASSERT_GE(corpus_files.size(), 100u);
  ASSERT_TRUE(episode && stub) << "the corpus should hold both episodes and failure stubs";

  TempDir edits;
  std::map<std::string, std::string> mutation_of_path;
  for (const Mutation& m : mutations()) {
    json doc = m.from_stub ? *stub : *episode;
    m.apply(doc);
    const fs::path path = edits.path() / (m.name + ".json");
    std::ofstream(path) << doc.dump();
    mutation_of_path[path.string()] = m.name;
  }

  const std::vector<fs::path> folders = {corpus, edits.path()};
  const PythonVerdicts python = python_verdicts(folders);
  if (!python.have_jsonschema) GTEST_SKIP() << "needs Python's jsonschema: apt-get install python3-jsonschema";
  const std::map<std::string, std::string> ours = valijson_verdicts(folders);
  ASSERT_EQ(python.by_path.size(), ours.size()) << "python3 and this test saw different files";
  ASSERT_EQ(ours.size(), corpus_files.size() + mutation_of_path.size());

  std::map<std::string, int> python_counts;
  int disagreements = 0;
  std::set<std::string> known_seen;
  for (const auto& [path, verdict] : ours) {
    const auto it = python.by_path.find(path);
    ASSERT_NE(it, python.by_path.end()) << path << " has no Python verdict";
    ++python_counts[it->second];
    const auto m = mutation_of_path.find(path);
    const std::string name = m != mutation_of_path.end() ? m->second : path;
    const bool known = kKnownDisagreements.count(name) != 0;
    if (verdict == it->second) {
      EXPECT_FALSE(known) << "edit " << name << " is in kKnownDisagreements ("
                          << kKnownDisagreements.at(name) << ") but now agrees; remove it";
      continue;
    }
    ++disagreements;
    if (known) {
      known_seen.insert(name);
      continue;
    }
    ADD_FAILURE() << name << ": valijson says " << verdict
                  << ", jsonschema.Draft202012Validator says " << it->second;
  }
  for (const auto& [name, reason] : kKnownDisagreements) {
    EXPECT_EQ(known_seen.count(name), 1u) << "kKnownDisagreements names " << name << ", which did not disagree";
  }
  // The edits must exercise both verdicts, or the comparison proves little.
  EXPECT_GE(python_counts["invalid"], 10);
  EXPECT_GE(python_counts["valid"], static_cast<int>(corpus_files.size()));
  RecordProperty("agreement_files", static_cast<int>(ours.size()));
  RecordProperty("agreement_disagreements", disagreements);
  std::cout << "valijson vs jsonschema.Draft202012Validator: " << ours.size() << " files ("
            << corpus_files.size() << " corpus, " << mutation_of_path.size() << " edits), "
            << python_counts["valid"] << " valid, " << python_counts["invalid"] << " invalid, "
            << disagreements << " disagreements (" << known_seen.size() << " known)\n";
}

}  // namespace
