#include "tools/staged_output.h"

#include "tools/atomic_file.h"
#include "tools/interrupts.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <unistd.h>

namespace haif {

namespace fs = std::filesystem;

namespace {

// The absolute, normalised form of `p` without a trailing separator ("out/" names "out").
fs::path normalised(const std::string& p) {
  std::error_code ec;
  fs::path a = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) a = fs::absolute(p).lexically_normal();
  if (a.filename().empty() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();
  return a;
}

// The nearest folder of `p`'s parents that exists ("" when none does).
fs::path nearestExistingParent(const fs::path& p) {
  std::error_code ec;
  for (fs::path q = p.parent_path(); !q.empty(); q = q.parent_path()) {
    if (fs::exists(q, ec)) return q;
    if (q == q.root_path()) break;
  }
  return {};
}

bool checkParentWritable(const std::string& shown, const fs::path& p, std::string& error) {
  const fs::path parent = nearestExistingParent(p);
  std::error_code ec;
  if (parent.empty() || !fs::is_directory(parent, ec)) {
    error = shown + ": cannot be created (" + (parent.empty() ? std::string("no parent folder") : parent.string() + " is not a folder") + ")";
    return false;
  }
  if (::access(parent.c_str(), W_OK) != 0) {
    error = shown + ": cannot be created (" + parent.string() + " is not writable: " + std::strerror(errno) + ")";
    return false;
  }
  return true;
}

}  // namespace

bool isInside(const std::string& path, const std::string& dir, std::string& rest) {
  const fs::path rel = normalised(path).lexically_relative(normalised(dir));
  if (rel.empty() || rel == "." || *rel.begin() == "..") return false;
  rest = rel.string();
  return true;
}

bool checkOutputFolder(const std::string& target, const std::vector<std::string>& markers, std::string& error) {
  if (target.empty()) {
    error = "output folder: the path is empty";
    return false;
  }
  const fs::path t = normalised(target);
  std::error_code ec;
  if (t == t.root_path() || !t.has_parent_path()) {
    error = target + ": cannot be an output folder (it is the root folder)";
    return false;
  }
  std::string rest;
  if (isInside(fs::current_path(ec).string(), t.string(), rest) || normalised(".") == t) {
    error = target + ": cannot be an output folder: it holds the current folder, and an output folder is replaced as a whole";
    return false;
  }
  if (fs::exists(fs::symlink_status(t, ec))) {
    if (!fs::is_directory(fs::symlink_status(t, ec))) {
      error = target + ": exists and is not a folder";
      return false;
    }
    bool empty = fs::is_empty(t, ec);
    bool marked = false;
    for (const std::string& m : markers) marked = marked || fs::exists(t / m, ec);
    if (!empty && !marked) {
      std::string names;
      for (const std::string& m : markers) names += (names.empty() ? "" : " or ") + m;
      error = target + ": exists and is not an output folder of this command (no " + names +
              " in it); an output folder is replaced as a whole, so choose a new folder or remove this one";
      return false;
    }
  }
  return checkParentWritable(target, t, error);
}

bool checkOutputFile(const std::string& path, std::string& error) {
  if (path.empty()) {
    error = "output file: the path is empty";
    return false;
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    error = path + ": is a directory, not a file";
    return false;
  }
  return checkParentWritable(path, normalised(path), error);
}

StagedFolder::~StagedFolder() { discard(); }

bool StagedFolder::open(const std::string& target, const std::vector<std::string>& markers, std::string& error) {
  discard();
  if (!checkOutputFolder(target, markers, error)) return false;
  const fs::path t = normalised(target);
  std::error_code ec;
  std::vector<fs::path> missing;
  for (fs::path q = t.parent_path(); !fs::exists(q, ec) && q != q.root_path(); q = q.parent_path()) missing.push_back(q);
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!fs::create_directory(*it, ec) && ec) {
      error = target + ": cannot create output folder (" + it->string() + ": " + ec.message() + ")";
      discard();
      return false;
    }
    createdParents_.insert(createdParents_.begin(), it->string());
    registerTemporary(it->string());
  }
  target_ = t.string();
  markers_ = markers;
  staging_ = temporaryPathFor(target_);  // the same .NAME.tmpPID beside it as a file written atomically
  fs::remove_all(staging_, ec);  // left by an earlier process of the same id that was killed
  registerTemporary(staging_);
  if (!fs::create_directory(staging_, ec)) {
    error = target + ": cannot create output folder (" + (ec ? ec.message() : "it exists") + ")";
    discard();
    return false;
  }
  return true;
}

bool StagedFolder::commit(std::string& error) {
  if (staging_.empty()) {
    error = "output folder: nothing to commit";
    return false;
  }
  // The target may have appeared or changed while the command ran: check it again.
  if (!checkOutputFolder(target_, markers_, error)) {
    discard();
    return false;
  }
  std::error_code ec;
  bool placed = false;
  if (fs::exists(target_, ec)) {
    // One atomic swap: a reader sees the old folder or the new one, never neither.
    if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
      placed = true;
    } else {
      // File systems without RENAME_EXCHANGE: the old folder steps aside first.
      const std::string old = staging_ + ".old";
      if (std::rename(target_.c_str(), old.c_str()) == 0) {
        registerTemporary(old);
        if (std::rename(staging_.c_str(), target_.c_str()) == 0) {
          placed = true;
          fs::remove_all(old, ec);
        } else {
          std::rename(old.c_str(), target_.c_str());
        }
        releaseTemporary(old);
      }
    }
    if (placed) fs::remove_all(staging_, ec);  // after the swap it holds the old output
  } else {
    placed = std::rename(staging_.c_str(), target_.c_str()) == 0;
  }
  if (!placed) {
    error = target_ + ": cannot move the finished output into place (" + std::strerror(errno) + ")";
    discard();
    return false;
  }
  releaseTemporary(staging_);
  staging_.clear();
  for (const std::string& p : createdParents_) releaseTemporary(p);
  createdParents_.clear();
  return true;
}

void StagedFolder::discard() {
  std::error_code ec;
  if (!staging_.empty()) {
    fs::remove_all(staging_, ec);
    releaseTemporary(staging_);
    staging_.clear();
  }
  for (const std::string& p : createdParents_) {  // deepest first; only if still empty
    fs::remove(p, ec);
    releaseTemporary(p);
  }
  createdParents_.clear();
}

}  // namespace haif
