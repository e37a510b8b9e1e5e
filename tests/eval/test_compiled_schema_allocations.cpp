// The compiled schema validates without allocating (issue 16: valijson copies its error context
// at every value). Counted by replacing operator new in this test program; valijson, on the same
// documents, shows that the counter sees allocations when there are some.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <iostream>
#include <new>
#include <vector>

#include "tests/eval/schema_agreement.hpp"
#include "tests/test_support.hpp"

namespace {

std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};

void* counted_malloc(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) ++g_allocations;
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

template <typename Work>
long allocations_during(Work&& work) {
  g_allocations = 0;
  g_counting = true;
  work();
  g_counting = false;
  return g_allocations.load();
}

}  // namespace

void* operator new(std::size_t size) { return counted_malloc(size); }
void* operator new[](std::size_t size) { return counted_malloc(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace a3::eval;
using namespace a3::eval::testing;

TEST(CompiledSchemaAllocations, ValidatingThePublicEpisodesAllocatesNothing) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  std::vector<rapidjson::Document> documents;
  for (const fs::path& path : json_files_under(corpus)) {
    ASSERT_TRUE(parse_like_the_reader(read_file(path), documents.emplace_back())) << path;
  }
  ASSERT_FALSE(documents.empty());
  const CompiledSchema& schema = compiled_schema();
  const JsonSchemaValidator& reference = valijson_validator();
  int valid = 0;
  const long compiled_allocations = allocations_during([&] {
    for (const rapidjson::Document& document : documents) valid += schema.is_valid(document) ? 1 : 0;
  });
  EXPECT_EQ(valid, static_cast<int>(documents.size()));
  EXPECT_EQ(compiled_allocations, 0);
  const long valijson_allocations = allocations_during([&] {
    for (const rapidjson::Document& document : documents) reference.is_valid(document);
  });
  EXPECT_GT(valijson_allocations, static_cast<long>(documents.size()));
  std::cout << documents.size() << " public episodes validated: " << compiled_allocations
            << " allocations with the compiled schema, " << valijson_allocations << " with valijson\n";
}

// The invalid side too: an edited episode fails without allocating.
TEST(CompiledSchemaAllocations, RejectingAnEpisodeAllocatesNothing) {
  A3_REQUIRE_SHARED(corpus, "alphabench");
  const std::vector<fs::path> files = json_files_under(corpus);
  ASSERT_FALSE(files.empty());
  rapidjson::Document document;
  ASSERT_TRUE(parse_like_the_reader(read_file(files.front()), document));
  document.RemoveMember("success");
  const CompiledSchema& schema = compiled_schema();
  bool valid = true;
  EXPECT_EQ(allocations_during([&] { valid = schema.is_valid(document); }), 0);
  EXPECT_FALSE(valid);
}

}  // namespace
