#include "haif/islands.h"

#include "dynamics/contact_solver.h"

#include <algorithm>

namespace haif {

// Every key is written, equal or not: the next step compares with this one's.
bool IslandBuilder::sameBodiesAndJoints(const BodyStore& bodies, const std::vector<Joint>& joints) {
  const uint32_t n = static_cast<uint32_t>(bodies.size());
  bool same = bodyKeys_.size() == n && jointKeys_.size() == joints.size();
  bodyKeys_.resize(n);
  jointKeys_.resize(joints.size());
  for (uint32_t i = 0; i < n; ++i) {
    const uint8_t key = bodyKey(bodies, i);
    same = same && bodyKeys_[i] == key;
    bodyKeys_[i] = key;
  }
  for (size_t j = 0; j < joints.size(); ++j) {
    const JointDef& d = joints[j].def;
    const JointKey key{d.bodyA, d.bodyB, jointRowCount(d), joints[j].broken};
    same = same && jointKeys_[j] == key;
    jointKeys_[j] = key;
  }
  return same;
}

void IslandBuilder::refreshCarriers(const BodyStore& bodies, IslandSet& out) const {
  for (Island& isl : out.islands) {
    if (isl.carrier == Island::kNoCarrier) continue;
    isl.carrierV = bodies.v[isl.carrier];
    isl.carrierW = bodies.w[isl.carrier];
    isl.carrierAt = bodies.xf[isl.carrier].p;
  }
}

void IslandBuilder::uniteContacts(const BodyStore& bodies, const ContactEdge* contacts, uint32_t begin, uint32_t end) {
  uint32_t touching = 0, points = 0;
  for (uint32_t ci = begin; ci < end; ++ci) {
    const ContactEdge& c = contacts[ci];
    uint32_t body = kNoBody;
    if (c.count > 0) {
      ++touching;
      points += c.count;
      const bool dynA = bodies.isAwakeDynamic(c.a), dynB = bodies.isAwakeDynamic(c.b);
      if (dynA && dynB && !c.apart) unite(c.a, c.b);
      // A contact belongs to the island of its (first) awake dynamic body.
      body = dynA ? c.a : dynB ? c.b : kNoBody;
    }
    contactBody_[ci] = body;
  }
  __atomic_fetch_add(&touching_, touching, __ATOMIC_RELAXED);
  __atomic_fetch_add(&points_, points, __ATOMIC_RELAXED);
}

void IslandBuilder::rootBodies(const BodyStore& bodies, uint32_t begin, uint32_t end) {
  for (uint32_t i = begin; i < end; ++i) root_[i] = bodies.isAwakeDynamic(i) ? find(i) : kNoBody;
}

void IslandBuilder::gather(const BodyStore& bodies, const ContactEdge* contacts, uint32_t contactCount,
                           const std::vector<Joint>& joints, IslandSet& out) {
  const uint32_t n = static_cast<uint32_t>(bodies.size());
  const uint32_t nc = contactCount;
  out.touchingContacts = touching_;
  out.contactPoints = points_;
  auto activeEnd = [&](uint32_t i) { return i != kWorldBody && bodies.isAwakeDynamic(i); };

  // Number the islands by their smallest body id (the root), in ascending order: a root comes
  // before every other body of its island.
  islandOfRoot_.resize(n);
  islandOfBody_.resize(n);
  unsorted_.clear();
  for (uint32_t i = 0; i < n; ++i) {
    islandOfBody_[i] = -1;
    const uint32_t r = root_[i];
    if (r == kNoBody) continue;
    if (r == i) {
      islandOfRoot_[i] = static_cast<int32_t>(unsorted_.size());
      unsorted_.emplace_back();
    }
    islandOfBody_[i] = islandOfRoot_[r];
    ++unsorted_[islandOfRoot_[r]].bodyCount;
  }
  auto islandOfContact = [&](uint32_t ci) -> int32_t {
    if (contactBody_[ci] == kNoBody) return -1;
    const ContactEdge& e = contacts[ci];
    const int32_t k = islandOfBody_[contactBody_[ci]];
    // Apart, between two islands: it holds nothing this step and belongs to neither.
    if (e.apart && bodies.isAwakeDynamic(e.a) && bodies.isAwakeDynamic(e.b) && islandOfBody_[e.a] != islandOfBody_[e.b]) return -1;
    return k;
  };
  for (uint32_t ci = 0; ci < nc; ++ci) {
    const int32_t k = islandOfContact(ci);
    if (k < 0) continue;
    Island& isl = unsorted_[k];
    ++isl.contactCount;
    isl.rows += solverRowsFor(int(contacts[ci].count));
    if (isl.carrier == Island::kNoCarrier) {
      const ContactEdge& e = contacts[ci];
      const uint32_t carrier = bodies.kind[e.a] == BodyKind::Kinematic   ? e.a
                               : bodies.kind[e.b] == BodyKind::Kinematic ? e.b
                                                                         : Island::kNoCarrier;
      if (carrier != Island::kNoCarrier) {
        isl.carrier = carrier;
        isl.carrierV = bodies.v[carrier];
        isl.carrierW = bodies.w[carrier];
        isl.carrierAt = bodies.xf[carrier].p;
      }
    }
  }
  auto islandOfJoint = [&](const Joint& j) -> int32_t {
    if (j.broken) return -1;
    if (activeEnd(j.def.bodyA)) return islandOfBody_[j.def.bodyA];
    if (activeEnd(j.def.bodyB)) return islandOfBody_[j.def.bodyB];
    return -1;
  };
  for (const Joint& j : joints) {
    const int32_t k = islandOfJoint(j);
    if (k < 0) continue;
    ++unsorted_[k].jointCount;
    unsorted_[k].rows += jointRowCount(j.def);
  }

  // Largest first, so the longest task starts first when islands run in parallel.
  const uint32_t m = static_cast<uint32_t>(unsorted_.size());
  order_.resize(m);
  for (uint32_t k = 0; k < m; ++k) order_[k] = k;
  std::stable_sort(order_.begin(), order_.end(), [&](uint32_t x, uint32_t y) {
    if (unsorted_[x].rows != unsorted_[y].rows) return unsorted_[x].rows > unsorted_[y].rows;
    return unsorted_[x].bodyCount > unsorted_[y].bodyCount;
  });
  out.islands.resize(m);
  cursorBody_.resize(m);
  cursorContact_.resize(m);
  cursorJoint_.resize(m);
  uint32_t fb = 0, fc = 0, fj = 0;
  out.totalRows = out.largestRows = out.largestBodies = 0;
  for (uint32_t s = 0; s < m; ++s) {
    Island isl = unsorted_[order_[s]];
    isl.firstBody = fb;
    isl.firstContact = fc;
    fb += isl.bodyCount;
    fc += isl.contactCount;
    isl.firstJoint = fj;
    fj += isl.jointCount;
    cursorJoint_[order_[s]] = isl.firstJoint;
    cursorBody_[order_[s]] = isl.firstBody;
    cursorContact_[order_[s]] = isl.firstContact;
    out.totalRows += isl.rows;
    out.largestRows = std::max(out.largestRows, isl.rows);
    out.largestBodies = std::max(out.largestBodies, isl.bodyCount);
    out.islands[s] = isl;
  }
  out.bodies.resize(fb);
  out.contacts.resize(fc);
  out.joints.resize(fj);
  for (uint32_t i = 0; i < n; ++i) {
    if (islandOfBody_[i] >= 0) out.bodies[cursorBody_[islandOfBody_[i]]++] = i;
  }
  for (uint32_t ci = 0; ci < nc; ++ci) {
    const int32_t k = islandOfContact(ci);
    if (k >= 0) out.contacts[cursorContact_[k]++] = ci;
  }
  for (uint32_t ji = 0; ji < joints.size(); ++ji) {
    const int32_t k = islandOfJoint(joints[ji]);
    if (k >= 0) out.joints[cursorJoint_[k]++] = ji;
  }
}

}  // namespace haif
