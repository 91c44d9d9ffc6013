// A motor's effective mass through the joint tree. A motor row is swept before the tree (joint_solver):
// with the mass of its own two bodies it asks too little of an arm whose links carry more links, the
// tree then shares its push with all of them, and the sweeps reach the motor's speed a fraction at a
// time. A servo following a path then lags, its position error grows its speed, and it overshoots:
// robot_arm's 2 kg hand swung at up to 16 m/s at 4 iterations (2.9 m/s converged) and was caught by
// the speed bound ~370 times a minute. Measured through the tree, the row's mass is what the tree
// lets the axis feel, and one sweep brings a lone motor to its speed.
#pragma once

#include "dynamics/joint_solver.h"
#include "dynamics/joint_tree.h"

#include <cstdint>

namespace haif {

/// Sets each motor row's mass from K = J M⁻¹ Jᵀ − gᵀ A⁻¹ g, with g the tree rows' velocity under a unit
/// push of the motor and A the tree's system: what is left of the axis once the tree answers. Rows
/// the tree (nearly) locks keep their own two bodies' mass. Marks the motors it sets
/// (JointConstraint::motorThroughTree): each sweep must let the tree answer each before the next
/// (solveJointIteration). Call after tree.build at the same rows.
void motorMassesThroughTree(JointConstraint* js, uint32_t n, JointTree& tree);

}  // namespace haif
