// Scene generators: parametric layouts expanded into bodies at load time (the reference scenes of
// docs/reference_scenes.md among them). Pure functions of their parameters: the same input gives bit-identical
// bodies on every machine (positions are computed in double and rounded once; the random pile uses
// its own integer PRNG and no transcendental functions).
#pragma once

#include "scene/scene_desc.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

using Vec3d = Eigen::Vector3d;

/// Deterministic 64-bit PRNG (splitmix64): tiny, fast, and the same sequence everywhere.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next();
  /// Uniform in [0, 1) with 53 random bits.
  double uniform();
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  uint64_t state_;
};

/// Common part of every generated body: motion type, material, mass (0: from density), damping.
/// Generators copy it and set shape, position, orientation and `where` ("<prefix> #k").
using BodyPrototype = BodyDesc;

/// The reference ground (docs/reference_scenes.md): a static box, by default half (500, 1, 500) centred at
/// y = -1 (top face at y = 0).
struct GroundParams {
  Vec3d halfExtents{500.0, 1.0, 500.0};
  Vec3d position{0.0, -1.0, 0.0};
};
void generateGround(const GroundParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// One vertical stack: box h centred at base + (0, hy + h * (2 hy + gap), 0).
struct StackParams {
  int count = 10;
  Vec3d base{0.0, 0.0, 0.0};  ///< point the stack stands on
  Vec3d halfExtents{0.5, 0.5, 0.5};
  double gap = 0.01;
};
void generateStack(const StackParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// Reference stacks_N: N boxes in stacks of `perStack`; stack s at origin + spacing * (s mod k, 0, floor(s / k)),
/// k = ceil(sqrt(ceil(N / perStack))); box h at y = hy + h * (2 hy + gap). The last stack may be partial.
struct StacksParams {
  int count = 100;
  int perStack = 10;
  double spacing = 3.0;
  Vec3d origin{0.0, 0.0, 0.0};
  Vec3d halfExtents{0.5, 0.5, 0.5};
  double gap = 0.01;
};
int stacksGridSide(int count, int perStack);  ///< k of the layout
void generateStacks(const StacksParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// Reference large_pyramid: a 2D pyramid of cubes (edge s = 2 half) in the x-y plane; for i in 0..base-1,
/// j in i..base-1: origin + s * (0.5 (i+1) + (j-i) - 0.5 base, i + 0.5, 0). base (base+1)/2 boxes.
struct Pyramid2dParams {
  int base = 100;
  double half = 0.5;
  Vec3d origin{0.0, 0.0, 0.0};
};
void generatePyramid2d(const Pyramid2dParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// Reference pyramid_15: square layers of cubes (half h); for i in 0..base-1, j,k in floor(i/2) .. base-1-floor((i+1)/2):
/// origin + (-base h + 2h j + (i odd ? h : 0), h + i (2h + layerGap), -base h + 2h k + (i odd ? h : 0)).
/// Layers start layerGap apart (default h/2) and settle. Sum of (base-i)^2 boxes.
struct Pyramid3dParams {
  int base = 15;
  double half = 1.0;
  double layerGap = -1.0;  ///< < 0: h / 2 (the reference layout)
  Vec3d origin{0.0, 0.0, 0.0};
};
void generatePyramid3d(const Pyramid3dParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// Reference many_pyramids: rows x cols 2D pyramids of `base` cubes (edge s); pitch P = (base + 1) s,
/// G_x = cols P / 2, G_z = rows P / 2; row z_r = -G_z + s + r 2 (G_z - s) / (rows - 1) (0 for one row),
/// column centre c_x = -G_x + c P + s; box (i, j >= i) at origin + (c_x + s (0.5 (i+1) + (j-i) - 0.5), s (i + 0.5), z_r).
/// Order: rows, then columns, then i, then j.
struct ManyPyramidsParams {
  int rows = 14;
  int cols = 14;
  int base = 10;
  double half = 0.5;
  Vec3d origin{0.0, 0.0, 0.0};
};
void generateManyPyramids(const ManyPyramidsParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// A brick wall standing on `position` (bottom centre), bricks along the wall's local x, turned by
/// yawDeg about +y. Running bond: odd rows shift half a brick and end in two half bricks, so both
/// ends are flush.
struct WallParams {
  int rows = 10;
  int cols = 10;
  Vec3d brickHalfExtents{0.5, 0.25, 0.25};
  double gap = 0.0;
  bool runningBond = true;
  Vec3d position{0.0, 0.0, 0.0};
  double yawDeg = 0.0;
};
void generateWall(const WallParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// nx * ny * nz copies of the prototype's shape at origin + (ix sx, iy sy, iz sz); x varies fastest, then z, then y.
struct GridParams {
  int nx = 1, ny = 1, nz = 1;
  Vec3d spacing{1.0, 1.0, 1.0};
  Vec3d origin{0.0, 0.0, 0.0};
};
void generateGrid(const GridParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// A seeded pile of mixed shapes in an axis-aligned region: the region is cut into cells of edge
/// 2.2 maxSize, filled from the bottom layer up, each body jittered inside its cell with a random
/// orientation, so nothing overlaps at the start. Sizes are bounding radii in [minSize, maxSize].
struct RandomPileParams {
  int count = 100;
  Vec3d lo{-2.0, 1.0, -2.0}, hi{2.0, 6.0, 2.0};
  uint64_t seed = 1;
  std::vector<ShapeType> kinds{ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule, ShapeType::ConvexHull};
  double minSize = 0.2, maxSize = 0.4;
};
int randomPileCapacity(const RandomPileParams& p);  ///< bodies the region holds
void generateRandomPile(const RandomPileParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

/// Dominoes standing on the ground (y = start.y or center.y) along a line or a circular arc,
/// `spacing` apart (arc length), thin side (half x) along the path. The first one can be tilted
/// forward about its front bottom edge to start the run.
struct DominoParams {
  int count = 20;
  double spacing = 0.8;
  Vec3d halfExtents{0.1, 0.6, 0.3};  ///< thickness, height, width
  bool arc = false;
  Vec3d start{0.0, 0.0, 0.0};      ///< line: first domino's bottom centre
  Vec3d direction{1.0, 0.0, 0.0};  ///< line: direction of the run (projected onto the ground plane)
  Vec3d center{0.0, 0.0, 0.0};     ///< arc: centre (bottom level)
  double radius = 5.0;             ///< arc
  double startDeg = 0.0;           ///< arc: angle of the first domino, from +x towards +z
  bool reverse = false;            ///< arc: false: the angle grows (from +x towards +z); true: it shrinks
  double firstTiltDeg = 0.0;       ///< tilt of the first domino towards the run
};
void generateDominoes(const DominoParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out);

}  // namespace haif
