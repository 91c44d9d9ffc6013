// Typed, checked access to a parsed JSON scene. Every accessor knows the JSON pointer and the
// readable place ("bodies[3].mass") of the value it reads, so the first problem found is thrown
// as a SceneError that the loader turns into `FILE:LINE:COL: PLACE: what is wrong`.
#pragma once

#include "core/math.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace haif {

using Json = nlohmann::json;

/// The first problem found in a scene file.
struct SceneError {
  std::string pointer;  ///< JSON pointer of the offending value (or of its nearest existing parent)
  std::string place;    ///< readable place, e.g. "bodies[3].mass"
  std::string message;  ///< what is wrong, e.g. "must be > 0 for a dynamic body (got -2)"
  bool atKey = false;   ///< locate the member's key rather than its value (unknown keys)
};

/// A value in the document together with where it is; `value` is null when the member is absent.
struct JsonNode {
  const Json* value = nullptr;
  std::string pointer;  ///< "" is the root
  std::string place;    ///< "" is the root

  bool present() const { return value != nullptr; }
  const Json& json() const { return *value; }
  /// Member `key` of an object (absent if this is not an object or has no such key).
  JsonNode member(const std::string& key) const;
  /// Element `i` of an array.
  JsonNode element(size_t i) const;
  /// Number of elements (array) or members (object).
  size_t size() const { return value ? value->size() : 0; }
};

/// Throws SceneError at `node`.
[[noreturn]] void fail(const JsonNode& node, const std::string& message);
/// Throws SceneError pointing at the key of member `key` of `object`.
[[noreturn]] void failAtKey(const JsonNode& object, const std::string& key, const std::string& message);

/// `text` with control characters written as escapes (\n, \t, \u0001), so a message that quotes a
/// key, a string or a path from the input stays one line. Idempotent: applying it twice is harmless.
std::string oneLine(const std::string& text);
/// Short text of a value for "(got ...)" parts of messages.
std::string describeValue(const Json& v);
/// A number as people write it, to float precision: -2, 0.5, 1e+30.
std::string formatNumber(double v);
/// " (did you mean 'x'?)" when one of `options` is a close spelling of `word`, else "".
std::string didYouMean(const std::string& word, const std::vector<std::string>& options);

void requireObject(const JsonNode& node);
void requireArray(const JsonNode& node);
/// Rejects members not in `allowed` (keys starting with '_' are comments and always allowed).
void checkKeys(const JsonNode& object, const std::vector<std::string>& allowed);
/// The member `key`, which must be present.
JsonNode requireMember(const JsonNode& object, const std::string& key, const std::string& hint = "");

double readNumber(const JsonNode& node);  ///< finite number, else SceneError
float readFloat(const JsonNode& node);    ///< finite number that fits a float
int readInt(const JsonNode& node, int lo, int hi);
bool readBool(const JsonNode& node);
std::string readString(const JsonNode& node);
Vec3 readVec3(const JsonNode& node);
/// A vector given either as [x, y, z] or as one number s meaning (s, s, s).
Vec3 readVec3OrScalar(const JsonNode& node);

/// Range checks that throw with the value in the message ("must be > 0 (got -2)").
float readPositive(const JsonNode& node);
float readNonNegative(const JsonNode& node);
Vec3 readPositiveVec3(const JsonNode& node);  ///< every component > 0 (accepts a scalar too)

/// Optional members with defaults.
float optFloat(const JsonNode& object, const std::string& key, float def);
float optPositive(const JsonNode& object, const std::string& key, float def);
float optNonNegative(const JsonNode& object, const std::string& key, float def);
int optInt(const JsonNode& object, const std::string& key, int def, int lo, int hi);
Vec3 optVec3(const JsonNode& object, const std::string& key, const Vec3& def);

}  // namespace haif
