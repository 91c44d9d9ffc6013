// The solve-error probe (docs/metrics.md): the step's solve measured against a converged one.
#include "haif/world_internal.h"

namespace haif {

namespace {

/// Mass-weighted RMS velocity error (m/s) below which a solve's starting point counts as exact.
constexpr float kSolveErrorFloor = 1e-4f;

}  // namespace

namespace {

// Sets a value for the life of the object and puts the old one back, exceptions included.
template <class T>
class ScopedValue {
 public:
  ScopedValue(T& ref, T value) : ref_(ref), old_(ref) { ref_ = value; }
  ~ScopedValue() { ref_ = old_; }
  ScopedValue(const ScopedValue&) = delete;
  ScopedValue& operator=(const ScopedValue&) = delete;

 private:
  T& ref_;
  T old_;
};

}  // namespace

double World::measureSolveError(int iterations) {
  // e = |v_I - v*|_M / |v_0 - v*|_M over the dynamic bodies of the islands (docs/metrics.md), with v_0
  // the solver's starting point (after warm starting), v_I after the iterations, v* converged.
  const uint32_t n = bodyCount();
  const auto t0 = Clock::now();
  // Each solve starts from the same state: the velocities and the islands' tails put back (the
  // contacts' impulses are only read, a landing's only cleared; solveIslands starts its dense
  // systems afresh).
  probe_.saveV = bodies_.v;
  probe_.saveW = bodies_.w;
  probe_.saveTail = order_.tail;
  auto restore = [&] {
    bodies_.v = probe_.saveV;
    bodies_.w = probe_.saveW;
    order_.tail = probe_.saveTail;
  };
  solveIslands(0);  // prepare + warm start only
  probe_.startV = bodies_.v;
  probe_.startW = bodies_.w;
  restore();
  {
    // The reference solve converges: a tight tolerance and no floor on the sweeps, put back on the
    // way out of this block however it is left.
    const ScopedValue<float> tol(settings_.residualTolerance, 1e-6f);
    const ScopedValue<int> iMin(controller_->iMin, 1);
    solveIslands(1000);
  }
  probe_.refV = bodies_.v;
  probe_.refW = bodies_.w;
  restore();
  measurementMs_ = msSince(t0);  // the reference solve is measurement, not step time
  resetPhaseClocks();
  solveIslands(iterations);
  double num = 0.0, den = 0.0, massSum = 0.0;
  for (uint32_t i = 0; i < n; ++i) {
    if (bodies_.kind[i] != BodyKind::Dynamic || bodies_.asleep[i]) continue;
    massSum += bodies_.mass[i];
    const Mat3 I = bodies_.xf[i].q.toRotationMatrix() * bodies_.inertiaLocal[i] *
                   bodies_.xf[i].q.toRotationMatrix().transpose();
    auto norm2 = [&](const Vec3& dv, const Vec3& dw) {
      return double(bodies_.mass[i]) * dv.squaredNorm() + double(dw.dot(I * dw));
    };
    num += norm2(bodies_.v[i] - probe_.refV[i], bodies_.w[i] - probe_.refW[i]);
    den += norm2(probe_.startV[i] - probe_.refV[i], probe_.startW[i] - probe_.refW[i]);
  }
  // When warm starting already put v_0 within float noise of v* (a resting stack), the ratio
  // of two noise-sized norms says nothing: the denominator is floored at an RMS velocity error
  // of kSolveErrorFloor, so a solve with nothing left to do reports an error near 0.
  const double floor = massSum * double(kSolveErrorFloor) * double(kSolveErrorFloor);
  return num > 0.0 ? std::sqrt(num / std::max(den, floor)) : 0.0;
}

}  // namespace haif
