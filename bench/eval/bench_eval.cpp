// Per-episode cost of each scoring stage on the public α³-Bench episodes: UTF-8 check, parse,
// depth and duplicate-key check, schema validation (valijson), semantic rules, fact extraction, pillars, and the whole check.
// Run: build/bench/bench_eval   (needs ../shared/alphabench or A3_SHARED_DIR)
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "eval/episode_document.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/json_shape.hpp"
#include "eval/pillars.hpp"
#include "eval/utf8.hpp"

namespace {

namespace fs = std::filesystem;
using namespace a3::eval;

std::vector<std::string>& episodes() {
  static std::vector<std::string> texts = [] {
    std::vector<std::string> out;
    const char* env = std::getenv("A3_SHARED_DIR");
    const fs::path root = fs::path(env != nullptr && *env ? env : A3_SHARED_DIR_DEFAULT) / "alphabench";
    if (!fs::exists(root)) return out;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (entry.path().extension() != ".json" || entry.path().filename() == "README.md") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream s;
      s << in.rdbuf();
      out.push_back(s.str());
    }
    std::sort(out.begin(), out.end());
    return out;
  }();
  return texts;
}

const JsonSchemaValidator& validator() {
  static const JsonSchemaValidator v(episode_schema_json(), kEpisodeSchemaName);
  return v;
}

bool need_corpus(benchmark::State& state) {
  if (!episodes().empty()) return true;
  state.SkipWithError("needs ../shared/alphabench (the α³-Bench public episodes) or A3_SHARED_DIR");
  return false;
}

std::vector<rapidjson::Document>& parsed() {
  static std::vector<rapidjson::Document> docs = [] {
    std::vector<rapidjson::Document> out(episodes().size());
    for (std::size_t i = 0; i < out.size(); ++i) {
      out[i].Parse<rapidjson::kParseFullPrecisionFlag>(episodes()[i].c_str());
    }
    return out;
  }();
  return docs;
}

void report(benchmark::State& state) {
  state.SetItemsProcessed(state.iterations());
  std::size_t bytes = 0;
  for (const auto& e : episodes()) bytes += e.size();
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes / std::max<std::size_t>(episodes().size(), 1)));
}

void BM_Utf8Check(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(find_invalid_utf8(episodes()[i++ % episodes().size()]));
  }
  report(state);
}

void BM_ParseInPlace(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::string buffer;
  std::size_t i = 0;
  for (auto _ : state) {
    buffer = episodes()[i++ % episodes().size()];
    rapidjson::Document d;
    d.ParseInsitu<rapidjson::kParseFullPrecisionFlag>(buffer.data());
    benchmark::DoNotOptimize(d.IsObject());
  }
  report(state);
}

// Iterative parsing cannot overflow the stack on deep input.
void BM_ParseInPlaceIterative(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::string buffer;
  std::size_t i = 0;
  for (auto _ : state) {
    buffer = episodes()[i++ % episodes().size()];
    rapidjson::Document d;
    d.ParseInsitu<rapidjson::kParseFullPrecisionFlag | rapidjson::kParseIterativeFlag>(buffer.data());
    benchmark::DoNotOptimize(d.IsObject());
  }
  report(state);
}

// What episode_reader does: iterative, numbers converted by eval/exact_numbers (RapidJSON's
// full-precision mode misreads 0E120).
void BM_ParseInPlaceExactNumbers(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::string buffer;
  ExactNumberParser parser;
  std::size_t i = 0;
  for (auto _ : state) {
    buffer = episodes()[i++ % episodes().size()];
    rapidjson::Document d;
    parser.parse_insitu(d, buffer.data());
    benchmark::DoNotOptimize(d.IsObject());
  }
  report(state);
}

void BM_DepthAndDuplicateKeys(benchmark::State& state) {
  if (!need_corpus(state)) return;
  JsonShapeChecker checker;
  Violations violations;
  std::size_t i = 0;
  for (auto _ : state) {
    violations.clear();
    benchmark::DoNotOptimize(checker.check(parsed()[i++ % parsed().size()], violations));
  }
  report(state);
}

void BM_SchemaValidation(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(validator().is_valid(parsed()[i++ % parsed().size()]));
  }
  report(state);
}

void BM_SemanticRules(benchmark::State& state) {
  if (!need_corpus(state)) return;
  const ScoringProfile profile = release_profile();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(check_semantics(parsed()[i++ % parsed().size()], profile));
  }
  report(state);
}

void BM_ExtractFacts(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(extract_facts(parsed()[i++ % parsed().size()]));
  }
  report(state);
}

void BM_Pillars(benchmark::State& state) {
  if (!need_corpus(state)) return;
  std::vector<EpisodeFacts> facts;
  for (const auto& d : parsed()) facts.push_back(extract_facts(d));
  const ScoringProfile profile = release_profile();
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(score_pillars(facts[i++ % facts.size()], profile, 10.0));
  }
  report(state);
}

void BM_WholeCheckFromMemory(benchmark::State& state) {
  if (!need_corpus(state)) return;
  const ScoringProfile profile = release_profile();
  EpisodeReader reader(validator(), profile);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reader.check_text(episodes()[i++ % episodes().size()]));
  }
  report(state);
}

BENCHMARK(BM_Utf8Check);
BENCHMARK(BM_ParseInPlace);
BENCHMARK(BM_ParseInPlaceIterative);
BENCHMARK(BM_ParseInPlaceExactNumbers);
BENCHMARK(BM_DepthAndDuplicateKeys);
BENCHMARK(BM_SchemaValidation);
BENCHMARK(BM_SemanticRules);
BENCHMARK(BM_ExtractFacts);
BENCHMARK(BM_Pillars);
BENCHMARK(BM_WholeCheckFromMemory);

}  // namespace

BENCHMARK_MAIN();
