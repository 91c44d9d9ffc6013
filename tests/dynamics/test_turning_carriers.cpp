// Bodies riding a turning body (a turntable, a motor-driven plate) stay where they were put on it:
// friction holds their contact's material points together along the arcs the turn moves them on
// (SolverParams::followArcs, contact_prepare.cpp's arcLag), not only their velocities.
#include "support/physics_test_util.h"

namespace haif::test {
namespace {

constexpr float kSpin = 1.0f;  // rad/s about +y
constexpr int kMinute = 3600;

/// A box of half extent h co-moving with a body turning at kSpin about the y axis through the origin.
uint32_t addRider(World& w, const Vec3& p, float h) {
  BodyDef d;
  d.shape = Shape::box(Vec3::Constant(h));
  d.xf.p = p;
  d.mass = 8000.0f * h * h * h;
  d.angularVelocity = Vec3(0.0f, kSpin, 0.0f);
  d.linearVelocity = d.angularVelocity.cross(p);
  return w.addBody(d);
}

/// Where body i is in the frame of body `carrier`.
Vec3 inFrameOf(const World& w, uint32_t carrier, uint32_t i) {
  const Transform& c = w.bodies().xf[carrier];
  return c.q.conjugate() * (w.bodies().xf[i].p - c.p);
}

struct Ride {
  float ringDrift = 0.0f;   ///< farthest a lone box 3 m out moved on the table (m)
  float stackDrift = 0.0f;  ///< farthest a box of a 3-box stack 1.5 m out moved on the table (m)
};

/// Boxes on a carrier of top y = 0.5 turning at kSpin: six lone 0.6 m boxes 3 m out and a stack of
/// three 0.5 m boxes 1.5 m out, for a minute; how far each moved in the carrier's frame.
template <typename MakeCarrier>
Ride ride(int iterations, bool followArcs, MakeCarrier makeCarrier) {
  WorldSettings s;
  s.iterations = iterations;
  s.contact.followArcs = followArcs;
  World w(s);
  addGround(w);
  const uint32_t carrier = makeCarrier(w);
  std::vector<uint32_t> ring, stack;
  for (int k = 0; k < 6; ++k) {
    const float a = 2.0f * kPi * float(k) / 6.0f;
    ring.push_back(addRider(w, Vec3(3.0f * std::cos(a), 0.8f, 3.0f * std::sin(a)), 0.3f));
  }
  for (int i = 0; i < 3; ++i) stack.push_back(addRider(w, Vec3(1.5f, 0.75f + 0.51f * float(i), 0.0f), 0.25f));
  // Measured from when the boxes have landed (their gaps closed) and settled on the carrier.
  for (int s = 0; s < 60; ++s) w.step();
  std::vector<Vec3> start;
  for (uint32_t i = 0; i < w.bodyCount(); ++i) start.push_back(inFrameOf(w, carrier, i));
  for (int s = 0; s < kMinute; ++s) w.step();
  Ride r;
  for (uint32_t i : ring) r.ringDrift = std::max(r.ringDrift, (inFrameOf(w, carrier, i) - start[i]).norm());
  for (uint32_t i : stack) r.stackDrift = std::max(r.stackDrift, (inFrameOf(w, carrier, i) - start[i]).norm());
  return r;
}

uint32_t kinematicTurntable(World& w) {
  return addKinematicBox(w, Vec3(0.0f, 0.25f, 0.0f), Vec3(4.0f, 0.25f, 4.0f), Vec3::Zero(), Vec3(0.0f, kSpin, 0.0f));
}

// A dynamic 500 kg plate on a hinge to a static post, its motor turning it at kSpin.
uint32_t motorTurntable(World& w) {
  const uint32_t post = addStaticBox(w, Vec3(0.0f, 0.125f, 0.0f), Vec3(0.3f, 0.125f, 0.3f));
  BodyDef d;
  d.shape = Shape::box(Vec3(4.0f, 0.125f, 4.0f));
  d.xf.p = Vec3(0.0f, 0.375f, 0.0f);
  d.mass = 500.0f;
  d.angularVelocity = Vec3(0.0f, kSpin, 0.0f);
  const uint32_t plate = w.addBody(d);
  JointDef j = jointAtWorld(JointType::Hinge, post, plate, w.bodies().xf[post], w.bodies().xf[plate],
                            Vec3(0.0f, 0.25f, 0.0f), Vec3::UnitY(), Vec3::Zero());
  j.motorEnabled = true;
  j.motorSpeed = kSpin;
  j.maxMotorForce = 1e5f;
  w.addJoint(j);
  return plate;
}

class TurningCarrier : public ::testing::TestWithParam<int> {};

// At 1 rad/s a box 3 m out needs 3 m/s² of friction (μ g = 5.9 m/s² holds it). Velocity-level
// friction alone let the lone boxes slide out at (ω dt)² r / 2 a step, 0.025 m/s: off the table's
// edge within the minute (drift 9.8-9.9 m). With the arcs followed, the lone boxes moved 0.01 mm and
// the stack 15 mm (fixed 4) and 5 mm (fixed 10); followed in the main sweeps only, the stack's top
// box slid 14-22 cm.
TEST_P(TurningCarrier, BoxesStayOnAKinematicTurntable) {
  const int iterations = GetParam();
  const Ride held = ride(iterations, true, kinematicTurntable);
  EXPECT_LT(held.ringDrift, 0.001f) << iterations << " iterations";
  EXPECT_LT(held.stackDrift, 0.03f) << iterations << " iterations";
  const Ride slid = ride(iterations, false, kinematicTurntable);
  EXPECT_GT(slid.ringDrift, 1.0f) << "without the arcs the boxes slid off the table";
}

// The same on a dynamic plate a hinge motor turns: its arcs are the plate's own. The motor turns it
// back to its speed every step against the riders' pull, which the arcs (from the speed at the
// step's start) do not know: the lone boxes moved 15 mm (fixed 4) and 3 mm (fixed 10), the stack
// 41 and 25 mm; without the arcs all slid off (9.7-9.8 m).
TEST_P(TurningCarrier, BoxesStayOnAMotorDrivenPlate) {
  const int iterations = GetParam();
  const Ride held = ride(iterations, true, motorTurntable);
  EXPECT_LT(held.ringDrift, 0.03f) << iterations << " iterations";
  EXPECT_LT(held.stackDrift, 0.08f) << iterations << " iterations";
  const Ride slid = ride(iterations, false, motorTurntable);
  EXPECT_GT(slid.ringDrift, 1.0f) << "without the arcs the boxes slid off the plate";
}

INSTANTIATE_TEST_SUITE_P(Friction, TurningCarrier, ::testing::Values(4, 10));

}  // namespace
}  // namespace haif::test
