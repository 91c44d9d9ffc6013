#include "scene/generator_parse.h"

#include "scene/generators.h"
#include "scene/scene_validate.h"

#include <cmath>
#include <limits>

namespace haif {

namespace {

const std::vector<std::string> kGeneratorTypes{"ground", "stack", "stacks", "pyramid_2d", "pyramid_3d", "many_pyramids",
                                               "wall", "grid", "random_pile", "domino_run"};

Vec3d optVec3d(const JsonNode& g, const std::string& key, const Vec3d& def) {
  const JsonNode m = g.member(key);
  return m.present() ? readVec3(m).cast<double>() : def;
}

double optPos(const JsonNode& g, const std::string& key, double def) {
  const JsonNode m = g.member(key);
  return m.present() ? readPositive(m) : def;
}

double optNonNeg(const JsonNode& g, const std::string& key, double def) {
  const JsonNode m = g.member(key);
  return m.present() ? readNonNegative(m) : def;
}

Vec3d optPositiveVec3d(const JsonNode& g, const std::string& key, const Vec3d& def) {
  const JsonNode m = g.member(key);
  return m.present() ? readPositiveVec3(m).cast<double>() : def;
}

// Counts are ints >= 1; the scene-wide cap is checked once the total is known.
int count(const JsonNode& g, const std::string& key, int def) {
  const JsonNode m = g.member(key);
  if (!m.present()) {
    if (def > 0) return def;
    fail(g, "missing required key '" + key + "'");
  }
  return readInt(m, 1, static_cast<int>(kMaxSceneBodies));
}

void checkTotal(const JsonNode& g, const std::string& key, int64_t n, size_t already) {
  if (n + static_cast<int64_t>(already) > kMaxSceneBodies) {
    const JsonNode at = g.member(key).present() ? g.member(key) : g;
    fail(at, "would make " + std::to_string(n + static_cast<int64_t>(already)) + " bodies; a scene holds at most " +
                 std::to_string(kMaxSceneBodies));
  }
}

// Common keys: body type, material, mass, damping.
BodyPrototype prototype(const JsonNode& g, const ParseContext& ctx, MotionType def) {
  BodyPrototype p;
  p.motion = g.member("body_type").present() ? parseMotionType(g.member("body_type")) : def;
  if (g.member("material").present()) p.material = parseMaterialRef(g.member("material"), ctx);
  if (g.member("mass").present()) p.mass = parseMass(g.member("mass"), p.motion);
  if (g.member("damping").present()) parseDamping(g.member("damping"), p);
  return p;
}

std::vector<std::string> keys(std::vector<std::string> specific) {
  for (const char* k : {"type", "body_type", "material", "mass", "damping"}) specific.push_back(k);
  return specific;
}

// Axis-aligned extent of a shape turned by q: used to refuse grids whose bodies would overlap.
Vec3 shapeExtent(const ShapeDesc& s, const Quat& q) {
  return 2.0f * (q.toRotationMatrix().cwiseAbs() * shapeHalfBox(s));
}

}  // namespace

void expandGenerator(const JsonNode& g, ParseContext& ctx, std::vector<BodyDesc>& out) {
  requireObject(g);
  const JsonNode typeNode = requireMember(g, "type", "one of ground, stack, stacks, pyramid_2d, pyramid_3d, many_pyramids, wall, grid, random_pile, domino_run");
  const std::string type = readString(typeNode);
  const std::string& where = g.place;

  if (type == "ground") {
    checkKeys(g, {"type", "material", "half_extents", "position"});
    GroundParams p;
    p.halfExtents = optPositiveVec3d(g, "half_extents", p.halfExtents);
    p.position = optVec3d(g, "position", Vec3d(0.0, -p.halfExtents.y(), 0.0));
    checkTotal(g, "type", 1, out.size());
    generateGround(p, prototype(g, ctx, MotionType::Static), where, out);
  } else if (type == "stack") {
    checkKeys(g, keys({"count", "position", "half_extents", "gap"}));
    StackParams p;
    p.count = count(g, "count", 0);
    p.base = optVec3d(g, "position", p.base);
    p.halfExtents = optPositiveVec3d(g, "half_extents", p.halfExtents);
    p.gap = optNonNeg(g, "gap", p.gap);
    checkTotal(g, "count", p.count, out.size());
    generateStack(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "stacks") {
    checkKeys(g, keys({"count", "per_stack", "spacing", "origin", "half_extents", "gap"}));
    StacksParams p;
    p.count = count(g, "count", 0);
    p.perStack = count(g, "per_stack", p.perStack);
    p.halfExtents = optPositiveVec3d(g, "half_extents", p.halfExtents);
    p.spacing = optPos(g, "spacing", p.spacing);
    p.origin = optVec3d(g, "origin", p.origin);
    p.gap = optNonNeg(g, "gap", p.gap);
    const double footprint = 2.0 * std::max(p.halfExtents.x(), p.halfExtents.z());
    if (p.spacing < footprint)
      fail(g.member("spacing").present() ? g.member("spacing") : g,
           "stacks would overlap: spacing " + formatNumber(p.spacing) + " is less than the box width " + formatNumber(footprint));
    checkTotal(g, "count", p.count, out.size());
    generateStacks(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "pyramid_2d") {
    checkKeys(g, keys({"base", "half_extent", "origin"}));
    Pyramid2dParams p;
    p.base = count(g, "base", 0);
    p.half = optPos(g, "half_extent", p.half);
    p.origin = optVec3d(g, "origin", p.origin);
    checkTotal(g, "base", static_cast<int64_t>(p.base) * (p.base + 1) / 2, out.size());
    generatePyramid2d(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "pyramid_3d") {
    checkKeys(g, keys({"base", "half_extent", "layer_gap", "origin"}));
    Pyramid3dParams p;
    p.base = count(g, "base", 0);
    p.half = optPos(g, "half_extent", p.half);
    p.layerGap = optNonNeg(g, "layer_gap", 0.5 * p.half);
    p.origin = optVec3d(g, "origin", p.origin);
    const int64_t b = p.base;
    checkTotal(g, "base", b * (b + 1) * (2 * b + 1) / 6, out.size());
    generatePyramid3d(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "many_pyramids") {
    checkKeys(g, keys({"rows", "cols", "base", "half_extent", "origin"}));
    ManyPyramidsParams p;
    p.rows = count(g, "rows", p.rows);
    p.cols = count(g, "cols", p.cols);
    p.base = count(g, "base", p.base);
    p.half = optPos(g, "half_extent", p.half);
    p.origin = optVec3d(g, "origin", p.origin);
    checkTotal(g, "base", static_cast<int64_t>(p.rows) * p.cols * p.base * (p.base + 1) / 2, out.size());
    generateManyPyramids(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "wall") {
    checkKeys(g, keys({"rows", "cols", "brick_half_extents", "gap", "bond", "position", "yaw_deg"}));
    WallParams p;
    p.rows = count(g, "rows", 0);
    p.cols = count(g, "cols", 0);
    p.brickHalfExtents = optPositiveVec3d(g, "brick_half_extents", p.brickHalfExtents);
    p.gap = optNonNeg(g, "gap", p.gap);
    if (g.member("bond").present()) {
      const std::string bond = readString(g.member("bond"));
      if (bond != "running" && bond != "stack")
        fail(g.member("bond"), "unknown bond '" + bond + "'" + didYouMean(bond, {"running", "stack"}) + "; use running or stack");
      p.runningBond = bond == "running";
    }
    p.position = optVec3d(g, "position", p.position);
    p.yawDeg = optFloat(g, "yaw_deg", 0.0f);
    checkTotal(g, "rows", static_cast<int64_t>(p.rows) * (p.cols + 1), out.size());
    generateWall(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "grid") {
    checkKeys(g, keys({"counts", "spacing", "origin", "shape", "orientation"}));
    GridParams p;
    const JsonNode counts = requireMember(g, "counts", "[nx, ny, nz]");
    if (!counts.json().is_array() || counts.size() != 3) fail(counts, "must be [nx, ny, nz] (got " + describeValue(counts.json()) + ")");
    p.nx = readInt(counts.element(0), 1, static_cast<int>(kMaxSceneBodies));
    p.ny = readInt(counts.element(1), 1, static_cast<int>(kMaxSceneBodies));
    p.nz = readInt(counts.element(2), 1, static_cast<int>(kMaxSceneBodies));
    checkTotal(g, "counts", static_cast<int64_t>(p.nx) * p.ny * p.nz, out.size());
    BodyPrototype proto = prototype(g, ctx, MotionType::Dynamic);
    proto.shape = parseShape(requireMember(g, "shape"), proto.motion, ctx);
    if (g.member("orientation").present()) proto.orientation = parseOrientation(g.member("orientation"));
    const JsonNode spacing = requireMember(g, "spacing", "metres between neighbours, a number or [sx, sy, sz]");
    p.spacing = readPositiveVec3(spacing).cast<double>();
    p.origin = optVec3d(g, "origin", p.origin);
    const Vec3 extent = shapeExtent(proto.shape, proto.orientation);
    const int n[3] = {p.nx, p.ny, p.nz};
    for (int a = 0; a < 3; ++a)
      if (n[a] > 1 && p.spacing[a] < extent[a] - 1e-6f)
        fail(spacing, std::string("bodies would overlap: spacing along ") + "xyz"[a] + " is " + formatNumber(p.spacing[a]) +
                          " but the shape is " + formatNumber(extent[a]) + " wide");
    generateGrid(p, proto, where, out);
  } else if (type == "random_pile") {
    checkKeys(g, keys({"count", "min", "max", "seed", "shapes", "size"}));
    RandomPileParams p;
    p.count = count(g, "count", 0);
    p.lo = readVec3(requireMember(g, "min", "lower corner of the region [x, y, z]")).cast<double>();
    const JsonNode maxNode = requireMember(g, "max", "upper corner of the region [x, y, z]");
    p.hi = readVec3(maxNode).cast<double>();
    for (int a = 0; a < 3; ++a)
      if (!(p.hi[a] > p.lo[a])) fail(maxNode.element(static_cast<size_t>(a)), "must be greater than min (" + formatNumber(p.lo[a]) + ")");
    if (g.member("seed").present()) p.seed = static_cast<uint64_t>(readInt(g.member("seed"), 0, std::numeric_limits<int>::max()));
    const JsonNode shapes = g.member("shapes");
    if (shapes.present()) {
      requireArray(shapes);
      if (shapes.size() == 0) fail(shapes, "must name at least one shape (sphere, box, capsule, hull)");
      p.kinds.clear();
      for (size_t i = 0; i < shapes.size(); ++i) {
        const std::string s = readString(shapes.element(i));
        if (s == "sphere") p.kinds.push_back(ShapeType::Sphere);
        else if (s == "box") p.kinds.push_back(ShapeType::Box);
        else if (s == "capsule") p.kinds.push_back(ShapeType::Capsule);
        else if (s == "hull") p.kinds.push_back(ShapeType::ConvexHull);
        else fail(shapes.element(i), "unknown pile shape '" + s + "'" + didYouMean(s, {"sphere", "box", "capsule", "hull"}) + "; use sphere, box, capsule or hull");
      }
    }
    const JsonNode size = g.member("size");
    if (size.present()) {
      if (!size.json().is_array() || size.size() != 2) fail(size, "must be [min, max] bounding radii in metres (got " + describeValue(size.json()) + ")");
      p.minSize = readPositive(size.element(0));
      p.maxSize = readPositive(size.element(1));
      if (p.maxSize < p.minSize) fail(size.element(1), "must be >= the minimum size " + formatNumber(p.minSize));
    }
    const int capacity = randomPileCapacity(p);
    if (p.count > capacity)
      fail(g.member("count"), "the region holds at most " + std::to_string(capacity) + " bodies of size up to " +
                                  formatNumber(p.maxSize) + " (got " + std::to_string(p.count) + "); enlarge min/max or shrink size");
    checkTotal(g, "count", p.count, out.size());
    generateRandomPile(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else if (type == "domino_run") {
    checkKeys(g, keys({"count", "spacing", "half_extents", "line", "arc", "first_tilt_deg"}));
    DominoParams p;
    p.count = count(g, "count", 0);
    p.halfExtents = optPositiveVec3d(g, "half_extents", p.halfExtents);
    p.spacing = optPos(g, "spacing", p.spacing);
    if (p.spacing <= 2.0 * p.halfExtents.x())
      fail(g.member("spacing").present() ? g.member("spacing") : g,
           "dominoes would overlap: spacing " + formatNumber(p.spacing) + " is not more than their thickness " + formatNumber(2.0 * p.halfExtents.x()));
    const JsonNode line = g.member("line"), arc = g.member("arc");
    if (line.present() && arc.present()) failAtKey(g, "arc", "give either line or arc, not both");
    if (line.present()) {
      checkKeys(line, {"start", "direction"});
      p.start = optVec3d(line, "start", p.start);
      p.direction = optVec3d(line, "direction", p.direction);
      if (!(Vec3d(p.direction.x(), 0.0, p.direction.z()).norm() > 1e-9))
        fail(line.member("direction"), "must have a horizontal (x or z) component");
    }
    if (arc.present()) {
      checkKeys(arc, {"center", "radius", "start_deg", "reverse"});
      p.arc = true;
      p.center = optVec3d(arc, "center", p.center);
      p.radius = optPos(arc, "radius", p.radius);
      p.startDeg = optFloat(arc, "start_deg", 0.0f);
      if (arc.member("reverse").present()) p.reverse = readBool(arc.member("reverse"));
      if (p.spacing * (p.count - 1) > 2.0 * 3.14159265358979323846 * p.radius)
        fail(g.member("count"), "the run is longer than the circle (" + formatNumber(p.spacing * (p.count - 1)) +
                                    " m > circumference " + formatNumber(2.0 * 3.14159265358979323846 * p.radius) + " m)");
    }
    p.firstTiltDeg = optFloat(g, "first_tilt_deg", 0.0f);
    if (std::fabs(p.firstTiltDeg) >= 90.0) fail(g.member("first_tilt_deg"), "must be in (-90, 90) degrees");
    checkTotal(g, "count", p.count, out.size());
    generateDominoes(p, prototype(g, ctx, MotionType::Dynamic), where, out);
  } else {
    fail(typeNode, "unknown generator type '" + type + "'" + didYouMean(type, kGeneratorTypes) +
                       "; use ground, stack, stacks, pyramid_2d, pyramid_3d, many_pyramids, wall, grid, random_pile or domino_run");
  }
  ctx.bodyPointers.resize(out.size(), g.pointer);
}

}  // namespace haif
