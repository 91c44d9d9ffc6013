// Minimal command-line parsing for the haif subcommands: --key value options, flags and positionals,
// with one clear message for anything malformed.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace haif {

class CommandLine {
 public:
  /// `valued`: options that take a value; `flags`: options that do not.
  CommandLine(std::string command, std::set<std::string> valued, std::set<std::string> flags)
      : command_(std::move(command)), valued_(std::move(valued)), flags_(std::move(flags)) {}

  /// Parses argv[first..argc). Returns false with `error` set on an unknown or incomplete option.
  bool parse(int argc, char** argv, int first, std::string& error);

  bool has(const std::string& key) const { return values_.count(key) || set_.count(key); }
  std::string get(const std::string& key, const std::string& fallback = "") const;
  const std::vector<std::string>& positional() const { return positional_; }

  /// Typed getters: false with `error` ("haif run: --frames: expected ...") when the value is bad.
  bool getInt(const std::string& key, int lo, int hi, int& out, std::string& error) const;
  bool getDouble(const std::string& key, double lo, double hi, double& out, std::string& error) const;

 private:
  std::string command_;
  std::set<std::string> valued_, flags_;
  std::map<std::string, std::string> values_;
  std::set<std::string> set_;
  std::vector<std::string> positional_;
};

/// The command as typed, "haif ARG ...", each argument shell-quoted unless it is plainly safe: what a
/// report records so its run can be repeated.
std::string commandLineOf(int argc, char** argv);

}  // namespace haif
