// libFuzzer target: the PNG reader of `haif diff` (docs/fuzzing.md).
#include "render/png_io.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  int w = 0, h = 0;
  std::vector<uint8_t> rgba;
  std::string error;
  // The same code as readPng with a smaller pixel bound: a header claiming 8192 x 8192 pixels
  // costs a 256 MiB buffer per input, which would only slow the search down.
  if (haif::render::decodePng(data, size, "fuzz.png", &w, &h, &rgba, &error, uint64_t(1) << 20)) {
    if (w <= 0 || h <= 0 || rgba.size() != size_t(w) * size_t(h) * 4) __builtin_trap();
  } else if (error.empty()) {
    __builtin_trap();
  }
  return 0;
}
