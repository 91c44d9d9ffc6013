// Where a pair's friction acts: the patch of the manifold points that touch.
//
// Friction (two tangent rows and a twist, prepareContact) acts at one centre, and its static anchor
// (World's updateAnchor) is set there. A manifold also holds speculative points that do not touch:
// a top spinning on its tip got two points of its rim, 21 cm up, and friction at their mean with the
// tip took the tip's load at 10 cm from it and a twist radius of 17 cm: the top, stable at 40
// rad/s, lost its spin within a second and fell. A point farther apart than kPatchDepthSpread
// beyond the pair's nearest point is out of the patch (scaled with small bodies' tolerances).
#pragma once

namespace haif {

inline constexpr float kPatchDepthSpread = 0.02f;  ///< m: four slops (SolverParams::slop)

/// The least depth a point of the friction patch has, in a manifold whose nearest (deepest) point
/// has depth `nearest`; `toleranceScale`: Contact::toleranceScale.
inline float frictionPatchFloor(float nearest, float toleranceScale) {
  return nearest - kPatchDepthSpread * toleranceScale;
}

}  // namespace haif
