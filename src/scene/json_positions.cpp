#include "scene/json_positions.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace haif {

TextLocation locationOfOffset(const std::string& text, size_t offset) {
  TextLocation loc;
  const size_t end = std::min(offset, text.size());
  for (size_t i = 0; i < end; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++loc.line;
      loc.column = 1;
    } else if ((c & 0xC0) != 0x80) {  // UTF-8 continuation bytes do not start a new column
      ++loc.column;
    }
  }
  return loc;
}

std::string jsonPointerToken(const std::string& key) {
  std::string out;
  out.reserve(key.size());
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

size_t JsonPositions::skipSpace(size_t pos) const {
  const std::string& t = *text_;
  while (pos < t.size() && (t[pos] == ' ' || t[pos] == '\t' || t[pos] == '\n' || t[pos] == '\r')) ++pos;
  return pos;
}

size_t JsonPositions::skipString(size_t pos) const {
  const std::string& t = *text_;
  ++pos;  // opening quote
  while (pos < t.size() && t[pos] != '"') pos += (t[pos] == '\\') ? 2 : 1;
  return pos + 1;
}

size_t findTooDeepNesting(const std::string& text, int maxDepth) {
  int depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"') {  // brackets inside strings do not nest
      ++i;
      while (i < text.size() && text[i] != '"') i += (text[i] == '\\') ? 2 : 1;
    } else if (c == '[' || c == '{') {
      if (++depth > maxDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

bool JsonPositions::scan(const std::string& text, std::string& duplicateKeyPointer) {
  text_ = &text;
  entries_.clear();
  duplicateKeyPointer.clear();
  // Checked before the recursive walk, which would otherwise run out of stack.
  tooDeep_ = findTooDeepNesting(text);
  if (tooDeep_ != std::string::npos) return false;
  scanValue(skipSpace(0), "", duplicateKeyPointer, 0);
  return duplicateKeyPointer.empty() && tooDeep_ == std::string::npos;
}

size_t JsonPositions::scanValue(size_t pos, const std::string& pointer, std::string& dup, int depth) {
  const std::string& t = *text_;
  entries_[pointer].value = pos;
  if (pos >= t.size()) return pos;
  const char c = t[pos];
  if ((c == '{' || c == '[') && depth >= kMaxJsonDepth) {  // unreachable after the check in scan()
    if (tooDeep_ == std::string::npos) tooDeep_ = pos;
    return t.size();
  }
  if (c == '{') {
    pos = skipSpace(pos + 1);
    if (pos < t.size() && t[pos] == '}') return pos + 1;
    while (pos < t.size()) {
      const size_t keyStart = pos;
      const size_t keyEnd = skipString(pos);
      std::string key = t.substr(keyStart + 1, keyEnd - keyStart - 2);
      // Keys with escapes are rare: let nlohmann decode them exactly.
      if (key.find('\\') != std::string::npos) key = nlohmann::json::parse(t.substr(keyStart, keyEnd - keyStart)).get<std::string>();
      const std::string child = pointer + "/" + jsonPointerToken(key);
      Entry& e = entries_[child];
      if (e.key != std::string::npos && dup.empty()) dup = child;
      e.key = keyStart;
      pos = skipSpace(keyEnd);
      pos = skipSpace(pos + 1);  // ':'
      pos = skipSpace(scanValue(pos, child, dup, depth + 1));
      if (pos < t.size() && t[pos] == ',') {
        pos = skipSpace(pos + 1);
        continue;
      }
      return pos + 1;  // '}'
    }
    return pos;
  }
  if (c == '[') {
    pos = skipSpace(pos + 1);
    if (pos < t.size() && t[pos] == ']') return pos + 1;
    for (size_t index = 0; pos < t.size(); ++index) {
      pos = skipSpace(scanValue(pos, pointer + "/" + std::to_string(index), dup, depth + 1));
      if (pos < t.size() && t[pos] == ',') {
        pos = skipSpace(pos + 1);
        continue;
      }
      return pos + 1;  // ']'
    }
    return pos;
  }
  if (c == '"') return skipString(pos);
  // number or literal: runs until a delimiter
  while (pos < t.size() && t[pos] != ',' && t[pos] != '}' && t[pos] != ']' && t[pos] != ' ' && t[pos] != '\n' &&
         t[pos] != '\r' && t[pos] != '\t')
    ++pos;
  return pos;
}

size_t JsonPositions::valueOffset(const std::string& pointer) const {
  auto it = entries_.find(pointer);
  return it == entries_.end() ? std::string::npos : it->second.value;
}

size_t JsonPositions::keyOffset(const std::string& pointer) const {
  auto it = entries_.find(pointer);
  return it == entries_.end() ? std::string::npos : it->second.key;
}

size_t JsonPositions::nearestValueOffset(std::string pointer) const {
  for (;;) {
    const size_t off = valueOffset(pointer);
    if (off != std::string::npos) return off;
    if (pointer.empty()) return 0;
    pointer.resize(pointer.rfind('/'));
  }
}

size_t findOverflowingNumber(const std::string& text) {
  size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '"') {  // skip strings: digits inside them are not numbers
      ++i;
      while (i < text.size() && text[i] != '"') i += (text[i] == '\\') ? 2 : 1;
      ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t j = i + 1;
      while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.' ||
                                 text[j] == 'e' || text[j] == 'E' || text[j] == '+' || text[j] == '-'))
        ++j;
      const double v = std::strtod(text.substr(i, j - i).c_str(), nullptr);
      if (!std::isfinite(v)) return i;
      i = j;
    } else {
      ++i;
    }
  }
  return std::string::npos;
}

}  // namespace haif
