// UTF-8 validation (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF), with a fast
// path for ASCII. JSON text must be UTF-8 (RFC 8259 §8.1); checking it once up front is
// several times cheaper than RapidJSON's per-character check while parsing.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

namespace a3::eval {

// The byte offset of the first invalid sequence, or nothing when the text is valid UTF-8.
std::optional<std::size_t> find_invalid_utf8(std::string_view text);

}  // namespace a3::eval
