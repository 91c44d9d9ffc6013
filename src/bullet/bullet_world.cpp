#include "bullet/bullet_world.h"

#include "bullet/bullet_shapes.h"
#include "scene/build_world.h"

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>

namespace haif {

namespace {

// HAIF combines restitution as the larger of the two; Bullet multiplies, and no per-body value
// turns a product into a maximum, so the adapter installs Bullet's combine hook.
btScalar maxRestitution(const btCollisionObject* a, const btCollisionObject* b) {
  return std::max(a->getRestitution(), b->getRestitution());
}

btVector3 toBt(const Vec3& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
btQuaternion toBt(const Quat& q) { return btQuaternion(q.x(), q.y(), q.z(), q.w()); }
Quat fromBt(const btQuaternion& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }

// HAIF damps by 1 / (1 + c·dt) per step; Bullet by (1 − d)^dt. The d that gives the same factor.
btScalar bulletDamping(float c, float dt) {
  if (c <= 0.0f) return 0;
  const double perStep = 1.0 / (1.0 + double(c) * dt);
  return btScalar(std::clamp(1.0 - std::pow(perStep, 1.0 / dt), 0.0, 1.0));
}

// Principal axes of an inertia tensor: `inertia = R diag(d) Rᵀ` with R a proper rotation. A tensor
// that is already diagonal keeps R = identity (an eigen solver would be free to permute its axes).
void principalAxes(const Mat3& inertia, Quat& r, Vec3& d) {
  const float off = std::fabs(inertia(0, 1)) + std::fabs(inertia(0, 2)) + std::fabs(inertia(1, 2));
  if (off <= 1e-6f * inertia.trace()) {
    r = Quat::Identity();
    d = inertia.diagonal();
    return;
  }
  Eigen::SelfAdjointEigenSolver<Mat3> es(inertia);
  Mat3 axes = es.eigenvectors();
  if (axes.determinant() < 0.0f) axes.col(2) = -axes.col(2);
  r = Quat(axes).normalized();
  d = es.eigenvalues();
}

}  // namespace

struct BulletWorld::Impl {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};

  BulletShapeStore shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> motionStates;  // kinematic bodies only
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<Quat> principal;      // per body: HAIF body frame from Bullet's principal frame
  std::vector<float> extent;        // smallestExtent of the HAIF shape
  std::vector<uint8_t> dynamic;
  std::vector<uint32_t> kinematic;  // bodies moved by their constant velocity each step
  std::vector<Vec3> kinematicV, kinematicW;
  float dt = 1.0f / 60.0f;
  int iterations = 10;

