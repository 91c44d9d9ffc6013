#include "render/box_occlusion.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace haif::render {
namespace {

// A sample counts as inside a box's outline only this far (pixels) inside every edge: more than the
// GPU's sub-pixel snapping (1/256 px on llvmpipe) and the rounding of the two vertex transforms.
constexpr float kEdgeMargin = 1.f / 32.f;
// A face is tested on every pixel within this distance (pixels) of its projection.
constexpr float kCoverMargin = 1.f / 16.f;
// A face is hidden only if its nearest corner is this much (relative) behind what covers it.
constexpr float kDepthMargin = 1e-4f;

// The corner of a box with bit t of k set = +half along axis t.
int cornerIndex(int axis, int side, int u, int su, int v, int sv) {
  return (side > 0 ? 1 << axis : 0) | (su > 0 ? 1 << u : 0) | (sv > 0 ? 1 << v : 0);
}

// The four corners of face (axis, side) in cyclic order.
void faceCorners(int axis, int side, int corner[4]) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  corner[0] = cornerIndex(axis, side, u, -1, v, -1);
  corner[1] = cornerIndex(axis, side, u, 1, v, -1);
  corner[2] = cornerIndex(axis, side, u, 1, v, 1);
  corner[3] = cornerIndex(axis, side, u, -1, v, 1);
}

}  // namespace

void BoxOcclusion::setSamples(const float* xy, int count) {
  count = std::clamp(count, 1, 8);
  sampleXY_.assign(xy, xy + 2 * count);
  fullMask_ = static_cast<uint8_t>((1u << count) - 1u);
}

void BoxOcclusion::project(const OcclusionView& view, const BoxPose& box, Projected& p) const {
  const Vec3 axis[3] = {rotate(box.orientation, {1.f, 0.f, 0.f}), rotate(box.orientation, {0.f, 1.f, 0.f}),
                        rotate(box.orientation, {0.f, 0.f, 1.f})};
  const float half[3] = {box.half.x, box.half.y, box.half.z};
  const float* m = view.viewProj.m;
  p.valid = std::isfinite(box.center.x + box.center.y + box.center.z + half[0] + half[1] + half[2]);
  p.front = 0;
  for (int k = 0; k < 8 && p.valid; ++k) {
    Vec3 c = box.center;
    for (int t = 0; t < 3; ++t) c = c + axis[t] * ((k >> t & 1) ? half[t] : -half[t]);
    const float cx = m[0] * c.x + m[4] * c.y + m[8] * c.z + m[12];
    const float cy = m[1] * c.x + m[5] * c.y + m[9] * c.z + m[13];
    const float w = m[3] * c.x + m[7] * c.y + m[11] * c.z + m[15];
    if (!(w >= view.zNear) || !std::isfinite(w)) p.valid = false;
    p.x[k] = (cx / w * 0.5f + 0.5f) * static_cast<float>(view.width);
    p.y[k] = (cy / w * 0.5f + 0.5f) * static_cast<float>(view.height);
    p.w[k] = w;
  }
  if (!p.valid) return;
  for (int a = 0; a < 3; ++a)
    for (int side = -1; side <= 1; side += 2) {
      const Vec3 n = axis[a] * static_cast<float>(side);
      const Vec3 faceCenter = box.center + n * half[a];
      if (dot(n, view.eye - faceCenter) > 0.f) p.front |= boxFaceBit(a, side);
    }
}

