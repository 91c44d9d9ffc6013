// Reading a JSON input file's text into a document, with one "PATH:LINE:COL: ..." error line for what
// stops it being one: nesting deeper than kMaxJsonDepth, a syntax error, a key given twice. The
// playlist and suite readers start this way; scene files format their own lines (scene_loader.cpp)
// but share the syntax message.
#pragma once

#include "scene/json_positions.h"
#include "scene/json_reader.h"

#include <cstdint>
#include <string>

namespace haif {

/// nlohmann's message without its "[json.exception...] parse error at line L, column C: " prefix:
/// the callers print their own position.
std::string jsonSyntaxMessage(const std::string& what);

/// Parses `text` (read from `path`, named in errors) into `doc` and its key positions. False with
/// `error` set when the text nests too deep, is not JSON, or gives a key twice in one object.
bool parseJsonDocument(const std::string& text, const std::string& path, Json& doc, JsonPositions& positions,
                       std::string& error);

/// FNV-1a (64 bits) of a file's bytes: what a run records of the scene or suite it read.
uint64_t fnv1aHash(const std::string& text);

}  // namespace haif