  ~Impl() {
    // The world must let go of the bodies before they (and it) are destroyed.
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

BulletWorld::BulletWorld() : impl_(std::make_unique<Impl>()) {}
BulletWorld::~BulletWorld() = default;

bool BulletWorld::build(const SceneDesc& scene, int iterations, std::string& error) {
  Impl& m = *impl_;
  if (!scene.water.empty()) {
    error = scene.sourcePath + ": water: the Bullet baseline has no buoyancy; scenes with water run on HAIF only";
    return false;
  }
  const WorldSettings ws = scene.settings.world;
  m.dt = ws.dt;
  m.iterations = iterations > 0 ? iterations : ws.iterations;
  m.world.setGravity(toBt(ws.gravity));
  btContactSolverInfo& info = m.world.getSolverInfo();
  info.m_numIterations = m.iterations;
  info.m_sor = ws.contact.omega;
  info.m_erp = ws.contact.beta;   // Baumgarte factor of non-contact rows
  info.m_erp2 = ws.contact.beta;  // and of contact rows
  info.m_linearSlop = ws.contact.slop;
  info.m_restitutionVelocityThreshold = ws.contact.restitutionThreshold;
  // Two friction rows per point, as HAIF has (Bullet's default is one, along the sliding direction).
  info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  gCalculateCombinedRestitutionCallback = &maxRestitution;
  gDeactivationTime = ws.timeToSleep;

  const uint32_t n = uint32_t(scene.bodies.size());
  m.bodies.reserve(n);
  for (uint32_t i = 0; i < n; ++i) {
    const BodyDesc& desc = scene.bodies[i];
    BodyDef def;
    if (!bodyDefFor(scene, desc, def, error)) return false;
    const bool isDynamic = def.kind == BodyKind::Dynamic;
    Quat r = Quat::Identity();
    Vec3 inertia = Vec3::Zero();
    float mass = 0.0f;
    if (isDynamic) {
      const MassProperties mp = bodyMassProperties(def.shape, def.density, def.mass);
      mass = mp.mass;
      principalAxes(mp.inertia, r, inertia);
    }
    btCollisionShape* shape = m.shapes.add(def.shape, r, error);
    if (!shape) {
      error = scene.sourcePath + ": " + desc.where + ".shape: " + error;
      return false;
    }
    // Bullet's body frame is the principal frame: world = q_haif · r · x_principal.
    const btTransform start(toBt(def.xf.q * r), toBt(def.xf.p));
    btDefaultMotionState* motion = nullptr;
    if (def.kind == BodyKind::Kinematic) {
      m.motionStates.push_back(std::make_unique<btDefaultMotionState>(start));
      motion = m.motionStates.back().get();
    }
    btRigidBody::btRigidBodyConstructionInfo ci(mass, motion, shape, toBt(inertia));
    ci.m_startWorldTransform = start;
    // Bullet multiplies the two friction values; √μ per body makes the product HAIF's √(μa·μb).
    ci.m_friction = std::sqrt(std::max(0.0f, def.friction));
    ci.m_restitution = def.restitution;
    ci.m_linearDamping = bulletDamping(def.linearDamping, m.dt);
    ci.m_angularDamping = bulletDamping(def.angularDamping, m.dt);
    auto body = std::make_unique<btRigidBody>(ci);
    body->setUserIndex(int(i));
    if (def.kind == BodyKind::Kinematic) {
      body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      m.kinematic.push_back(i);
      m.kinematicV.push_back(def.linearVelocity);
      m.kinematicW.push_back(def.angularVelocity);
    }
    if (isDynamic) {
      body->setLinearVelocity(toBt(def.linearVelocity));
      body->setAngularVelocity(toBt(def.angularVelocity));
      body->setSleepingThresholds(ws.sleepLinear, ws.sleepAngular);
    }
    if (def.kind != BodyKind::Static && !ws.sleeping) body->setActivationState(DISABLE_DEACTIVATION);
    m.world.addRigidBody(body.get());
    m.bodies.push_back(std::move(body));
    m.principal.push_back(r);
    m.extent.push_back(haif::smallestExtent(def.shape));
    m.dynamic.push_back(isDynamic ? 1 : 0);
  }
  return true;
}

void BulletWorld::step() {
  Impl& m = *impl_;
  // Kinematic bodies follow their constant velocity; Bullet derives their velocity from the move.
  for (size_t k = 0; k < m.kinematic.size(); ++k) {
    const uint32_t i = m.kinematic[k];
    Transform xf = pose(i);
    xf.p += m.dt * m.kinematicV[k];
    const Vec3& w = m.kinematicW[k];
    if (w.squaredNorm() > 0.0f) {
      const Quat dq(0.0f, 0.5f * m.dt * w.x(), 0.5f * m.dt * w.y(), 0.5f * m.dt * w.z());
      Quat q = xf.q;
      q.coeffs() += (dq * xf.q).coeffs();
      xf.q = q.normalized();
    }
    m.bodies[i]->getMotionState()->setWorldTransform(btTransform(toBt(xf.q * m.principal[i]), toBt(xf.p)));
  }
  // maxSubSteps = 0: exactly one internal step of dt, no interpolation.
  m.world.stepSimulation(m.dt, 0);
}

int BulletWorld::iterations() const { return impl_->iterations; }
uint32_t BulletWorld::bodyCount() const { return uint32_t(impl_->bodies.size()); }
bool BulletWorld::isDynamic(uint32_t body) const { return impl_->dynamic[body] != 0; }
float BulletWorld::smallestExtent(uint32_t body) const { return impl_->extent[body]; }

Transform BulletWorld::pose(uint32_t body) const {
  const btTransform& t = impl_->bodies[body]->getWorldTransform();
  Transform xf;
  xf.p = fromBt(t.getOrigin());
  xf.q = (fromBt(t.getRotation()) * impl_->principal[body].conjugate()).normalized();
  return xf;
}

Vec3 BulletWorld::linearVelocity(uint32_t body) const { return fromBt(impl_->bodies[body]->getLinearVelocity()); }
Vec3 BulletWorld::angularVelocity(uint32_t body) const { return fromBt(impl_->bodies[body]->getAngularVelocity()); }

void BulletWorld::readContactPoints(std::vector<BulletContactPoint>& out) const {
  out.clear();
  btCollisionDispatcher& d = impl_->dispatcher;
  for (int k = 0; k < d.getNumManifolds(); ++k) {
    const btPersistentManifold* pm = d.getManifoldByIndexInternal(k);
    const uint32_t a = uint32_t(pm->getBody0()->getUserIndex()), b = uint32_t(pm->getBody1()->getUserIndex());
    for (int j = 0; j < pm->getNumContacts(); ++j) out.push_back({a, b, float(-pm->getContactPoint(j).getDistance())});
  }
}

namespace {

// The first contact point Bullet made between bodies a and b in the last collision pass.
const btManifoldPoint* findPoint(btCollisionDispatcher& d, uint32_t a, uint32_t b) {
  for (int k = 0; k < d.getNumManifolds(); ++k) {
    const btPersistentManifold* pm = d.getManifoldByIndexInternal(k);
    const uint32_t i = uint32_t(pm->getBody0()->getUserIndex()), j = uint32_t(pm->getBody1()->getUserIndex());
    if (((i == a && j == b) || (i == b && j == a)) && pm->getNumContacts() > 0) return &pm->getContactPoint(0);
  }
  return nullptr;
}

}  // namespace

float BulletWorld::combinedFriction(uint32_t a, uint32_t b) const {
  const btManifoldPoint* p = findPoint(impl_->dispatcher, a, b);
  return p ? float(p->m_combinedFriction) : std::numeric_limits<float>::quiet_NaN();
}

float BulletWorld::combinedRestitution(uint32_t a, uint32_t b) const {
  const btManifoldPoint* p = findPoint(impl_->dispatcher, a, b);
  return p ? float(p->m_combinedRestitution) : std::numeric_limits<float>::quiet_NaN();
}

}  // namespace haif
