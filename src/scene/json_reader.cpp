#include "scene/json_reader.h"

#include "scene/json_positions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace haif {

JsonNode JsonNode::member(const std::string& key) const {
  JsonNode n;
  n.pointer = pointer + "/" + jsonPointerToken(key);
  n.place = place.empty() ? key : place + "." + key;
  if (value && value->is_object()) {
    auto it = value->find(key);
    if (it != value->end()) n.value = &*it;
  }
  return n;
}

JsonNode JsonNode::element(size_t i) const {
  JsonNode n;
  n.pointer = pointer + "/" + std::to_string(i);
  n.place = place + "[" + std::to_string(i) + "]";
  if (value && value->is_array() && i < value->size()) n.value = &(*value)[i];
  return n;
}

std::string oneLine(const std::string& text) {
  static const char* const kHex = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c != 0x7f) {
      out += ch;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      out += "\\u00";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

// Places and messages quote keys and strings from the input, which may hold escaped newlines.
void fail(const JsonNode& node, const std::string& message) {
  throw SceneError{node.pointer, node.place.empty() ? "scene" : oneLine(node.place), oneLine(message), false};
}

void failAtKey(const JsonNode& object, const std::string& key, const std::string& message) {
  const JsonNode m = object.member(key);
  throw SceneError{m.pointer, oneLine(m.place), oneLine(message), true};
}

std::string formatNumber(double v) {
  std::ostringstream s;
  s.precision(7);  // float precision: -0.01f prints as the user wrote it, not -0.00999999978
  s << v;
  return s.str();
}

std::string describeValue(const Json& v) {
  switch (v.type()) {
    case Json::value_t::null: return "null";
    case Json::value_t::boolean: return v.get<bool>() ? "true" : "false";
    case Json::value_t::string: {
      std::string s = v.dump();
      return s.size() > 40 ? "string " + s.substr(0, 37) + "...\"" : "string " + s;
    }
    case Json::value_t::array: return "an array of " + std::to_string(v.size());
    case Json::value_t::object: return "an object";
    default: return v.is_number() ? formatNumber(v.get<double>()) : v.dump();
  }
}

// Edit distance (insert, delete, substitute, swap of neighbours): typos are usually one of these.
static size_t editDistance(const std::string& a, const std::string& b) {
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (size_t i = 1; i <= n; ++i)
    for (size_t j = 1; j <= m; ++j) {
      const size_t cost = std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

std::string didYouMean(const std::string& word, const std::vector<std::string>& options) {
  // A truncated name ("euler" for "euler_deg") is the most common slip after a typo.
  if (word.size() >= 3)
    for (const std::string& o : options)
      if (o.size() > word.size() && o.compare(0, word.size(), word) == 0) return " (did you mean '" + o + "'?)";
  std::string best;
  size_t bestDist = std::numeric_limits<size_t>::max();
  for (const std::string& o : options) {
    const size_t dist = editDistance(word, o);
    if (dist < bestDist) {
      bestDist = dist;
      best = o;
    }
  }
  // Allow about one typo per three letters, at least one.
  const size_t limit = std::max<size_t>(1, std::max(word.size(), best.size()) / 3);
  return (!best.empty() && bestDist <= limit) ? " (did you mean '" + best + "'?)" : "";
}

void requireObject(const JsonNode& node) {
  if (!node.value->is_object()) fail(node, "must be an object {...} (got " + describeValue(node.json()) + ")");
}

void requireArray(const JsonNode& node) {
  if (!node.value->is_array()) fail(node, "must be an array [...] (got " + describeValue(node.json()) + ")");
}

void checkKeys(const JsonNode& object, const std::vector<std::string>& allowed) {
  requireObject(object);
  for (auto it = object.json().begin(); it != object.json().end(); ++it) {
    const std::string& key = it.key();
    if (!key.empty() && key[0] == '_') continue;
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string known;
    for (const std::string& a : allowed) known += (known.empty() ? "" : ", ") + a;
    const std::string hint = didYouMean(key, allowed);
    failAtKey(object, key, "unknown key" + (hint.empty() ? " (known keys: " + known + ")" : hint));
  }
}

JsonNode requireMember(const JsonNode& object, const std::string& key, const std::string& hint) {
  JsonNode m = object.member(key);
  if (!m.present()) fail(object, "missing required key '" + key + "'" + (hint.empty() ? "" : " (" + hint + ")"));
  return m;
}

double readNumber(const JsonNode& node) {
  const Json& v = node.json();
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (s == "nan" || s == "inf" || s == "-inf" || s == "+inf" || s == "infinity" || s == "-infinity")
      fail(node, "must be a finite number (got " + describeValue(v) + "; NaN and infinity are not allowed)");
  }
  if (!v.is_number()) fail(node, "must be a number (got " + describeValue(v) + ")");
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(node, "must be a finite number (got " + v.dump() + ")");
  return d;
}

float readFloat(const JsonNode& node) {
  const double d = readNumber(node);
  if (std::fabs(d) > static_cast<double>(std::numeric_limits<float>::max()))
    fail(node, "number out of range (got " + formatNumber(d) + "; the engine uses 32-bit floats, |x| <= 3.4e38)");
  return static_cast<float>(d);
}

int readInt(const JsonNode& node, int lo, int hi) {
  const Json& v = node.json();
  if (!v.is_number_integer()) fail(node, "must be an integer (got " + describeValue(v) + ")");
  const bool neg = v.is_number_unsigned() ? false : v.get<int64_t>() < 0;
  const int64_t i = neg ? v.get<int64_t>() : static_cast<int64_t>(std::min<uint64_t>(v.get<uint64_t>(), INT64_MAX));
  if (i < lo || i > hi) {
    std::string range = hi == std::numeric_limits<int>::max() ? ">= " + std::to_string(lo)
                                                              : "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    fail(node, "must be " + range + " (got " + v.dump() + ")");
  }
  return static_cast<int>(i);
}

bool readBool(const JsonNode& node) {
  if (!node.json().is_boolean()) fail(node, "must be true or false (got " + describeValue(node.json()) + ")");
  return node.json().get<bool>();
}

std::string readString(const JsonNode& node) {
  if (!node.json().is_string()) fail(node, "must be a string (got " + describeValue(node.json()) + ")");
  return node.json().get<std::string>();
}

Vec3 readVec3(const JsonNode& node) {
  const Json& v = node.json();
  if (!v.is_array() || v.size() != 3)
    fail(node, "must be an array of 3 numbers [x, y, z] (got " + describeValue(v) + ")");
  return Vec3(readFloat(node.element(0)), readFloat(node.element(1)), readFloat(node.element(2)));
}

Vec3 readVec3OrScalar(const JsonNode& node) {
  if (node.json().is_number()) return Vec3::Constant(readFloat(node));
  if (!node.json().is_array())
    fail(node, "must be a number or an array of 3 numbers [x, y, z] (got " + describeValue(node.json()) + ")");
  return readVec3(node);
}

float readPositive(const JsonNode& node) {
  const float f = readFloat(node);
  if (!(f > 0.0f)) {
    // The value as written: 1e-300 is > 0 as a double and rounds to 0 as a float.
    const double d = readNumber(node);
    fail(node, d > 0.0 ? "must be > 0 (got " + formatNumber(d) + ", which is 0 in the engine's 32-bit floats)"
                       : "must be > 0 (got " + formatNumber(d) + ")");
  }
  return f;
}

float readNonNegative(const JsonNode& node) {
  const float f = readFloat(node);
  if (f < 0.0f) fail(node, "must be >= 0 (got " + formatNumber(f) + ")");
  return f;
}

Vec3 readPositiveVec3(const JsonNode& node) {
  if (node.json().is_number()) return Vec3::Constant(readPositive(node));
  const Vec3 v = readVec3(node);
  for (int i = 0; i < 3; ++i)
    if (!(v[i] > 0.0f)) fail(node.element(static_cast<size_t>(i)), "must be > 0 (got " + formatNumber(v[i]) + ")");
  return v;
}

float optFloat(const JsonNode& object, const std::string& key, float def) {
  const JsonNode m = object.member(key);
  return m.present() ? readFloat(m) : def;
}

float optPositive(const JsonNode& object, const std::string& key, float def) {
  const JsonNode m = object.member(key);
  return m.present() ? readPositive(m) : def;
}

float optNonNegative(const JsonNode& object, const std::string& key, float def) {
  const JsonNode m = object.member(key);
  return m.present() ? readNonNegative(m) : def;
}

int optInt(const JsonNode& object, const std::string& key, int def, int lo, int hi) {
  const JsonNode m = object.member(key);
  return m.present() ? readInt(m, lo, hi) : def;
}

Vec3 optVec3(const JsonNode& object, const std::string& key, const Vec3& def) {
  const JsonNode m = object.member(key);
  return m.present() ? readVec3(m) : def;
}

}  // namespace haif
