// Pinched bodies: a dynamic body pressed from opposite sides by bodies that cannot move.
//
// Between two static bodies (a box wedged under a wall's foot on the ground) both push-outs ask the
// body to move, in opposite directions; between a kinematic body and static geometry (a bar sweeping
// a pile into a wall) the kinematic one asks it to move into the other. No velocity meets all of its
// contacts, so each sweep adds impulse to both sides, warm starting carries it into the next step,
// and when one side lets go the body leaves with all of it (80 m/s out of a pit swept at 14 m/s).
// A kinematic body presses where its surface overlaps the body or closes a point's gap within the
// step (the speculative row then asks the body to move away as a push-out would).
// Such contacts are marked (Contact::pinched) and solved without push-out and without impulses
// carried between steps, and the static side is solved last, so the body stays out of the static
// world and the kinematic body passes it instead.
//
// A crush is the same conflict passed along a row of bodies: a kinematic blade driving a pile into a
// wall presses the first body into the second and so on to the one against the wall. Each body is
// pressed from one side only, yet the row's impulses grow step after step just the same (a 2 m/s
// blade meeting a wall threw 7435 bodies against the speed bound in 1200 steps). The pressure of a
// kinematic body moving into a dynamic one is passed on through overlapping contacts whose normal
// points the same way (within 60 degrees); a pressed body that touches another immovable body
// pushing it back (more than 120 degrees away) closes a crush, and the row's two ends are marked
// pinched: its contact with that body and the kinematic body's contact with the row's first body.
// With both ends carrying nothing between steps the row's impulses cannot grow; the links between
// its dynamic bodies keep theirs (in a pile they carry its weight, and rows run through it to a wall
// far from any real crush: marked as well, a pile stirred by a paddle sank twice as deep).
#pragma once

#include "core/body_store.h"
#include "dynamics/contact.h"
#include "haif/islands.h"

#include <cstdint>
#include <vector>

namespace haif {

class PinchDetector {
 public:
  /// Two normals pointing into a body this far from parallel (cosine below) press it from opposite
  /// sides: more than 120 degrees apart.
  static constexpr float kOpposed = -0.5f;

  /// Sets Contact::pinched on the contacts the narrow phase noted as pressed by an immovable body
  /// (ContactEdge::pressedByImmovable) whose dynamic body is pressed so from opposite sides (the
  /// narrow phase clears it on every contact it visits). Contacts are read in index order: the
  /// result does not depend on threads. Returns the number of pinched bodies.
  uint32_t mark(const BodyStore& bodies, const ContactEdge* edges, ContactList& contacts);
  /// The contacts the last mark() set pinched (some may be listed twice): read without the contacts.
  const std::vector<uint32_t>& pinchedContacts() const { return pinchedContacts_; }

  /// A kinematic body's pressure passes to a body ahead when their normal is within 60 degrees of it.
  static constexpr float kAhead = 0.5f;
  /// Passes over the contacts that carry pressure along rows: each reaches at least one body further
  /// (more where the contact order follows the row); a wider pile is not crushed as a whole.
  static constexpr int kCrushPasses = 8;

 private:
  // The dynamic body of a contact with an immovable body, the other body, and the direction the
  // contact pushes the dynamic one in.
  struct Side {
    uint32_t dyn, other;
    Vec3 into;
  };
  static Side sideOf(const BodyStore& bodies, const ContactEdge& e, const Contact& c);

  // The crushes (header comment): returns the bodies at their ends that were not pinched already.
  uint32_t markCrushes(const BodyStore& bodies, const ContactEdge* edges, ContactList& contacts);

  struct Note {
    uint32_t body;
    Vec3 n1, n2;  // the first two unlike normals pointing into the body
    bool two = false, pinched = false;
  };
  void setPinched(ContactList& contacts, uint32_t c, bool pinched) {
    contacts[c].pinched = pinched;
    if (pinched) pinchedContacts_.push_back(c);
  }
  std::vector<uint32_t> pinchedContacts_;
  std::vector<uint32_t> links_;  // markCrushes: the contacts that may still pass pressure on
  std::vector<int32_t> noteOfBody_;   // per body: its Note this step, or -1
  std::vector<Note> notes_;
  struct Candidate {
    uint32_t contact;  // overlapping, between a dynamic and an immovable body
    uint32_t note;     // its dynamic body's Note
  };
  std::vector<Candidate> candidates_;

  struct Pressure {
    uint32_t body = 0;
    Vec3 into = Vec3::Zero();  // the direction the body is pushed
    Vec3 push = Vec3::Zero();  // the direction the kinematic body pushed the first body of the row
    uint32_t source = 0;       // the kinematic body the pressure comes from
    uint32_t via = 0;          // the contact it came through
    uint32_t head = 0;         // the Pressure of its row's first body (the one the kinematic body touches)
    bool marked = false;       // its body's end of a crush is marked (counted once)
  };
  std::vector<int32_t> pressureOfBody_;  // per body: its Pressure this step, or -1
  std::vector<Pressure> pressures_;
};

}  // namespace haif
