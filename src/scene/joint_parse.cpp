#include "scene/joint_parse.h"

#include <cmath>

namespace haif {

BodyNames::BodyNames(const SceneDesc& scene) {
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].name.empty()) indices[scene.bodies[i].name].push_back(static_cast<int32_t>(i));
}

namespace {

const std::vector<std::string> kJointTypes{"ball", "hinge", "fixed", "distance", "rope", "slider", "cone_twist"};
constexpr float kDeg = kPi / 180.0f;

// "world", a body name, or a body index; -1 is the world.
int32_t parseBodyRef(const JsonNode& node, const SceneDesc& scene, const BodyNames& names) {
  const Json& v = node.json();
  const int count = static_cast<int>(scene.bodies.size());
  if (v.is_number_integer() || v.is_number_unsigned()) {
    if (count == 0) fail(node, "the scene has no bodies to join");
    return readInt(node, 0, count - 1);
  }
  if (!v.is_string()) fail(node, "must be a body name, a body index or \"world\" (got " + describeValue(v) + ")");
  const std::string name = v.get<std::string>();
  auto it = names.indices.find(name);
  if (name == "world") {
    if (it != names.indices.end()) fail(node, "\"world\" is ambiguous: a body is also named 'world'");
    return -1;
  }
  if (it == names.indices.end()) {
    std::vector<std::string> known{"world"};
    for (const auto& kv : names.indices) known.push_back(kv.first);
    const std::string hint = didYouMean(name, known);
    fail(node, "no body is named '" + name + "'" +
                   (hint.empty() ? " (name bodies with \"name\", or use an index)" : hint));
  }
  if (it->second.size() > 1)
    fail(node, "body name '" + name + "' is ambiguous: " + scene.bodies[size_t(it->second[0])].where + " and " +
                   scene.bodies[size_t(it->second[1])].where + " both have it");
  return it->second[0];
}

std::string describeBody(const SceneDesc& scene, int32_t b) {
  if (b < 0) return "the world";
  const BodyDesc& d = scene.bodies[size_t(b)];
  const char* motion = d.motion == MotionType::Static      ? "static"
                       : d.motion == MotionType::Kinematic ? "kinematic"
                                                           : "dynamic";
  return std::string(motion) + " " + (d.name.empty() ? d.where : "'" + d.name + "'");
}

// [lo, hi] with lo <= hi, scaled (degrees to radians), each within [-bound, bound] when bound > 0.
void readRange(const JsonNode& node, float scale, float bound, const char* unit, float& lo, float& hi) {
  if (!node.json().is_array() || node.size() != 2)
    fail(node, std::string("must be [lower, upper] in ") + unit + " (got " + describeValue(node.json()) + ")");
  for (size_t i = 0; i < 2; ++i) {
    const float v = readFloat(node.element(i));
    if (bound > 0.0f && std::fabs(v) > bound)
      fail(node.element(i), "must be within +-" + formatNumber(bound) + " " + unit + " (got " + formatNumber(v) + ")");
  }
  lo = readFloat(node.element(0)) * scale;
  hi = readFloat(node.element(1)) * scale;
  if (lo > hi) fail(node.element(1), "upper must be >= lower (" + formatNumber(readFloat(node.element(0))) + ")");
}

Vec3 readDirection(const JsonNode& node) {
  const Vec3 v = readVec3(node);
  if (!(v.norm() > 1e-6f)) fail(node, "must not be the zero vector");
  return v.normalized();
}

// Exactly one of two alternative keys (or neither when optional).
JsonNode oneOf(const JsonNode& j, const char* a, const char* b, bool required, const std::string& hint) {
  const JsonNode na = j.member(a), nb = j.member(b);
  if (na.present() && nb.present()) failAtKey(j, b, std::string("give either '") + a + "' or '" + b + "', not both");
  if (!na.present() && !nb.present() && required) fail(j, std::string("missing '") + a + "' (or '" + b + "'): " + hint);
  return na.present() ? na : nb;
}

void parseMotor(const JsonNode& node, JointDef& p) {
  checkKeys(node, {"speed", "max_force"});
  p.motorEnabled = true;
  p.motorSpeed = readFloat(requireMember(node, "speed", "rad/s (hinge) or m/s (slider)"));
  p.maxMotorForce = readPositive(requireMember(node, "max_force", "N m (hinge) or N (slider), > 0"));
}

void parseServo(const JsonNode& node, bool hinge, JointDef& p) {
  checkKeys(node, hinge ? std::vector<std::string>{"keys", "keys_deg", "max_force", "loop", "response_time"}
                        : std::vector<std::string>{"keys", "max_force", "loop", "response_time"});
  p.motorEnabled = true;
  const char* hint = "[[time, position], ...]";
  const JsonNode keys = hinge ? oneOf(node, "keys", "keys_deg", true, hint) : requireMember(node, "keys", hint);
  const float scale = keys.place.size() > 4 && keys.place.compare(keys.place.size() - 4, 4, "_deg") == 0 ? kDeg : 1.0f;
  requireArray(keys);
  if (keys.size() == 0) fail(keys, "needs at least one [time, position] key");
  for (size_t i = 0; i < keys.size(); ++i) {
    const JsonNode k = keys.element(i);
    if (!k.json().is_array() || k.size() != 2)
      fail(k, "must be [time, position] (got " + describeValue(k.json()) + ")");
    ServoKey key;
    key.time = readNonNegative(k.element(0));
    key.position = readFloat(k.element(1)) * scale;
    if (!p.servo.empty() && !(key.time > p.servo.back().time))
      fail(k.element(0), "times must increase (previous key at " + formatNumber(p.servo.back().time) + " s)");
    p.servo.push_back(key);
  }
  p.maxMotorForce = readPositive(requireMember(node, "max_force", "N m (hinge) or N (slider), > 0"));
  if (node.member("loop").present()) p.servoLoop = readBool(node.member("loop"));
  p.servoTime = optPositive(node, "response_time", p.servoTime);
}

}  // namespace

