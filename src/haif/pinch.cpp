#include "haif/pinch.h"

namespace haif {

uint32_t PinchDetector::mark(const BodyStore& bodies, const ContactEdge* edges, std::vector<Contact>& contacts) {
  if (noteOfBody_.size() < bodies.size()) noteOfBody_.resize(bodies.size(), -1);
  notes_.clear();
  candidates_.clear();
  const uint32_t n = static_cast<uint32_t>(contacts.size());
  for (uint32_t ci = 0; ci < n; ++ci) {
    const ContactEdge& e = edges[ci];
    if (!e.pressedByImmovable) continue;
    const bool da = bodies.isAwakeDynamic(e.a);
    const uint32_t dyn = da ? e.a : e.b;
    const Contact& c = contacts[ci];
    // The normal points from shape A to shape B: into the dynamic body when it is B.
    const Vec3 into = da ? Vec3(-c.manifold.points[0].normal) : c.manifold.points[0].normal;
    int32_t& slot = noteOfBody_[dyn];
    if (slot < 0) {
      slot = int32_t(notes_.size());
      notes_.push_back(Note{dyn, into, Vec3::Zero()});
      candidates_.push_back({ci, uint32_t(slot)});
      continue;
    }
    candidates_.push_back({ci, uint32_t(slot)});
    Note& note = notes_[slot];
    if (into.dot(note.n1) < kOpposed || (note.two && into.dot(note.n2) < kOpposed)) {
      note.pinched = true;
    } else if (!note.two) {
      note.n2 = into;
      note.two = true;
    }
  }
  for (const Candidate& k : candidates_) contacts[k.contact].pinched = notes_[k.note].pinched;
  uint32_t pinched = 0;
  for (const Note& note : notes_) {
    pinched += note.pinched ? 1u : 0u;
    noteOfBody_[note.body] = -1;
  }
  return pinched;
}

}  // namespace haif
