// The compiled schema (eval/compiled_schema.hpp) against valijson on the public α³-Bench episodes
// ($A3_SHARED_DIR/alphabench): every file as published, every file with a few targeted edits
// (a required field dropped, a type changed, a string outside an enum, bounds crossed) whose
// verdict is known, and sampled files with every value replaced, removed or nudged. Skipped,
// with a message, when the episodes are absent.
#include <gtest/gtest.h>

#include "eval/rapidjson.hpp"  // first: RapidJSON configured as everywhere in eval/

#include <rapidjson/pointer.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "tests/eval/schema_agreement.hpp"
#include "tests/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace a3::eval;
using namespace a3::eval::testing;

TEST(CompiledSchemaAgreement, EveryPublicEpisode) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  Agreement agreement;
  for (const fs::path& path : json_files_under(corpus)) {
    rapidjson::Document document;
    ASSERT_TRUE(parse_like_the_reader(read_file(path), document)) << path;
    agreement.compare(document, path.string());
  }
  std::cout << "public episodes: " << agreement.compared << " compared, " << agreement.valid << " valid, "
            << agreement.invalid << " invalid, " << agreement.disagreements << " disagreements\n";
  EXPECT_GE(agreement.compared, 100);
  EXPECT_EQ(agreement.valid, agreement.compared);  // every published file is valid
}

// ---- Targeted edits of every public episode ------------------------------------------------

// An edit at a JSON Pointer: the value replaced by `json`, or removed when `json` is empty. It
// applies when its target (for a removal) or the target's parent (for a replacement) exists:
// failure stubs have no turns.
struct TargetedEdit {
  const char* pointer;
  const char* json;
  bool valid_after;  // valijson's verdict on an edited valid file (asserted, not only compared)
};

const std::vector<TargetedEdit> kTargetedEdits = {
    {"/initial_state", "", false},
    {"/dialogue", "", false},
    {"/final_state", "", false},
    {"/success", "", false},
    {"/_meta", "", false},
    {"/success", "\"true\"", false},
    {"/_meta/generation_failed", "\"yes\"", false},
    {"/_meta/attempts_used", "0", false},
    {"/_meta/attempts_used", "1.5", false},
    {"/_meta/attempts_used", "2.0", true},
    {"/_meta/usage/total_tokens", "-1", false},
    {"/initial_state/airspace/alt_bounds", "[10]", false},
    {"/initial_state/env/wind_mps", "-0.5", false},
    {"/final_state/uav/pose/z", "\"12\"", false},
    {"/final_state/safety_flags/nfz_violation", "0", false},
    {"/final_state/safety_flags", "", false},
    {"/dialogue/0/turn", "1.5", false},
    {"/dialogue/0/net/slice", "\"urllc\"", false},
    {"/dialogue/0/net/slice", "1", false},
    {"/dialogue/0/net/lat_ms", "", false},
    {"/dialogue/0/net/loss_pct", "100.5", false},
    {"/dialogue/0/net/edge_load", "1", true},
    {"/dialogue/0/actions/0/type", "\"MCP\"", false},
    {"/dialogue/0/obs", "{}", false},
    {"/an_extra_field", "{}", true},
};

// The edited copy, or nothing when the edit does not apply to this document.
std::optional<rapidjson::Document> edited(const rapidjson::Document& original, const TargetedEdit& edit) {
  const rapidjson::Pointer pointer(edit.pointer);
  rapidjson::Document copy;
  copy.CopyFrom(original, copy.GetAllocator());
  if (*edit.json == '\0') {
    if (!pointer.Erase(copy)) return std::nullopt;
    return copy;
  }
  const rapidjson::Pointer parent(pointer.GetTokens(), pointer.GetTokenCount() - 1);
  if (parent.Get(copy) == nullptr) return std::nullopt;
  rapidjson::Document replacement;
  replacement.Parse(edit.json);
  const rapidjson::Value& value = replacement;  // copied (the non-const overload would move it)
  pointer.Set(copy, value, copy.GetAllocator());
  return copy;
}

TEST(CompiledSchemaAgreement, EveryPublicEpisodeWithTargetedEdits) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  Agreement agreement;
  int wrong_verdicts = 0;
  for (const fs::path& path : json_files_under(corpus)) {
    rapidjson::Document original;
    ASSERT_TRUE(parse_like_the_reader(read_file(path), original)) << path;
    for (const TargetedEdit& edit : kTargetedEdits) {
      const std::optional<rapidjson::Document> document = edited(original, edit);
      if (!document) continue;
      const std::string what = path.filename().string() + ": " + edit.pointer + (*edit.json ? " = " : " removed") + edit.json;
      agreement.compare(*document, what);
      if (valijson_validator().is_valid(*document) != edit.valid_after && ++wrong_verdicts <= 5) {
        ADD_FAILURE() << what << ": expected " << (edit.valid_after ? "valid" : "invalid");
      }
    }
  }
  std::cout << "targeted edits of the public episodes: " << agreement.compared << " compared, " << agreement.valid
            << " valid, " << agreement.invalid << " invalid, " << agreement.disagreements << " disagreements\n";
  EXPECT_EQ(wrong_verdicts, 0);
  EXPECT_GT(agreement.compared, 2000);
}

// ---- Every value of sampled episodes replaced, removed or nudged ------------------------------

using Path = std::vector<rapidjson::SizeType>;  // member or element index at each level

