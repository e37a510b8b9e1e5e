// RapidJSON, configured the same way in every file that uses it. RapidJSON's assertions
// (a type mismatch, say) throw std::logic_error instead of aborting. valijson's RapidJSON adapter
// would define RAPIDJSON_ASSERT too, but its version builds a std::string on every successful
// check, which made scoring five times slower; ours costs nothing until it fails.
#pragma once

#include <cstddef>
#include <stdexcept>

namespace a3::eval {
[[noreturn]] void rapidjson_assertion_failed(const char* condition, const char* file, int line);
}  // namespace a3::eval

#ifndef RAPIDJSON_ASSERT
#define RAPIDJSON_ASSERT(x) \
  (static_cast<bool>(x) ? void(0) : ::a3::eval::rapidjson_assertion_failed(#x, __FILE__, __LINE__))
#endif

// SIMD scanning of strings and whitespace (the same results, found 16 bytes at a time). SSE2 is
// in every x86-64 CPU; SSE4.2 only when the compiler targets it. Its aligned loads may read up
// to 15 bytes past a text's terminating NUL: in-place buffers keep kRapidJsonPaddingBytes there,
// but other texts do not, so AddressSanitizer builds (the fuzz targets) keep the scalar scan.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define A3_RAPIDJSON_NO_SIMD
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define A3_RAPIDJSON_NO_SIMD
#endif
#if !defined(A3_RAPIDJSON_NO_SIMD) && !defined(RAPIDJSON_SSE2) && !defined(RAPIDJSON_SSE42)
#if defined(__SSE4_2__)
#define RAPIDJSON_SSE42
#elif defined(__SSE2__)
#define RAPIDJSON_SSE2
#endif
#endif

#include <rapidjson/document.h>
#include <rapidjson/error/en.h>

namespace a3::eval {
inline constexpr std::size_t kRapidJsonPaddingBytes = 16;
}  // namespace a3::eval

// The valijson headers the adapter needs, read while VALIJSON_USE_EXCEPTIONS is still set (so
// valijson reports errors by exception); the adapter itself is read with it unset, which only
// skips its own RAPIDJSON_ASSERT definition (and its #warning that one already exists).
#include <valijson/exceptions.hpp>
#include <valijson/internal/adapter.hpp>
#include <valijson/internal/basic_adapter.hpp>
#include <valijson/internal/frozen_value.hpp>
#pragma push_macro("VALIJSON_USE_EXCEPTIONS")
#undef VALIJSON_USE_EXCEPTIONS
#include <valijson/adapters/rapidjson_adapter.hpp>
#pragma pop_macro("VALIJSON_USE_EXCEPTIONS")
