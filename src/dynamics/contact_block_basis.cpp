// Dense helpers of a manifold's normal block: the points' in-plane coordinates and basis. The chain
// solver (contact_chain.cpp) builds its links' rows with them.
#include "dynamics/contact_solver.h"

namespace haif {

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
  const double spread = css + ctt;
  const bool onePlace = m < 2 || !(spread > single);
  const bool collinear = !onePlace && css * ctt - cst * cst <= 1e-4 * spread * spread;
  const int k = onePlace ? 1 : m >= 3 && !collinear ? 3 : 2;
  if (k == 2 && ctt > css)
    for (int i = 0; i < count; ++i) B[i][1] = B[i][2];
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
