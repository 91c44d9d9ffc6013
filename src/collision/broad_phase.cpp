#include "collision/broad_phase.h"

namespace haif {

void BroadPhase::addBody(uint32_t body, const Aabb& tight, bool isStatic, float marginScale) {
  if (proxy_.size() <= body) {
    proxy_.resize(body + 1, DynamicTree::kNull);
    isStatic_.resize(body + 1, 0);
    marginScale_.resize(body + 1, 1.0f);
    movedFlag_.resize(body + 1, 0);
    previousFat_.resize(body + 1);
  }
  previousFat_[body] = Aabb{};  // new: it overlapped nothing before
  wideReady_ = false;
  if (isStatic) staticWideReady_ = false;
  isStatic_[body] = isStatic ? 1 : 0;
  marginScale_[body] = marginScale;
  // Static boxes need no margin: they never move.
  proxy_[body] = isStatic ? staticTree_.createProxy(tight, body)
                          : movingTree_.createProxy(tight.expanded(fatMargin * marginScale), body);
  markMoved(body);
}

bool BroadPhase::update(uint32_t body, const Aabb& tight, const Vec3& lead) {
  if (fits(body, tight)) return false;
  move(body, tight, lead, false);
  return true;
}

void BroadPhase::move(uint32_t body, const Aabb& tight, const Vec3& lead, bool rebuildLater) {
  const int32_t p = proxy_[body];
  if (!movedFlag_[body]) previousFat_[body] = movingTree_.fatAabb(p);
  const Aabb fat = tight.expanded(fatMargin * marginScale_[body]).swept(lead);
  wideReady_ = false;
  if (rebuildLater) movingTree_.setLeafBox(p, fat);
  else movingTree_.moveProxy(p, fat);
  markMoved(body);
}

}  // namespace haif
