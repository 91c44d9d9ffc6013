// Sutherland-Hodgman clipping of a convex polygon by a plane, on fixed-size arrays, keeping a
// feature id per point so contact ids stay stable while the same features touch.
#pragma once

#include "core/math.h"

#include <cstdint>

namespace haif {
namespace detail {

inline constexpr int kMaxClipVerts = 128;

struct ClipPoint {
  Vec3 p;
  uint16_t fid;      ///< incident vertex k (< 0x8000) or 0x8000 | edgeIdentity << 7 | plane
  uint8_t outEdge;   ///< identity of the edge leaving this point: incident edge k (< 0x80) or 0x80 | plane
};

/// Keeps the part of `in` where dot(n, p) <= d. `plane` (0..127) names the plane in the ids.
/// Returns the number of points written to `out` (at most n + 1, never more than kMaxClipVerts).
inline int clipPolygon(const ClipPoint* in, int n, ClipPoint* out, const Vec3& pn, float d, uint32_t plane) {
  int m = 0;
  plane &= 0x7Fu;
  for (int i = 0; i < n && m < kMaxClipVerts - 1; ++i) {
    const ClipPoint& a = in[i];
    const ClipPoint& b = in[i + 1 == n ? 0 : i + 1];
    const float da = pn.dot(a.p) - d, db = pn.dot(b.p) - d;
    if (da <= 0.0f) out[m++] = a;
    if ((da <= 0.0f) != (db <= 0.0f)) {
      const float t = da / (da - db);
      ClipPoint c;
      c.p = a.p + t * (b.p - a.p);
      c.fid = uint16_t(0x8000u | (uint32_t(a.outEdge) << 7) | plane);
      // Leaving the kept side the new edge runs along the plane; entering, it continues a's edge.
      c.outEdge = da <= 0.0f ? uint8_t(0x80u | plane) : a.outEdge;
      out[m++] = c;
    }
  }
  return m;
}

}  // namespace detail
}  // namespace haif
