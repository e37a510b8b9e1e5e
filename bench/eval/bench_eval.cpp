// Per-episode cost of each scoring stage on the public α³-Bench episodes: UTF-8 check, parse
// (RapidJSON, and simdjson, the fast path),
// depth and duplicate-key check, schema validation (valijson and the compiled schema), semantic
// rules, fact extraction, pillars, and the whole check; then whole-corpus scoring (score_corpus)
// on 1 and 2 threads with each schema engine, over $A3_BENCH_CORPUS (a folder of episodes, e.g.
// the replicated corpus score_throughput.py builds) or else the public episodes.
// Run: build/bench/bench_eval   (needs ../shared/alphabench or A3_SHARED_DIR)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "eval/corpus_scorer.hpp"
#include "eval/episode_document.hpp"
#include "eval/episode_reader.hpp"
#include "eval/episode_schema.hpp"
#include "eval/exact_numbers.hpp"
#include "eval/json_shape.hpp"
#include "eval/pillars.hpp"
#include "eval/simdjson_parser.hpp"
#include "eval/utf8.hpp"

namespace {

namespace fs = std::filesystem;
using namespace a3::eval;

fs::path public_episodes() {
  const char* env = std::getenv("A3_SHARED_DIR");
  return fs::path(env != nullptr && *env ? env : A3_SHARED_DIR_DEFAULT) / "alphabench";
}

std::vector<std::string>& episodes() {
  static std::vector<std::string> texts = [] {
    std::vector<std::string> out;
    const fs::path root = public_episodes();
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

// Argument 0: valijson, 1: the compiled schema (what scoring uses).
const JsonSchemaValidator& validator(int64_t engine = 1) {
  static const JsonSchemaValidator valijson(episode_schema_json(), kEpisodeSchemaName, SchemaEngine::kValijson);
  static const JsonSchemaValidator compiled(episode_schema_json(), kEpisodeSchemaName, SchemaEngine::kCompiled);
  return engine == 0 ? valijson : compiled;
}

const char* engine_label(int64_t engine) { return engine == 0 ? "valijson" : "compiled"; }

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

// The read buffer and document pool EpisodeReader keeps between files.
struct ReaderMemory {
  std::string buffer;
  std::vector<char> chunk = std::vector<char>(256u << 10);
  rapidjson::MemoryPoolAllocator<> pool{chunk.data(), chunk.size()};

  // `text` in the buffer followed by 1 + padding zero bytes; the pool emptied.
  char* next(const std::string& text, std::size_t padding) {
    buffer.assign(text.size() + 1 + padding, '\0');
    std::copy(text.begin(), text.end(), buffer.begin());
    pool.Clear();
    return buffer.data();
  }
};

// Numbers converted by eval/exact_numbers (RapidJSON's full-precision mode misreads 0E120), into
// a pool that keeps its memory between documents as EpisodeReader's does. Argument 0: the
// iterative parse (the fallback for errors and deep nesting), 1: the recursive one episode_reader
// uses first.
void BM_ParseInPlaceExactNumbers(benchmark::State& state) {
  if (!need_corpus(state)) return;
  ReaderMemory memory;
  ExactNumberParser parser;
  const bool recursive = state.range(0) == 1;
  std::size_t i = 0;
  for (auto _ : state) {
    char* text = memory.next(episodes()[i++ % episodes().size()], kRapidJsonPaddingBytes);
    rapidjson::Document d(&memory.pool);
    if (recursive) {
      benchmark::DoNotOptimize(parser.parse_insitu_shallow(d, text));
    } else {
      parser.parse_insitu(d, text);
    }
    benchmark::DoNotOptimize(d.IsObject());
  }
  state.SetLabel(recursive ? "recursive" : "iterative");
  report(state);
}

// The fast path episode_reader takes first: simdjson, then the same RapidJSON document built
// from its result (with the long-exponent scan and the duplicate-key answer).
void BM_ParseSimdjson(benchmark::State& state) {
  if (!need_corpus(state)) return;
  ReaderMemory memory;
  SimdjsonParser parser;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::string& text = episodes()[i++ % episodes().size()];
    char* padded = memory.next(text, kSimdjsonPaddingBytes);
    rapidjson::Document d(&memory.pool);
    benchmark::DoNotOptimize(parser.parse(d, std::string_view(padded, text.size())));
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
  const JsonSchemaValidator& v = validator(state.range(0));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(v.is_valid(parsed()[i++ % parsed().size()]));
  }
  state.SetLabel(engine_label(state.range(0)));
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
  EpisodeReader reader(validator(state.range(0)), profile);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reader.check_text(episodes()[i++ % episodes().size()]));
  }
  state.SetLabel(engine_label(state.range(0)));
  report(state);
}

// What `a3rig score` does (walk, read, check, score, aggregate), minus printing: episodes/s is
// items_per_second. Arguments: engine, threads.
void BM_ScoreCorpus(benchmark::State& state) {
  const char* env = std::getenv("A3_BENCH_CORPUS");
  const fs::path root = env != nullptr && *env ? fs::path(env) : public_episodes();
  if (!fs::exists(root)) {
    state.SkipWithError("needs A3_BENCH_CORPUS or ../shared/alphabench");
    return;
  }
  ScoreOptions options;
  options.threads = static_cast<std::size_t>(state.range(1));
  uint64_t files = 0;
  for (auto _ : state) {
    const ScoreResult result = score_corpus({root}, validator(state.range(0)), options);
    files += result.files;
  }
  state.SetItemsProcessed(static_cast<int64_t>(files));
  state.SetLabel(std::string(engine_label(state.range(0))) + ", " + std::to_string(state.range(1)) + " thread(s)");
}

BENCHMARK(BM_Utf8Check);
BENCHMARK(BM_ParseInPlace);
BENCHMARK(BM_ParseInPlaceIterative);
BENCHMARK(BM_ParseInPlaceExactNumbers)->Arg(0)->Arg(1);
BENCHMARK(BM_ParseSimdjson);
BENCHMARK(BM_DepthAndDuplicateKeys);
BENCHMARK(BM_SchemaValidation)->Arg(0)->Arg(1);
BENCHMARK(BM_SemanticRules);
BENCHMARK(BM_ExtractFacts);
BENCHMARK(BM_Pillars);
BENCHMARK(BM_WholeCheckFromMemory)->Arg(0)->Arg(1);
BENCHMARK(BM_ScoreCorpus)->ArgsProduct({{0, 1}, {1, 2}})->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
