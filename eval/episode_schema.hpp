// The episode JSON Schema (eval/schema/episode.schema.json), compiled into the program so that
// `a3rig` validates the same way wherever it runs.
#pragma once

#include <string_view>

namespace a3::eval {

std::string_view episode_schema_json();
inline constexpr std::string_view kEpisodeSchemaName = "episode.schema.json";

}  // namespace a3::eval
