// Scene files: JSON in the documented schema (docs/scene-format.md), read
// into a sol::Scene and written back.
//
// Every error names its source (the file name) and the field, and for a
// field that is in the file the line and column where its value starts:
//   "my.json: objects[1].radius must be finite and > 0 (line 6, column 16)".
#pragma once

#include <string>
#include <string_view>

#include "sol/scene.hpp"

namespace sol {

/// How deeply a scene file's objects and arrays may nest (the schema needs 4).
/// Deeper text is refused before it is parsed: parsers recurse per level.
inline constexpr int kSceneFileMaxDepth = 32;

/// Parses a scene from JSON text; `source` (a file name) prefixes every error
/// message. Unknown keys are errors (a typo must not pass silently), as are
/// nesting deeper than kSceneFileMaxDepth and NUL bytes (nothing after the
/// JSON value is ignored). Throws InvalidArgument on malformed or
/// inconsistent input (sol::validate's checks).
Scene parse_scene(std::string_view json, std::string_view source = "<scene>");

/// Reads and parses a scene file; InvalidArgument if unreadable or invalid.
Scene load_scene(const std::string& path);

/// Scene as JSON text in the documented schema (parse_scene reads it back).
std::string to_json(const Scene& scene);

}  // namespace sol
