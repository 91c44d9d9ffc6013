// libFuzzer target: the `haif reel` playlist parser, which also loads every scene it names
// (docs/fuzzing.md).
#include "app/reel_playlist.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  haif::ReelPlaylist playlist;
  std::string error;
  // Beside scenes/reel.json, so its items' scene paths reach the shipped scenes.
  const bool ok = haif::parseReelPlaylistText(text, HAIF_SOURCE_DIR "/scenes/fuzz_reel.json", playlist, error);
  if (!ok && (error.empty() || error.find('\n') != std::string::npos)) __builtin_trap();  // one line, always
  return 0;
}