void BoxOcclusion::rasterSilhouette(const Projected& p) {
  if (!p.front) return;
  // The box covers its whole outline: what its drawn front faces leave out are faces inside a
  // neighbouring box (HiddenBoxFaces), and that neighbour covers them nearer. One convex outline
  // also leaves no margin-wide cracks between the faces of one box. Its front surface lies no
  // farther than the farthest corner of a front face.
  float far = 0.f;
  for (int k = 0; k < 8; ++k) {
    bool onFront = false;
    for (int a = 0; a < 3; ++a) onFront |= (p.front & boxFaceBit(a, (k >> a & 1) ? 1 : -1)) != 0;
    if (onFront) far = std::max(far, p.w[k]);
  }
  // Convex hull of the 8 projected corners, counter-clockwise (monotone chain).
  int order[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  std::sort(order, order + 8, [&](int a, int b) { return p.x[a] < p.x[b] || (p.x[a] == p.x[b] && p.y[a] < p.y[b]); });
  int hull[16], n = 0;
  const auto turn = [&](int o, int a, int b) {
    return (p.x[a] - p.x[o]) * (p.y[b] - p.y[o]) - (p.y[a] - p.y[o]) * (p.x[b] - p.x[o]);
  };
  for (int i = 0; i < 8; ++i) {
    while (n >= 2 && turn(hull[n - 2], hull[n - 1], order[i]) <= 0.f) --n;
    hull[n++] = order[i];
  }
  for (int i = 6, lower = n + 1; i >= 0; --i) {
    while (n >= lower && turn(hull[n - 2], hull[n - 1], order[i]) <= 0.f) --n;
    hull[n++] = order[i];
  }
  --n;  // the first point closes the loop
  if (n < 3) return;

  float x0 = 1e30f, y0 = 1e30f, x1 = -1e30f, y1 = -1e30f;
  for (int i = 0; i < n; ++i) {
    x0 = std::min(x0, p.x[hull[i]]), x1 = std::max(x1, p.x[hull[i]]);
    y0 = std::min(y0, p.y[hull[i]]), y1 = std::max(y1, p.y[hull[i]]);
  }
  const float big = 1e6f;  // corners just past the near plane can project very far away
  Rect r;
  r.x0 = std::max(0, static_cast<int>(std::floor(std::clamp(x0, -big, big))));
  r.y0 = std::max(0, static_cast<int>(std::floor(std::clamp(y0, -big, big))));
  r.x1 = std::min(width_, static_cast<int>(std::ceil(std::clamp(x1, -big, big))));
  r.y1 = std::min(height_, static_cast<int>(std::ceil(std::clamp(y1, -big, big))));
  if (r.empty()) return;
  // Edge e (counter-clockwise): inside when A * px + B * py + C > 0, shrunk by kEdgeMargin, in
  // coordinates relative to the rectangle (small numbers keep float exact enough). Along a row an
  // edge bounds x from below (A > 0) or above (A < 0) at x = slope * py + offset; a horizontal
  // one keeps the whole row or nothing.
  float loSlope[8], loOffset[8], hiSlope[8], hiOffset[8], flatB[8], flatC[8];
  int lows = 0, highs = 0, flats = 0;
  for (int e = 0; e < n; ++e) {
    const int a = hull[e], b = hull[(e + 1) % n];
    const float xa = p.x[a] - static_cast<float>(r.x0), ya = p.y[a] - static_cast<float>(r.y0);
    const float A = -(p.y[b] - p.y[a]), B = p.x[b] - p.x[a];
    const float C = -(A * xa + B * ya) - kEdgeMargin * std::sqrt(A * A + B * B);
    if (A > 0.f)
      loSlope[lows] = -B / A, loOffset[lows++] = -C / A;
    else if (A < 0.f)
      hiSlope[highs] = -B / A, hiOffset[highs++] = -C / A;
    else
      flatB[flats] = B, flatC[flats++] = C;
  }
  // Per pixel row and sample, the face (convex) is an open interval of x; a pixel has sample s
  // when its x offset lands inside sample s's interval.
  const int samples = static_cast<int>(sampleXY_.size() / 2);
  const float width = static_cast<float>(r.x1 - r.x0);
  const int lastPixel = r.x1 - r.x0 - 1;
  for (int j = r.y0; j < r.y1; ++j) {
    int first[8], last[8];  // per sample: pixels (relative to r.x0) holding it, inclusive
    int allFirst = 0, allLast = lastPixel, anyFirst = lastPixel + 1, anyLast = -1;
    for (int s = 0; s < samples; ++s) {
      const float py = static_cast<float>(j - r.y0) + sampleXY_[2 * s + 1];
      const float sx = sampleXY_[2 * s];
      float lo = -2.f + sx, hi = width + 2.f + sx;
      for (int k = 0; k < lows; ++k) lo = std::max(lo, loSlope[k] * py + loOffset[k]);
      for (int k = 0; k < highs; ++k) hi = std::min(hi, hiSlope[k] * py + hiOffset[k]);
      for (int k = 0; k < flats; ++k)
        if (!(flatB[k] * py + flatC[k] > 0.f)) hi = lo;
      // Pixel i holds the sample when lo < i + sx < hi (strictly).
      first[s] = std::max(0, static_cast<int>(std::floor(lo - sx)) + 1);
      last[s] = std::min(lastPixel, static_cast<int>(std::ceil(hi - sx)) - 1);
      allFirst = std::max(allFirst, first[s]);
      allLast = std::min(allLast, last[s]);
      anyFirst = std::min(anyFirst, first[s]);
      anyLast = std::max(anyLast, last[s]);
    }
    uint8_t* mask = &mask_[static_cast<size_t>(j) * width_ + r.x0];
    float* depth = &depth_[static_cast<size_t>(j) * width_ + r.x0];
    const uint8_t full = fullMask_;
    // Pixels holding every sample: this face alone covers them.
    for (int i = allFirst; i <= allLast; ++i) {
      depth[i] = mask[i] == full ? std::min(depth[i], far) : far;
      mask[i] = full;
    }
    // Pixels holding some: partial coverage adds up, and the pixel is then covered no farther
    // than the farthest part.
    for (int i = anyFirst; i <= anyLast; ++i) {
      if (i == allFirst && allFirst <= allLast) i = allLast + 1;
      if (i > anyLast) break;
      unsigned m = 0;
      for (int s = 0; s < samples; ++s)
        if (i >= first[s] && i <= last[s]) m |= 1u << s;
      if (!m || mask[i] == full) continue;
      depth[i] = mask[i] ? std::max(depth[i], far) : far;
      mask[i] = static_cast<uint8_t>(mask[i] | m);
    }
  }
}

bool BoxOcclusion::faceHidden(const Projected& p, const int corner[4]) const {
  float x[4], y[4], ymin = 1e30f, ymax = -1e30f, nearest = 1e30f;
  for (int i = 0; i < 4; ++i) {
    x[i] = p.x[corner[i]], y[i] = p.y[corner[i]];
    ymin = std::min(ymin, y[i]), ymax = std::max(ymax, y[i]);
    nearest = std::min(nearest, p.w[corner[i]]);
  }
  const float limit = nearest / (1.f + kDepthMargin);
  const float m = kCoverMargin;
  const int j0 = std::max(0, static_cast<int>(std::floor(std::max(ymin - m, -1.f))));
  const int j1 = std::min(height_, static_cast<int>(std::ceil(std::min(ymax + m, static_cast<float>(height_) + 1.f))));
  for (int j = j0; j < j1; ++j) {
    // The face's x extent within this pixel row (grown by the margin): every pixel the GPU could
    // give a sample of this face lies in it.
    const float yb = static_cast<float>(j) - m, yt = static_cast<float>(j + 1) + m;
    float xmin = 1e30f, xmax = -1e30f;
    for (int e = 0; e < 4; ++e) {
      const int f = (e + 1) % 4;
      if (std::max(y[e], y[f]) < yb || std::min(y[e], y[f]) > yt) continue;
      float ta = 0.f, tb = 1.f;
      if (y[f] != y[e]) {
        const float t0 = (yb - y[e]) / (y[f] - y[e]), t1 = (yt - y[e]) / (y[f] - y[e]);
        ta = std::max(0.f, std::min(t0, t1)), tb = std::min(1.f, std::max(t0, t1));
      }
      const float xa = x[e] + (x[f] - x[e]) * ta, xb = x[e] + (x[f] - x[e]) * tb;
      xmin = std::min(xmin, std::min(xa, xb)), xmax = std::max(xmax, std::max(xa, xb));
    }
    if (xmin > xmax) continue;
    const int i0 = std::max(0, static_cast<int>(std::floor(std::max(xmin - m, -1.f))));
    const int i1 = std::min(width_, static_cast<int>(std::ceil(std::min(xmax + m, static_cast<float>(width_) + 1.f))));
    const size_t row = static_cast<size_t>(j) * width_;
    for (int i = i0; i < i1; ++i)
      if (mask_[row + i] != fullMask_ || !(depth_[row + i] < limit)) return false;
  }
  return true;  // also for a face wholly off screen: nothing of it is drawn
}

uint8_t BoxOcclusion::hiddenFaces(const Projected& p, uint8_t undrawn) const {
  int corner[4];
  uint8_t hidden = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = -1; side <= 1; side += 2) {
      const uint8_t bit = boxFaceBit(axis, side);
      if (!(p.front & bit) || (undrawn & bit)) continue;
      faceCorners(axis, side, corner);
      if (faceHidden(p, corner)) hidden |= bit;
    }
  return hidden;
}

