#include "render/hidden_box_faces.h"

#include <algorithm>
#include <cmath>

namespace haif::render {
namespace {

constexpr uint32_t kNone = 0xffffffffu;

uint32_t hashCell(int x, int y, int z, uint32_t bucketMask) {
  const uint32_t h = static_cast<uint32_t>(x) * 73856093u ^ static_cast<uint32_t>(y) * 19349663u ^
                     static_cast<uint32_t>(z) * 83492791u;
  return h & bucketMask;
}

int cellOf(float v, float cell) { return static_cast<int>(std::floor(v / cell)); }

}  // namespace

float HiddenBoxFaces::tolerance(Vec3 half) { return 0.01f * std::min({half.x, half.y, half.z}); }

void HiddenBoxFaces::find(const std::vector<BoxPose>& boxes, std::vector<uint8_t>& masks) {
  const size_t n = boxes.size();
  masks.assign(n, 0);
  if (n < 2) return;
  radius_.resize(n);
  scratch_.resize(n);
  axes_.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    const BoxPose& b = boxes[i];
    radius_[i] = std::isfinite(length(b.half)) ? length(b.half) : -1.f;  // -1: skipped
    scratch_[i] = radius_[i];
    axes_[3 * i] = rotate(b.orientation, {1.f, 0.f, 0.f});
    axes_[3 * i + 1] = rotate(b.orientation, {0.f, 1.f, 0.f});
    axes_[3 * i + 2] = rotate(b.orientation, {0.f, 0.f, 1.f});
  }
  // Boxes much larger than the typical one (the ground) stay out of the grid and are tried as
  // coverers of every box; the grid cell fits the largest of the others.
  std::nth_element(scratch_.begin(), scratch_.begin() + n / 2, scratch_.end());
  const float bigRadius = 4.f * std::max(scratch_[n / 2], 1e-6f);
  float maxRadius = 0.f;
  big_.clear();
  for (size_t i = 0; i < n; ++i) {
    if (!(radius_[i] >= 0.f) || !std::isfinite(boxes[i].center.x + boxes[i].center.y + boxes[i].center.z)) {
      radius_[i] = -1.f;
      continue;
    }
    if (radius_[i] > bigRadius)
      big_.push_back(static_cast<uint32_t>(i));
    else
      maxRadius = std::max(maxRadius, radius_[i]);
  }
  const float cell = std::max(2.02f * maxRadius, 1e-6f);

  uint32_t buckets = 1;
  while (buckets < 2 * n) buckets <<= 1;
  const uint32_t bucketMask = buckets - 1;
  cellStart_.assign(buckets + 1, 0);
  bucketOf_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 c = boxes[i].center;
    const bool inGrid = radius_[i] >= 0.f && radius_[i] <= bigRadius;
    bucketOf_[i] = inGrid ? hashCell(cellOf(c.x, cell), cellOf(c.y, cell), cellOf(c.z, cell), bucketMask) : kNone;
    if (inGrid) ++cellStart_[bucketOf_[i] + 1];
  }
  for (uint32_t b = 0; b < buckets; ++b) cellStart_[b + 1] += cellStart_[b];
  cellBoxes_.resize(cellStart_[buckets]);
  // Counting sort: place each box at the cursor of its bucket, then shift the cursors (which end
  // at the next bucket's start) back by one bucket.
  for (size_t i = 0; i < n; ++i)
    if (bucketOf_[i] != kNone) cellBoxes_[cellStart_[bucketOf_[i]]++] = static_cast<uint32_t>(i);
  for (uint32_t b = buckets; b > 0; --b) cellStart_[b] = cellStart_[b - 1];
  cellStart_[0] = 0;

  // Tests whether faces of box i lie inside box j; sets their bits in masks[i].
  auto tryCover = [&](size_t i, size_t j) {
    if (i == j || radius_[j] < 0.f) return;
    const BoxPose& a = boxes[i];
    const BoxPose& b = boxes[j];
    const Vec3 d = a.center - b.center;
    const float tol = tolerance(a.half);
    const float reach = radius_[i] + radius_[j] + tol;
    if (dot(d, d) > reach * reach) return;
    const Vec3* ai = &axes_[3 * i];
    const Vec3* bj = &axes_[3 * j];
    // Box i's centre and scaled axes in box j's frame.
    const float halfI[3] = {a.half.x, a.half.y, a.half.z};
    const float limit[3] = {b.half.x + tol, b.half.y + tol, b.half.z + tol};
    float c[3], ax[3][3];
    for (int m = 0; m < 3; ++m) {
      c[m] = dot(d, bj[m]);
      for (int k = 0; k < 3; ++k) ax[k][m] = dot(ai[k], bj[m]) * halfI[k];
    }
    uint8_t inside = 0;  // bit k: corner k (bit t of k set = +half along axis t of box i) inside j
    for (int k = 0; k < 8; ++k) {
      bool in = true;
      for (int m = 0; m < 3 && in; ++m) {
        float p = c[m];
        for (int t = 0; t < 3; ++t) p += (k >> t & 1) ? ax[t][m] : -ax[t][m];
        in = std::fabs(p) <= limit[m];
      }
      if (in) inside |= static_cast<uint8_t>(1u << k);
    }
    if (!inside) return;
    for (int axis = 0; axis < 3; ++axis)
      for (int side = -1; side <= 1; side += 2) {
        uint8_t corners = 0;  // the four corners on this face
        for (int k = 0; k < 8; ++k)
          if (((k >> axis) & 1) == (side > 0 ? 1 : 0)) corners |= static_cast<uint8_t>(1u << k);
        if ((inside & corners) != corners) continue;
        // Box j must reach past the face's plane, or two overlapping boxes could hide each other.
        if (static_cast<float>(side) * -dot(d, ai[axis]) <= halfI[axis]) continue;
        masks[i] |= boxFaceBit(axis, side);
      }
  };

  for (size_t i = 0; i < n; ++i) {
    if (radius_[i] < 0.f) continue;
    for (uint32_t j : big_) tryCover(i, j);
    if (bucketOf_[i] == kNone) continue;  // big boxes are only covered by other big ones
    const Vec3 c = boxes[i].center;
    const int cx = cellOf(c.x, cell), cy = cellOf(c.y, cell), cz = cellOf(c.z, cell);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const uint32_t b = hashCell(cx + dx, cy + dy, cz + dz, bucketMask);
          for (uint32_t k = cellStart_[b]; k < cellStart_[b + 1]; ++k) tryCover(i, cellBoxes_[k]);
        }
  }
}

}  // namespace haif::render
