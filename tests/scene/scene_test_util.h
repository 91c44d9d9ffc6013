// Helpers shared by the scene tests.
#pragma once

#include "haif/world.h"
#include "scene/build_world.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace haif::test {

inline std::string sourceDir() { return HAIF_SOURCE_DIR; }

/// Loads scenes/<name> from the source tree; fails the test on error.
inline SceneDesc loadReferenceScene(const std::string& name) {
  SceneDesc scene;
  std::string error;
  EXPECT_TRUE(loadSceneFile(sourceDir() + "/scenes/" + name, scene, error)) << error;
  return scene;
}

/// The scene's world, solved at `iterations` a step (fixed); null (a failure reported) when it cannot
/// be built.
inline std::unique_ptr<World> worldAt(const SceneDesc& scene, int iterations) {
  WorldSettings s = scene.settings.world;
  s.iterations = iterations;
  auto w = std::make_unique<World>(s);
  std::string error;
  if (buildWorld(scene, *w, error)) return w;
  ADD_FAILURE() << scene.name << ": " << error;
  return nullptr;
}

/// Parses `text` as "mem/test.json", expecting success.
inline SceneDesc parseOk(const std::string& text) {
  SceneDesc scene;
  std::string error;
  EXPECT_TRUE(parseSceneText(text, "mem/test.json", scene, error)) << error;
  return scene;
}

/// Parses `text` as "mem/bad.json", expecting failure; returns the error line.
inline std::string parseError(const std::string& text) {
  SceneDesc scene;
  std::string error;
  EXPECT_FALSE(parseSceneText(text, "mem/bad.json", scene, error)) << "expected an error for:\n" << text;
  return error;
}

inline int countMotion(const SceneDesc& s, MotionType m) {
  int n = 0;
  for (const BodyDesc& b : s.bodies) n += b.motion == m ? 1 : 0;
  return n;
}

// "mem/bad.json:LINE:COL: " of the first occurrence of `needle` in `text` (counted here, ASCII only).
inline std::string at(const std::string& text, const std::string& needle, size_t skip = 0) {
  size_t pos = text.find(needle);
  for (size_t i = 0; i < skip && pos != std::string::npos; ++i) pos = text.find(needle, pos + 1);
  EXPECT_NE(pos, std::string::npos) << needle;
  int line = 1, col = 1;
  for (size_t i = 0; i < pos; ++i) {
    if (text[i] == '\n') ++line, col = 1;
    else ++col;
  }
  return "mem/bad.json:" + std::to_string(line) + ":" + std::to_string(col) + ": ";
}

// A scene whose only body has the given members (after "shape").
inline std::string body(const std::string& members, const std::string& shape = R"({"type": "sphere"})") {
  return "{\n  \"bodies\": [\n    {\"shape\": " + shape + (members.empty() ? "" : ", " + members) + "}\n  ]\n}\n";
}

#define EXPECT_ERROR(text, needle, place_and_message)                               \
  do {                                                                             \
    const std::string t_ = (text);                                                 \
    const std::string e_ = parseError(t_);                                         \
    EXPECT_EQ(e_.rfind(at(t_, needle), 0), 0u) << "error: " << e_;                 \
    EXPECT_NE(e_.find(place_and_message), std::string::npos) << "error: " << e_;   \
    EXPECT_EQ(e_.find('\n'), std::string::npos) << "one line: " << e_;            \
  } while (0)

}  // namespace haif::test