void BoxOcclusion::find(const OcclusionView& view, const std::vector<BoxPose>& boxes, size_t count,
                        const std::vector<uint8_t>& undrawn, std::vector<uint8_t>& faces,
                        std::vector<uint8_t>& whole) {
  faces.assign(count, 0);
  whole.assign(count, 0);
  width_ = std::max(view.width, 1), height_ = std::max(view.height, 1);
  const size_t pixels = static_cast<size_t>(width_) * height_;
  if (mask_.size() != pixels) mask_.resize(pixels), depth_.resize(pixels);
  std::memset(mask_.data(), 0, pixels);
  projected_.resize(count);
  for (size_t i = 0; i < count; ++i) project(view, boxes[i], projected_[i]);

  // Boxes the ones before them already hide add no coverage (what they would cover is covered
  // nearer): they are settled without rasterising them. Coverage only grows, so they stay hidden.
  for (size_t i = 0; i < count; ++i) {
    const Projected& p = projected_[i];
    if (!p.valid) continue;
    const uint8_t drawn = static_cast<uint8_t>(p.front & ~undrawn[i]);
    if (hiddenFaces(p, undrawn[i]) == drawn) {
      whole[i] = 1, faces[i] = drawn;
      continue;
    }
    rasterSilhouette(p);
  }
  for (size_t i = 0; i < count; ++i) {
    const Projected& p = projected_[i];
    if (!p.valid || whole[i]) continue;
    faces[i] = hiddenFaces(p, undrawn[i]);
    whole[i] = faces[i] == (p.front & ~undrawn[i]) ? 1 : 0;
  }
}

}  // namespace haif::render
