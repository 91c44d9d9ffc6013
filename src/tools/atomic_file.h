// Writing output files so that a reader never sees a half-written file: write to a temporary
// name in the same folder, then rename over the final name (atomic on POSIX file systems).
#pragma once

#include <string>

namespace haif {

/// Writes `content` to `path` atomically. On failure returns false with a message naming the file.
bool writeFileAtomic(const std::string& path, const std::string& content, std::string& error);

/// Creates `dir` (and parents) if needed and checks that it is writable.
bool ensureWritableDir(const std::string& dir, std::string& error);

/// The temporary name used for `path` while it is being written.
std::string temporaryPathFor(const std::string& path);

}  // namespace haif
