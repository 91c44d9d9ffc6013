// libFuzzer target: the scene loader (JSON text to a validated SceneDesc). Any input must give a
// scene or one error line; a crash, a sanitizer report or a hang is a bug (docs/fuzzing.md).
#include "scene/scene_loader.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  haif::SceneDesc scene;
  std::string error;
  // Asset paths resolve against the scenes folder, so the shipped assets can be reached.
  const bool ok = haif::parseSceneText(text, HAIF_SOURCE_DIR "/scenes/fuzz.json", scene, error);
  if (!ok && (error.empty() || error.find('\n') != std::string::npos)) __builtin_trap();  // one line, always
  return 0;
}