JointType parseJointType(const JsonNode& node, bool& isRope) {
  const std::string s = readString(node);
  isRope = s == "rope";
  if (s == "ball") return JointType::Ball;
  if (s == "hinge") return JointType::Hinge;
  if (s == "fixed") return JointType::Fixed;
  if (s == "distance" || s == "rope") return JointType::Distance;
  if (s == "slider") return JointType::Slider;
  if (s == "cone_twist") return JointType::ConeTwist;
  fail(node, "unknown joint type '" + s + "'" + didYouMean(s, kJointTypes) +
                 "; use ball, hinge, fixed, distance, rope, slider or cone_twist");
}

JointDesc parseJoint(const JsonNode& node, const SceneDesc& scene, const BodyNames& names) {
  requireObject(node);
  bool rope = false;
  const JsonNode typeNode =
      requireMember(node, "type", "one of ball, hinge, fixed, distance, rope, slider, cone_twist");
  const JointType type = parseJointType(typeNode, rope);
  const bool distance = type == JointType::Distance;
  const bool hasAxis = type == JointType::Hinge || type == JointType::Slider || type == JointType::ConeTwist;

  std::vector<std::string> keys{"type", "name", "body_a", "body_b", "local_anchor_a", "local_anchor_b",
                                "break_force", "break_torque", "collide"};
  auto add = [&](std::initializer_list<const char*> more) { keys.insert(keys.end(), more.begin(), more.end()); };
  if (distance) add({"anchor_a", "anchor_b"});
  else add({"anchor"});
  if (hasAxis) add({"axis", "local_axis"});
  if (type == JointType::Hinge) add({"limits", "limits_deg", "motor", "servo"});
  if (type == JointType::Slider) add({"limits", "motor", "servo"});
  if (type == JointType::ConeTwist) add({"swing", "swing_deg", "twist", "twist_deg"});
  if (distance) rope ? add({"length"}) : add({"min", "max"});
  checkKeys(node, keys);

  JointDesc j;
  j.where = node.place;
  j.params.type = type;
  if (node.member("name").present()) j.name = readString(node.member("name"));
  const JsonNode a = node.member("body_a");
  const JsonNode b = requireMember(node, "body_b", "a body name, a body index or \"world\"");
  j.bodyA = a.present() ? parseBodyRef(a, scene, names) : -1;
  j.bodyB = parseBodyRef(b, scene, names);
  if (j.bodyA == j.bodyB) fail(b, "a joint needs two different bodies (both are " + describeBody(scene, j.bodyA) + ")");
  auto dynamic = [&](int32_t i) { return i >= 0 && scene.bodies[size_t(i)].motion == MotionType::Dynamic; };
  if (!dynamic(j.bodyA) && !dynamic(j.bodyB))
    fail(b, "a joint needs a dynamic body (body_a is " + describeBody(scene, j.bodyA) + ", body_b is " +
                describeBody(scene, j.bodyB) + ")");

  // Anchors: world points, or one point in each body's frame.
  const JsonNode la = node.member("local_anchor_a"), lb = node.member("local_anchor_b");
  const JsonNode wa = node.member(distance ? "anchor_a" : "anchor");
  const JsonNode wb = distance ? node.member("anchor_b") : JsonNode{};
  if (la.present() || lb.present()) {
    if (wa.present() || wb.present()) failAtKey(node, la.present() ? "local_anchor_a" : "local_anchor_b",
                                                 "give world anchors or local anchors, not both");
    j.localAnchors = true;
    j.anchorA = readVec3(requireMember(node, "local_anchor_a", "the joint point in body A's frame"));
    j.anchorB = readVec3(requireMember(node, "local_anchor_b", "the joint point in body B's frame"));
  } else if (distance) {
    j.anchorA = readVec3(requireMember(node, "anchor_a", "world point on body A (or local_anchor_a/local_anchor_b)"));
    j.anchorB = readVec3(requireMember(node, "anchor_b", "world point on body B"));
  } else {
    j.anchorA = j.anchorB =
        readVec3(requireMember(node, "anchor", "world point of the joint (or local_anchor_a/local_anchor_b)"));
  }
  if (hasAxis) {
    const JsonNode axis = oneOf(node, "axis", "local_axis", true, "the joint axis [x, y, z]");
    j.localAxis = axis.place.size() > 10 && axis.place.compare(axis.place.size() - 10, 10, "local_axis") == 0;
    j.axis = readDirection(axis);
  }

  JointDef& p = j.params;
  if (type == JointType::Hinge || type == JointType::Slider) {
    const bool hinge = type == JointType::Hinge;
    const JsonNode lim = hinge ? oneOf(node, "limits", "limits_deg", false, "") : node.member("limits");
    if (lim.present()) {
      const bool deg = node.member("limits_deg").present();
      p.limitEnabled = true;
      readRange(lim, deg ? kDeg : 1.0f, hinge ? (deg ? 180.0f : kPi) : 0.0f, hinge ? (deg ? "degrees" : "rad") : "m",
                p.lower, p.upper);
    }
    const JsonNode motor = node.member("motor"), servo = node.member("servo");
    if (motor.present() && servo.present())
      failAtKey(node, "servo", "give either a motor (constant speed) or a servo (trajectory), not both");
    if (motor.present()) parseMotor(motor, p);
    if (servo.present()) parseServo(servo, hinge, p);
  }
  if (type == JointType::ConeTwist) {
    const JsonNode swing = oneOf(node, "swing", "swing_deg", false, "");
    if (swing.present()) {
      const bool deg = node.member("swing_deg").present();
      const float v = readPositive(swing);
      if (v > (deg ? 180.0f : kPi)) fail(swing, "must be at most " + std::string(deg ? "180 degrees" : "pi"));
      p.swingLimit = deg ? v * kDeg : v;
    }
    const JsonNode twist = oneOf(node, "twist", "twist_deg", false, "");
    if (twist.present()) {
      const bool deg = node.member("twist_deg").present();
      readRange(twist, deg ? kDeg : 1.0f, deg ? 180.0f : kPi, deg ? "degrees" : "rad", p.twistLower, p.twistUpper);
    }
  }
  if (distance) {
    p.minDistance = p.maxDistance = -1.0f;  // the initial anchor distance
    if (rope) {
      p.minDistance = 0.0f;
      if (node.member("length").present()) p.maxDistance = readPositive(node.member("length"));
    } else {
      if (node.member("min").present()) p.minDistance = readNonNegative(node.member("min"));
      if (node.member("max").present()) p.maxDistance = readPositive(node.member("max"));
      if (p.minDistance >= 0.0f && p.maxDistance >= 0.0f && p.minDistance > p.maxDistance)
        fail(node.member("max"), "must be >= min (" + formatNumber(p.minDistance) + ")");
    }
  }
  if (node.member("break_force").present()) p.breakForce = readPositive(node.member("break_force"));
  if (node.member("break_torque").present()) p.breakTorque = readPositive(node.member("break_torque"));
  if (node.member("collide").present()) p.collideConnected = readBool(node.member("collide"));
  return j;
}

}  // namespace haif
