// Output that appears whole or not at all. A command that writes a folder builds it in a
// temporary folder beside the target (DIR/.NAME.tmpPID) and moves it into place only when every
// file in it is complete; an existing output folder is replaced as a whole, so no frame of an
// earlier, longer run survives beside a new summary. Nothing is created until the command's
// options and inputs have been checked, and a failed or interrupted command leaves the target as
// it was (tools/interrupts.h removes the temporary folder on SIGINT and SIGTERM).
//
// Replacing deletes the old folder, so only a folder this command wrote may be replaced: one that
// holds one of its marker files (a run's summary.json, a diff's report.json, ...) or nothing at
// all. Any other existing folder is refused with a message, never emptied.
#pragma once

#include <string>
#include <vector>

namespace haif {

/// Checks, without creating anything, that a folder can be written at `target`: it does not exist,
/// or it is a folder holding nothing or one of `markers`; and its nearest existing parent is a
/// writable folder. One error line naming the path otherwise.
bool checkOutputFolder(const std::string& target, const std::vector<std::string>& markers, std::string& error);

/// Checks, without creating anything, that a file can be written at `path`: it is not a folder and
/// its nearest existing parent is a writable folder.
bool checkOutputFile(const std::string& path, std::string& error);

/// True when `path` lies inside the folder `dir` (compared as absolute, normalised paths); `rest`
/// is then its path relative to `dir`.
bool isInside(const std::string& path, const std::string& dir, std::string& rest);

class StagedFolder {
 public:
  StagedFolder() = default;
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;
  /// Not committed: the temporary folder (and any parent folders open() created) is removed.
  ~StagedFolder();

  /// checkOutputFolder, then creates the temporary folder beside `target` (and `target`'s missing
  /// parents). One error line on failure, and nothing left behind.
  bool open(const std::string& target, const std::vector<std::string>& markers, std::string& error);
  /// Where the output is written until commit().
  const std::string& path() const { return staging_; }
  const std::string& target() const { return target_; }
  /// Moves the temporary folder into place, replacing an existing target as a whole.
  bool commit(std::string& error);

 private:
  void discard();
  std::string target_, staging_;
  std::vector<std::string> createdParents_;  // deepest first: removed again if the output is discarded
  std::vector<std::string> markers_;
};

}  // namespace haif
