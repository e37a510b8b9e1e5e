// How valijson 1.0 (strong types, RapidJSON adapter) reads a value's number and compares two
// values, written out so the compiled schema (compiled_schema.hpp) gives exactly its verdicts:
// integers become doubles through int64_t (a uint64 above INT64_MAX wraps to a negative number),
// strings that strtod reads whole count as numbers for multipleOf, and `const` / `enum` compare
// strictly (1 equals 1.0, true never equals 1, objects match by size and the first member of a name).
#pragma once

#include "eval/rapidjson.hpp"

namespace a3::eval {

// A number's value as valijson's getNumber()/asDouble() gives it. `value` must be a number.
double valijson_number(const rapidjson::Value& value);

// valijson's maybeDouble() + asDouble(): numbers, and strings that strtod reads to their end.
bool valijson_maybe_double(const rapidjson::Value& value, double& out);

// valijson's strict equalTo(), with `schema_value` on the left (as in its const and enum checks).
bool valijson_equal(const rapidjson::Value& schema_value, const rapidjson::Value& target);

}  // namespace a3::eval
