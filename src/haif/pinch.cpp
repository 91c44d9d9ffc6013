#include "haif/pinch.h"

namespace haif {

PinchDetector::Side PinchDetector::sideOf(const BodyStore& bodies, const ContactEdge& e, const Contact& c) {
  const bool da = bodies.isAwakeDynamic(e.a);
  const Vec3& n = c.manifold.points[0].normal;  // from shape A into shape B
  return Side{da ? e.a : e.b, da ? e.b : e.a, da ? Vec3(-n) : n};
}

uint32_t PinchDetector::mark(const BodyStore& bodies, const ContactEdge* edges, ContactList& contacts) {
  if (noteOfBody_.size() < bodies.size()) noteOfBody_.resize(bodies.size(), -1);
  notes_.clear();
  candidates_.clear();
  pinchedContacts_.clear();
  const uint32_t n = static_cast<uint32_t>(contacts.size());
  for (uint32_t ci = 0; ci < n; ++ci) {
    if (!edges[ci].pressedByImmovable) continue;
    const Side side = sideOf(bodies, edges[ci], contacts[ci]);
    const uint32_t dyn = side.dyn;
    const Vec3& into = side.into;
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
  for (const Candidate& k : candidates_) setPinched(contacts, k.contact, notes_[k.note].pinched);
  uint32_t pinched = candidates_.empty() ? 0u : markCrushes(bodies, edges, contacts);
  for (const Note& note : notes_) {
    pinched += note.pinched ? 1u : 0u;
    noteOfBody_[note.body] = -1;
  }
  return pinched;
}

uint32_t PinchDetector::markCrushes(const BodyStore& bodies, const ContactEdge* edges, ContactList& contacts) {
  if (pressureOfBody_.size() < bodies.size()) pressureOfBody_.resize(bodies.size(), -1);
  pressures_.clear();
  auto press = [&](uint32_t body, const Vec3& into, const Vec3& push, uint32_t source, uint32_t via, uint32_t head) {
    pressureOfBody_[body] = int32_t(pressures_.size());
    pressures_.push_back(Pressure{body, into, push, source, via, head});
  };
  const uint32_t n = static_cast<uint32_t>(contacts.size());
  // Seeds: a kinematic body whose surface, where it presses a dynamic body, moves into it.
  for (const Candidate& k : candidates_) {
    const Side s = sideOf(bodies, edges[k.contact], contacts[k.contact]);
    if (bodies.kind[s.other] != BodyKind::Kinematic || pressureOfBody_[s.dyn] >= 0) continue;
    const Vec3 at = contacts[k.contact].manifold.points[0].position;
    const Vec3 surface = bodies.velocityAt(s.other, at);
    if (surface.dot(s.into) > 0.0f) press(s.dyn, s.into, s.into, s.other, k.contact, uint32_t(pressures_.size()));
  }
  if (pressures_.empty()) return 0;
  // Passed on, in contact order (the same on any thread count), to the bodies ahead, along the
  // contacts that can carry it: listed once, and a contact whose bodies are both pressed leaves the
  // list (pressure is only added, so it carries nothing more). A turning drum's pressure took all
  // eight passes over every contact of its pile.
  links_.clear();
  for (uint32_t ci = 0; ci < n; ++ci) {
    const ContactEdge& e = edges[ci];
    if (e.overlapping && bodies.isAwakeDynamic(e.a) && bodies.isAwakeDynamic(e.b)) links_.push_back(ci);
  }
  for (int pass = 0; pass < kCrushPasses; ++pass) {
    bool grew = false;
    size_t kept = 0;
    for (size_t j = 0; j < links_.size(); ++j) {
      const uint32_t ci = links_[j];
      const ContactEdge& e = edges[ci];
      const int32_t pa = pressureOfBody_[e.a], pb = pressureOfBody_[e.b];
      if (pa >= 0 && pb >= 0) continue;
      links_[kept++] = ci;
      if (pa < 0 && pb < 0) continue;
      const Vec3& ab = contacts[ci].manifold.points[0].normal;
      if (pa >= 0 && ab.dot(pressures_[pa].into) >= kAhead) {
        press(e.b, ab, pressures_[pa].push, pressures_[pa].source, ci, pressures_[pa].head);
        grew = true;
      } else if (pb >= 0 && -ab.dot(pressures_[pb].into) >= kAhead) {
        press(e.a, -ab, pressures_[pb].push, pressures_[pb].source, ci, pressures_[pb].head);
        grew = true;
      }
    }
    links_.resize(kept);
    if (!grew) break;
  }
  // Ends: a pressed body that another immovable body pushes back, against the row's push too: each
  // link may turn the push by up to 60 degrees, and a lift raising a box under a box that leaned on
  // a wall read as a crush (the lift then passed through the lower box). (The kinematic body the
  // pressure comes from does not close a crush of its own: a turning drum presses a pile from every
  // side and carries it along.)
  uint32_t crushed = 0;
  for (const Candidate& k : candidates_) {
    const Side s = sideOf(bodies, edges[k.contact], contacts[k.contact]);
    const int32_t first = pressureOfBody_[s.dyn];
    if (first < 0 || s.other == pressures_[first].source || s.into.dot(pressures_[first].into) >= kOpposed ||
        s.into.dot(pressures_[first].push) >= kOpposed)
      continue;
    setPinched(contacts, k.contact, true);
    for (const uint32_t end : {uint32_t(first), pressures_[first].head}) {
      Pressure& q = pressures_[end];
      if (q.marked) continue;
      q.marked = true;
      if (end == q.head) setPinched(contacts, q.via, true);
      if (noteOfBody_[q.body] < 0 || !notes_[noteOfBody_[q.body]].pinched) ++crushed;
    }
  }
  for (const Pressure& q : pressures_) pressureOfBody_[q.body] = -1;
  return crushed;
}

}  // namespace haif