void collect_paths(const rapidjson::Value& value, Path& here, std::vector<Path>& out) {
  out.push_back(here);
  rapidjson::SizeType i = 0;
  if (value.IsObject()) {
    for (auto it = value.MemberBegin(); it != value.MemberEnd(); ++it, ++i) {
      here.push_back(i);
      collect_paths(it->value, here, out);
      here.pop_back();
    }
  } else if (value.IsArray()) {
    for (const rapidjson::Value& element : value.GetArray()) {
      here.push_back(i++);
      collect_paths(element, here, out);
      here.pop_back();
    }
  }
}

rapidjson::Value& child_at(rapidjson::Value& parent, rapidjson::SizeType i) {
  return parent.IsObject() ? (parent.MemberBegin() + i)->value : parent[i];
}

rapidjson::Value& value_at(rapidjson::Value& root, const Path& path, std::size_t levels) {
  rapidjson::Value* at = &root;
  for (std::size_t k = 0; k < levels; ++k) at = &child_at(*at, path[k]);
  return *at;
}

std::string describe(const rapidjson::Value& root, const Path& path) {
  std::string pointer;
  const rapidjson::Value* at = &root;
  for (rapidjson::SizeType i : path) {
    if (at->IsObject()) {
      pointer += "/" + std::string((at->MemberBegin() + i)->name.GetString());
      at = &(at->MemberBegin() + i)->value;
    } else {
      pointer += "/" + std::to_string(i);
      at = &(*at)[i];
    }
  }
  return pointer.empty() ? "/" : pointer;
}

// Replacements of other types, at and beyond the schema's bounds, and numbers valijson reads
// in its own way (uint64 above INT64_MAX, -0.0, values one ulp from an integer).
const std::vector<std::string> kReplacements = {
    "null", "true", "false", "0", "-1", "1", "2", "8.0", "1.5", "-0.0", "100", "100.5", "1.0000000000000002",
    "0.9999999999999999", "1e308", "-1e308", "4.9e-324", "18446744073709551615", "-9223372036854775808",
    "9223372036854775808", "\"\"", "\"x\"", "\"1\"", "\"1.5\"", "\"mcp\"", "\"a2a\"", "\"eMBB\"", "\"home\"",
    "{}", "[]", "[1, 2]", "[0, 0, 0]", "[{}]", "{\"a\": 1}", "{\"site\": \"home\"}"};

struct Edits {
  const rapidjson::Document& original;
  Agreement& agreement;

  void replace_each_value(const std::vector<Path>& paths, const std::vector<rapidjson::Document>& replacements) {
    for (const Path& path : paths) {
      for (std::size_t r = 0; r < replacements.size(); ++r) {
        rapidjson::Document edited;
        edited.CopyFrom(original, edited.GetAllocator());
        value_at(edited, path, path.size()).CopyFrom(replacements[r], edited.GetAllocator());
        agreement.compare(edited, describe(original, path) + " = " + kReplacements[r]);
      }
    }
  }

  void remove_each_value(const std::vector<Path>& paths) {
    for (const Path& path : paths) {
      if (path.empty()) continue;
      rapidjson::Document edited;
      edited.CopyFrom(original, edited.GetAllocator());
      rapidjson::Value& parent = value_at(edited, path, path.size() - 1);
      if (parent.IsObject()) {
        parent.EraseMember(parent.MemberBegin() + path.back());
      } else {
        parent.Erase(parent.Begin() + path.back());
      }
      agreement.compare(edited, describe(original, path) + " removed");
    }
  }

  // Numbers moved by one ulp each way and negated: the bounds and multipleOf at their edges.
  void nudge_each_number(const std::vector<Path>& paths) {
    for (const Path& path : paths) {
      rapidjson::Document probe;
      probe.CopyFrom(original, probe.GetAllocator());
      if (!value_at(probe, path, path.size()).IsNumber()) continue;
      const double x = value_at(probe, path, path.size()).GetDouble();
      for (const double y : {std::nextafter(x, INFINITY), std::nextafter(x, -INFINITY), -x}) {
        rapidjson::Document edited;
        edited.CopyFrom(original, edited.GetAllocator());
        value_at(edited, path, path.size()).SetDouble(y);
        agreement.compare(edited, describe(original, path) + " nudged");
      }
    }
  }
};

TEST(CompiledSchemaAgreement, EditsOfPublicEpisodes) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  std::vector<rapidjson::Document> replacements(kReplacements.size());
  for (std::size_t r = 0; r < kReplacements.size(); ++r) {
    ASSERT_TRUE(parse_like_the_reader(kReplacements[r], replacements[r])) << kReplacements[r];
  }
  const std::vector<fs::path> files = json_files_under(corpus);
  ASSERT_FALSE(files.empty());
  // Every 20th file, and every failure stub (the other branch of the schema's if).
  Agreement agreement;
  int sampled = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string text = read_file(files[i]);
    const bool stub = text.find("\"generation_failed\": true") != std::string::npos ||
                      text.find("\"generation_failed\":true") != std::string::npos;
    if (i % 20 != 0 && !stub) continue;
    rapidjson::Document original;
    ASSERT_TRUE(parse_like_the_reader(text, original)) << files[i];
    std::vector<Path> paths;
    Path here;
    collect_paths(original, here, paths);
    Edits edits{original, agreement};
    edits.replace_each_value(paths, replacements);
    edits.remove_each_value(paths);
    edits.nudge_each_number(paths);
    ++sampled;
  }
  std::cout << "edits of " << sampled << " public episodes: " << agreement.compared << " compared, "
            << agreement.valid << " valid, " << agreement.invalid << " invalid, " << agreement.disagreements
            << " disagreements\n";
  EXPECT_EQ(agreement.disagreements, 0);
  // Both verdicts in numbers, or the comparison proves little.
  EXPECT_GT(agreement.valid, 1000);
  EXPECT_GT(agreement.invalid, 1000);
}

}  // namespace
