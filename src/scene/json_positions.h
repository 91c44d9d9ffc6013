// Where every value of a JSON text sits. nlohmann::json keeps no source positions, so after a
// successful parse we scan the (now known valid) text once more and record the byte offset of
// each value and each object key under its JSON pointer. Error messages then name a line:column.
#pragma once

#include <cstddef>
#include <string>
#include <unordered_map>

namespace haif {

/// 1-based line and column (column counts UTF-8 code points, as editors do).
struct TextLocation {
  int line = 1;
  int column = 1;
};

/// Line and column of a byte offset in `text` (offsets past the end clamp to the end).
TextLocation locationOfOffset(const std::string& text, size_t offset);

/// Escape one object key or array index as a JSON pointer reference token (RFC 6901: ~ -> ~0, / -> ~1).
std::string jsonPointerToken(const std::string& key);

/// How deep a JSON text may nest arrays and objects. Scene files and playlists nest a few levels;
/// anything walked recursively (the scanner below, nlohmann's dump() in messages) would overflow the
/// stack on a text of 20,000 '[', so deeper texts are refused before they are walked.
constexpr int kMaxJsonDepth = 256;

/// Offset of the first '[' or '{' (outside strings) that opens level `maxDepth` + 1, or npos.
size_t findTooDeepNesting(const std::string& text, int maxDepth = kMaxJsonDepth);

class JsonPositions {
 public:
  /// Scans `text`, which must be valid JSON. Returns false and sets `duplicateKeyPointer` when an
  /// object repeats a key (nlohmann would silently keep the last one, hiding a mistake), or, with
  /// `duplicateKeyPointer` empty, when the text nests deeper than kMaxJsonDepth (tooDeepOffset()).
  bool scan(const std::string& text, std::string& duplicateKeyPointer);
  /// Where the text first nests too deep (npos when it does not).
  size_t tooDeepOffset() const { return tooDeep_; }

  /// Byte offset of the value at `pointer` ("" is the root); npos if unknown.
  size_t valueOffset(const std::string& pointer) const;
  /// Byte offset of the key that introduces the member at `pointer`; npos for array elements/root.
  size_t keyOffset(const std::string& pointer) const;
  /// Offset of the value at `pointer`, or of its nearest recorded ancestor (never npos after a scan).
  size_t nearestValueOffset(std::string pointer) const;

 private:
  struct Entry {
    size_t value = std::string::npos;
    size_t key = std::string::npos;
  };
  size_t scanValue(size_t pos, const std::string& pointer, std::string& dup, int depth);
  size_t skipString(size_t pos) const;  ///< pos at the opening quote; returns one past the closing quote
  size_t skipSpace(size_t pos) const;

  const std::string* text_ = nullptr;
  size_t tooDeep_ = std::string::npos;
  std::unordered_map<std::string, Entry> entries_;
};

/// Offset of the first number literal in `text` (outside strings) that overflows a double, or npos.
/// nlohmann reports such overflow without a position, so we find it ourselves.
size_t findOverflowingNumber(const std::string& text);

}  // namespace haif
