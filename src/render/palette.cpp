#include "render/palette.h"

#include <algorithm>
#include <cmath>

namespace haif::render {
namespace {

// Muted, distinguishable sRGB colours that read well under a warm sun and a grey ground.
constexpr float kPalette[][3] = {
    {0.90f, 0.42f, 0.35f}, {0.95f, 0.68f, 0.30f}, {0.93f, 0.83f, 0.40f}, {0.55f, 0.78f, 0.42f},
    {0.30f, 0.70f, 0.62f}, {0.35f, 0.62f, 0.85f}, {0.50f, 0.50f, 0.86f}, {0.72f, 0.48f, 0.80f},
    {0.90f, 0.52f, 0.68f}, {0.62f, 0.45f, 0.35f}, {0.45f, 0.82f, 0.85f}, {0.80f, 0.80f, 0.78f},
};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

// Perceptual-ish ramp (sRGB stops), in the spirit of viridis, for heat mode.
constexpr float kHeat[][3] = {
    {0.18f, 0.10f, 0.38f}, {0.20f, 0.33f, 0.58f}, {0.15f, 0.55f, 0.56f},
    {0.30f, 0.72f, 0.42f}, {0.70f, 0.84f, 0.20f}, {0.99f, 0.91f, 0.15f},
};
constexpr int kHeatSize = sizeof(kHeat) / sizeof(kHeat[0]);

LinearColor fromSrgb(const float c[3], float scale = 1.f) {
  return {srgbToLinear(std::min(1.f, c[0] * scale)), srgbToLinear(std::min(1.f, c[1] * scale)),
          srgbToLinear(std::min(1.f, c[2] * scale))};
}

}  // namespace

float srgbToLinear(float c) {
  c = std::clamp(c, 0.f, 1.f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float c) {
  c = std::clamp(c, 0.f, 1.f);
  return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.f / 2.4f) - 0.055f;
}

uint32_t hashId(uint32_t x) {
  // Murmur3 finaliser: cheap and avalanches well.
  x ^= x >> 16;
  x *= 0x85ebca6bu;
  x ^= x >> 13;
  x *= 0xc2b2ae35u;
  x ^= x >> 16;
  return x;
}

LinearColor idColor(uint32_t id) {
  const uint32_t h = hashId(id);
  const float* c = kPalette[h % kPaletteSize];
  // A little brightness jitter so two neighbours with the same entry still separate.
  const float scale = 0.88f + 0.2f * static_cast<float>((h >> 8) & 0xff) / 255.f;
  return fromSrgb(c, scale);
}

LinearColor heatColor(float t) {
  if (!(t >= 0.f)) t = 0.f;  // also catches NaN
  t = std::min(t, 1.f) * (kHeatSize - 1);
  const int i = std::min(static_cast<int>(t), kHeatSize - 2);
  const float f = t - static_cast<float>(i);
  float c[3];
  for (int k = 0; k < 3; ++k) c[k] = kHeat[i][k] + (kHeat[i + 1][k] - kHeat[i][k]) * f;
  return fromSrgb(c);
}

LinearColor instanceColor(const Instance& inst, ViewMode mode) {
  static const float kStatic[3] = {0.55f, 0.55f, 0.56f};
  static const float kAwake[3] = {0.95f, 0.60f, 0.28f};
  static const float kAsleep[3] = {0.48f, 0.56f, 0.70f};
  if (inst.isStatic) return fromSrgb(kStatic);
  switch (mode) {
    case ViewMode::Island:
      return inst.sleeping ? fromSrgb(kAsleep, 0.8f) : idColor(inst.islandId * 2654435761u + 17u);
    case ViewMode::Sleep:
      return fromSrgb(inst.sleeping ? kAsleep : kAwake);
    case ViewMode::Heat:
      return heatColor(inst.heat);
    case ViewMode::Normal:
    default:
      return inst.useColor ? fromSrgb(inst.color) : idColor(inst.bodyId);
  }
}

}  // namespace haif::render
