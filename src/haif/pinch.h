// Pinched bodies: a dynamic body pressed from opposite sides by bodies that cannot move.
//
// Between two static bodies (a box wedged under a wall's foot on the ground) both push-outs ask the
// body to move, in opposite directions; between a kinematic body and static geometry (a bar sweeping
// a pile into a wall) the kinematic one asks it to move into the other. No velocity meets all of its
// contacts, so each sweep adds impulse to both sides, warm starting carries it into the next step,
// and when one side lets go the body leaves with all of it (80 m/s out of a pit swept at 14 m/s).
// Such contacts are marked (Contact::pinched) and solved without push-out and without impulses
// carried between steps, and the static side is solved last, so the body stays out of the static
// world and the kinematic body passes it instead.
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
  uint32_t mark(const BodyStore& bodies, const ContactEdge* edges, std::vector<Contact>& contacts);

 private:
  struct Note {
    uint32_t body;
    Vec3 n1, n2;  // the first two unlike normals pointing into the body
    bool two = false, pinched = false;
  };
  std::vector<int32_t> noteOfBody_;   // per body: its Note this step, or -1
  std::vector<Note> notes_;
  struct Candidate {
    uint32_t contact;  // overlapping, between a dynamic and an immovable body
    uint32_t note;     // its dynamic body's Note
  };
  std::vector<Candidate> candidates_;
};

}  // namespace haif
