// Dense helpers of a manifold's normal block: the points' in-plane coordinates and basis. The chain
// solver (contact_chain.cpp) builds its links' rows with them.
#include "dynamics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace haif {

int spreadRank(double css, double ctt, double cst, int count, double single, double along[2]) {
  const double half = 0.5 * (css + ctt), dev = std::sqrt(0.25 * (css - ctt) * (css - ctt) + cst * cst);
  const double major = half + dev, minor = std::max(0.0, half - dev);
  if (count < 2 || !(major > single)) return 1;
  if (count >= 3 && minor > single && minor * major > kLineWidthRatio * (css + ctt) * (css + ctt)) return 3;
  // A line along the major axis: an eigenvector of [[css, cst], [cst, ctt]] for `major`, from
  // whichever of its two forms is the longer (both vanish only where no axis leads).
  const double ux = major - ctt, uy = cst, vx = cst, vy = major - css;
  const bool first = ux * ux + uy * uy >= vx * vx + vy * vy;
  const double x = first ? ux : vx, y = first ? uy : vy, length = std::sqrt(x * x + y * y);
  along[0] = length > 0.0 ? x / length : 1.0;
  along[1] = length > 0.0 ? y / length : 0.0;
  return 2;
}

int pointBasis(const double coords[kMaxManifoldPoints][2], int count, unsigned mask, double single,
               double B[kMaxManifoldPoints][3]) {
  // The span of [1, s, t] does not depend on where (s, t) are measured from, but the rank test does:
  // it takes the spread about the points' mean (the coordinates of a whole manifold already are).
  const unsigned all = (1u << count) - 1u;
  double ms = 0.0, mt = 0.0;
  int m = 0;
  for (int i = 0; i < count; ++i)
    if (mask & (1u << i)) {
      ms += coords[i][0];
      mt += coords[i][1];
      ++m;
    }
  if (m == 0) {
    for (int i = 0; i < kMaxManifoldPoints; ++i) B[i][0] = B[i][1] = B[i][2] = 0.0;
    return 0;
  }
  if ((mask & all) == all) ms = mt = 0.0;
  else ms /= m, mt /= m;
  // Every entry is written (rows of points not in the mask are zero), so no separate clearing pass:
  // called once per manifold per step, the clearing loops compiled to two memset calls.
  double css = 0.0, ctt = 0.0, cst = 0.0;
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    const bool in = i < count && (mask & (1u << i));
    const double s = in ? coords[i][0] - ms : 0.0, t = in ? coords[i][1] - mt : 0.0;
    B[i][0] = in ? 1.0 : 0.0;
    B[i][1] = s;
    B[i][2] = t;
    if (!in) continue;
    css += s * s;
    ctt += t * t;
    cst += s * t;
  }
  double along[2];
  const int k = spreadRank(css, ctt, cst, m, single, along);
  if (k == 2)
    for (int i = 0; i < count; ++i) B[i][1] = along[0] * B[i][1] + along[1] * B[i][2];
  for (int i = 0; i < count; ++i)
    for (int a = k; a < 3; ++a) B[i][a] = 0.0;
  return k;
}

void planarCoords(const Manifold& mf, const Vec3& centre, const Vec3& t1, const Vec3& t2,
                  double coords[kMaxManifoldPoints][2]) {
  for (int i = 0; i < kMaxManifoldPoints; ++i) {
    if (i < mf.count) {
      const Vec3 d = mf.points[i].position - centre;
      coords[i][0] = d.dot(t1);
      coords[i][1] = d.dot(t2);
    } else {
      coords[i][0] = coords[i][1] = 0.0;
    }
  }
}

}  // namespace haif
