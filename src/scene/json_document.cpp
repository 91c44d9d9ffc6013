#include "scene/json_document.h"

namespace haif {

std::string jsonSyntaxMessage(const std::string& what) {
  const size_t column = what.find("column ");
  const size_t colon = column == std::string::npos ? std::string::npos : what.find(": ", column);
  if (colon != std::string::npos) return what.substr(colon + 2);
  const size_t bracket = what.find("] ");
  return bracket == std::string::npos ? what : what.substr(bracket + 2);
}

bool parseJsonDocument(const std::string& text, const std::string& path, Json& doc, JsonPositions& positions,
                       std::string& error) {
  auto at = [&](size_t offset) {
    const TextLocation loc = locationOfOffset(text, offset);
    return path + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) + ": ";
  };
  const size_t deep = findTooDeepNesting(text);
  if (deep != std::string::npos) {
    error = at(deep) + "syntax error: nested deeper than " + std::to_string(kMaxJsonDepth) + " levels of [ and {";
    return false;
  }
  try {
    doc = Json::parse(text);
  } catch (const Json::exception& e) {
    const auto* pe = dynamic_cast<const Json::parse_error*>(&e);
    error = at(pe && pe->byte > 0 ? pe->byte - 1 : 0) + "syntax error: " + jsonSyntaxMessage(e.what());
    return false;
  }
  std::string duplicate;
  if (!positions.scan(text, duplicate)) {
    error = at(positions.keyOffset(duplicate)) + "duplicate key at " + duplicate;
    return false;
  }
  return true;
}

uint64_t fnv1aHash(const std::string& text) {
  uint64_t hash = 0xcbf29ce484222325ull;
  for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return hash;
}

}  // namespace haif
