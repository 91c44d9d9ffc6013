// Support balance: how a resting body's load divides among the points that hold it up.
//
// The cold start (World::estimateColdImpulses) gives the contacts of a pile created at rest the
// weight they carry before the first sweep. Shared equally among a body's supports, the load is an
// equilibrium only where the body sits centred on symmetric supports. In a Jenga tower jittered as
// a hand builds it (blocks ±2 mm, ±2°, masses ±10 %) the equal shares left every block a torque;
// 10 sweeps on 18 crossed layers did not take it out, the first step tilted blocks by 0.2°, and the
// tower fell after ~250 steps (4 iterations: at once). With the first step solved to convergence it
// stood the minute at 4 and at 10. So the load is divided here so that it balances: the vertical
// force and both moments about horizontal axes.
//
// Among the divisions that balance with no point pulling, the least-squares one: the load spreads
// as a plane over the points that push, λ_k = max(0, a + b x_k + c z_k), found by Newton on (a, b, c)
// (support_balance.cpp). For rigid bodies at rest any non-negative balance of every body is a
// solution of the contact problem, so a pile whose bodies each balance this way starts solved.
#pragma once

#include <cstdint>

namespace haif {

/// A point holding the body up: where it is across the vertical, relative to the body's centre (m),
/// and the vertical impulse it carries (N s, the result).
struct SupportPoint {
  float x = 0.0f, z = 0.0f;
  float load = 0.0f;
};

/// Divides a vertical load (N s) whose moment about the centre is (mx, mz) (N s m; mx = Σ load·x)
/// among the points, none pulling. Where no such division exists (the load's centre outside what
/// the points span) the points left carry what balances best, their sum the load. Returns false,
/// loads untouched, only if there are no points or no load.
bool balanceSupportLoad(SupportPoint* points, int count, float load, float mx, float mz);

}  // namespace haif
