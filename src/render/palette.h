// Colours for bodies: stable per-id picks from a hand-made palette, sleep/static greys and a heat
// map. All results are linear RGB (the shaders light in linear space and encode sRGB at the end).
#pragma once

#include <cstdint>

#include "render/frame_input.h"

namespace haif::render {

struct LinearColor {
  float r = 0.f, g = 0.f, b = 0.f;
};

/// sRGB-encoded channel in [0,1] -> linear.
float srgbToLinear(float c);
/// Linear channel in [0,1] -> sRGB-encoded.
float linearToSrgb(float c);

/// Well-mixed 32-bit hash so that neighbouring ids get unrelated colours.
uint32_t hashId(uint32_t id);
/// Deterministic pleasant colour for an id (palette entry with a small brightness variation).
LinearColor idColor(uint32_t id);
/// Heat map colour for t in [0,1] (clamped): dark blue -> teal -> green -> yellow.
LinearColor heatColor(float t);
/// The colour an instance gets in the given view mode (ground excluded: it has its own look).
LinearColor instanceColor(const Instance& inst, ViewMode mode);

}  // namespace haif::render
