// Reading a whole input file (a scene, a playlist, a replay log) with one error line that names
// the file and what it was meant to be. A folder opens as a stream on Linux and reads as empty,
// which the parsers then reported as "1:1 syntax error"; here it is said for what it is.
#pragma once

#include <cstddef>
#include <string>

namespace haif {

/// The largest input file read: scenes with inline meshes run to a few MiB.
constexpr size_t kMaxTextFileBytes = size_t(256) << 20;

/// Reads `path` into `text`. False with "PATH: cannot open WHAT (why)" or "PATH: is a directory,
/// not a WHAT" when it cannot.
bool readTextFile(const std::string& path, const std::string& what, std::string& text, std::string& error);

}  // namespace haif
