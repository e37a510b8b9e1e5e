// RapidJSON, configured the same way in every file that uses it. RapidJSON's assertions
// (a type mismatch, say) throw std::logic_error instead of aborting. valijson's RapidJSON adapter
// would define RAPIDJSON_ASSERT too, but its version builds a std::string on every successful
// check, which made scoring five times slower; ours costs nothing until it fails.
#pragma once

#include <stdexcept>

namespace a3::eval {
[[noreturn]] void rapidjson_assertion_failed(const char* condition, const char* file, int line);
}  // namespace a3::eval

#ifndef RAPIDJSON_ASSERT
#define RAPIDJSON_ASSERT(x) \
  (static_cast<bool>(x) ? void(0) : ::a3::eval::rapidjson_assertion_failed(#x, __FILE__, __LINE__))
#endif

#include <rapidjson/document.h>
#include <rapidjson/error/en.h>

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
