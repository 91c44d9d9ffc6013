#include "haif/support_balance.h"

#include <cmath>

namespace haif {

namespace {

// The division sought is the least-squares one that balances and never pulls:
//   min ½ Σ λ_k²  subject to  Σ λ_k φ_k = r,  λ ≥ 0,  with φ_k = (1, x_k, z_k), r = (load, mx, mz).
// Its solution is λ_k = max(0, φ_k · μ) for the μ that maximises the concave dual
//   D(μ) = r · μ − ½ Σ max(0, φ_k · μ)²,
// whose gradient is the imbalance r − Σ λ_k φ_k. Newton on μ (the Hessian is the sum of φ φᵀ over
// the points that push) with a backtracking line search converges in a few steps; points let go
// come back when the balance needs them.
// Adds φ φᵀ of the point (x, z) to h (upper triangle: 00 01 02 11 12 22).
void addOuter(double h[6], double x, double z) {
  h[0] += 1.0;
  h[1] += x;
  h[2] += z;
  h[3] += x * x;
  h[4] += x * z;
  h[5] += z * z;
}

struct Dual {
  const SupportPoint* points;
  int count;
  double r[3];

  double push(int k, const double mu[3]) const {
    return std::fmax(0.0, mu[0] + mu[1] * points[k].x + mu[2] * points[k].z);
  }
  double value(const double mu[3]) const {
    double v = r[0] * mu[0] + r[1] * mu[1] + r[2] * mu[2];
    for (int k = 0; k < count; ++k) v -= 0.5 * push(k, mu) * push(k, mu);
    return v;
  }
  // The imbalance, and the sum of φ φᵀ over the points that push.
  void imbalance(const double mu[3], double g[3], double h[6]) const {
    g[0] = r[0];
    g[1] = r[1];
    g[2] = r[2];
    for (int i = 0; i < 6; ++i) h[i] = 0.0;
    for (int k = 0; k < count; ++k) {
      const double l = push(k, mu);
      if (l <= 0.0) continue;
      const double x = points[k].x, z = points[k].z;
      g[0] -= l;
      g[1] -= l * x;
      g[2] -= l * z;
      addOuter(h, x, z);
    }
  }
};

// Solves the symmetric 3×3 system h d = g (upper triangle as in addOuter), a small ridge added so that
// points in a line (an edge) or one point leave the direction they cannot hold out.
bool solve3(const double h[6], const double g[3], double d[3]) {
  const double ridge = 1e-12 * (h[0] + h[3] + h[5]) + 1e-30;
  const double a = h[0] + ridge, b = h[1], c = h[2], e = h[3] + ridge, f = h[4], i = h[5] + ridge;
  const double c00 = e * i - f * f, c01 = c * f - b * i, c02 = b * f - c * e;
  const double det = a * c00 + b * c01 + c * c02;
  if (!(std::fabs(det) > 0.0)) return false;
  const double c11 = a * i - c * c, c12 = b * c - a * f, c22 = a * e - b * b;
  d[0] = (c00 * g[0] + c01 * g[1] + c02 * g[2]) / det;
  d[1] = (c01 * g[0] + c11 * g[1] + c12 * g[2]) / det;
  d[2] = (c02 * g[0] + c12 * g[1] + c22 * g[2]) / det;
  return true;
}

bool balanceExactly(SupportPoint* points, int count, float load, float mx, float mz) {
  Dual dual{points, count, {load, mx, mz}};
  double spread2 = 0.0;
  for (int k = 0; k < count; ++k) spread2 += double(points[k].x) * points[k].x + double(points[k].z) * points[k].z;
  const double arm = std::sqrt(spread2 / count) + 1e-9;
  const double forceTolerance = 1e-6 * double(load), momentTolerance = forceTolerance * arm;
  // From μ = 0 every point is taken as pushing for the first step (the plain least-squares balance).
  double mu[3] = {0.0, 0.0, 0.0}, g[3], h[6];
  dual.imbalance(mu, g, h);
  for (int k = 0; k < count; ++k) addOuter(h, points[k].x, points[k].z);
  constexpr int kNewtonSteps = 20;
  for (int step = 0; step < kNewtonSteps; ++step) {
    double d[3];
    if (!solve3(h, g, d)) return false;
    const double slope = g[0] * d[0] + g[1] * d[1] + g[2] * d[2];
    const double before = dual.value(mu);
    double t = 1.0, next[3];
    for (int halving = 0; halving < 40; ++halving, t *= 0.5) {
      for (int i = 0; i < 3; ++i) next[i] = mu[i] + t * d[i];
      if (dual.value(next) >= before + 1e-4 * t * slope) break;
    }
    for (int i = 0; i < 3; ++i) mu[i] = next[i];
    dual.imbalance(mu, g, h);
    if (std::fabs(g[0]) <= forceTolerance && std::hypot(g[1], g[2]) <= momentTolerance) {
      for (int k = 0; k < count; ++k) points[k].load = float(dual.push(k, mu));
      return true;
    }
  }
  return false;  // no division balances: the load's centre is outside what the points span
}

// Where nothing balances: the point that would pull hardest is let go and the rest balanced by least
// squares again, until none pulls; what is left carries the whole load, as near to balance as it can.
void letGoWhatPulls(SupportPoint* points, int count, float load, float mx, float mz) {
  for (int k = 0; k < count; ++k) points[k].load = 0.0f;  // < 0 marks a point let go
  for (int round = 0; round < count; ++round) {
    double n = 0.0, cx = 0.0, cz = 0.0;
    for (int k = 0; k < count; ++k)
      if (points[k].load >= 0.0f) {
        n += 1.0;
        cx += points[k].x;
        cz += points[k].z;
      }
    cx /= n;
    cz /= n;
    // Centred on the points still holding, λ_k = load / n + b x'_k + c z'_k sums to the load for any (b, c).
    double sxx = 0.0, sxz = 0.0, szz = 0.0;
    for (int k = 0; k < count; ++k)
      if (points[k].load >= 0.0f) {
        const double x = points[k].x - cx, z = points[k].z - cz;
        sxx += x * x;
        sxz += x * z;
        szz += z * z;
      }
    const double ridge = 1e-12 * (sxx + szz) + 1e-30;
    sxx += ridge;
    szz += ridge;
    const double rx = double(mx) - double(load) * cx, rz = double(mz) - double(load) * cz;
    const double det = sxx * szz - sxz * sxz;
    const bool turns = det > 0.0;  // one point, or points on top of each other: no moment at all
    const double b = turns ? (szz * rx - sxz * rz) / det : 0.0, c = turns ? (sxx * rz - sxz * rx) / det : 0.0;
    const double each = double(load) / n;
    int worst = -1;
    double worstLoad = -1e-6 * double(load);
    for (int k = 0; k < count; ++k) {
      if (points[k].load < 0.0f) continue;
      const double l = each + b * (points[k].x - cx) + c * (points[k].z - cz);
      if (l < worstLoad) {
        worstLoad = l;
        worst = k;
      }
    }
    if (worst < 0) {
      for (int k = 0; k < count; ++k) {
        const double l = each + b * (points[k].x - cx) + c * (points[k].z - cz);
        points[k].load = points[k].load < 0.0f ? 0.0f : float(std::fmax(l, 0.0));
      }
      return;
    }
    points[worst].load = -1.0f;
  }
}

}  // namespace

bool balanceSupportLoad(SupportPoint* points, int count, float load, float mx, float mz) {
  if (count <= 0 || !(load > 0.0f)) return false;
  if (!balanceExactly(points, count, load, mx, mz)) letGoWhatPulls(points, count, load, mx, mz);
  return true;
}

}  // namespace haif
