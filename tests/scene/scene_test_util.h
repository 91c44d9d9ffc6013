// Helpers shared by the scene tests.
#pragma once

#include "scene/scene_loader.h"

#include <gtest/gtest.h>

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

}  // namespace haif::test
