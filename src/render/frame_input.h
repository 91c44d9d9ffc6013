// Plain data describing one frame. The app fills these from the simulation; nothing here knows
// about physics types. Units are metres and radians unless a field says otherwise; y is up.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace haif::render {

/// What an Instance is drawn as.
enum class ShapeKind : uint8_t {
  Sphere,        ///< radius
  Box,           ///< halfExtents
  Capsule,       ///< radius + halfHeight, axis along local y
  ConvexHull,    ///< registered mesh meshId, vertices in body-local coordinates, flat shaded
  TriangleMesh,  ///< registered mesh meshId, vertices in body-local coordinates, flat shaded
  Plane,         ///< infinite-looking ground plane through position with normal = local +y
};

/// How bodies are coloured.
enum class ViewMode : uint8_t {
  Normal,  ///< a stable pleasant colour per bodyId
  Island,  ///< a stable colour per islandId (sleeping and static bodies greyed)
  Sleep,   ///< awake = warm, sleeping = blue-grey, static = grey
  Heat,    ///< Instance::heat in [0,1] through a perceptual colour map (dark blue -> yellow)
};

/// Screen corner of the overlay panel.
enum class Corner : uint8_t { TopLeft, TopRight, BottomLeft, BottomRight };

/// Where the picture is taken from.
struct Camera {
  bool automatic = true;             ///< true: frame all non-ground instances from a 3/4 view (eye/target/up ignored)
  float eye[3] = {10.f, 8.f, 10.f};  ///< camera position (world) when !automatic
  float target[3] = {0.f, 0.f, 0.f}; ///< point looked at (world) when !automatic
  float up[3] = {0.f, 1.f, 0.f};     ///< up direction when !automatic (need not be exact)
  float fovYDegrees = 45.f;          ///< vertical field of view in degrees
};

/// One rigid body (or static shape) to draw.
struct Instance {
  ShapeKind kind = ShapeKind::Box;          ///< which shape fields below are used
  float position[3] = {0.f, 0.f, 0.f};      ///< world position of the body origin
  float orientation[4] = {0.f, 0.f, 0.f, 1.f};  ///< unit quaternion x, y, z, w (body -> world)
  float halfExtents[3] = {0.5f, 0.5f, 0.5f};    ///< Box half extents (a Plane is always drawn 2 km wide)
  float radius = 0.5f;                      ///< Sphere and Capsule radius
  float halfHeight = 0.5f;                  ///< Capsule half length of the segment between the cap centres (local y)
  uint32_t meshId = 0;                      ///< ConvexHull/TriangleMesh: id given to Renderer::registerMesh
  uint32_t bodyId = 0;                      ///< stable id: picks the Normal-mode colour
  uint32_t islandId = 0;                    ///< island the body belongs to this step (Island mode)
  bool sleeping = false;                    ///< body is asleep (Sleep and Island modes)
  bool isStatic = false;                    ///< static body: drawn grey; a large static Box gets the ground look
  float heat = 0.f;                         ///< scalar in [0,1] for Heat mode (clamped), e.g. penetration / max
  bool useColor = false;                    ///< Normal mode: use `color` instead of the per-bodyId palette colour
  float color[3] = {0.8f, 0.8f, 0.8f};      ///< sRGB colour in [0,1] used when useColor
};

/// A contact point with its normal, drawn as a dot and a short arrow when contacts are shown.
struct ContactMarker {
  float point[3] = {0.f, 0.f, 0.f};   ///< world contact point
  float normal[3] = {0.f, 1.f, 0.f};  ///< world contact normal (any length; normalised when drawn)
};

/// Heads-up panel: text lines and two charts over the most recent steps. Drawn only if enabled.
struct Overlay {
  bool enabled = false;                ///< draw the panel (FreeType is not touched while false)
  Corner corner = Corner::TopLeft;     ///< where the panel sits
  std::string scene;                   ///< scene name
  std::string mode;                    ///< controller mode, e.g. "adaptive"
  int bodies = 0;                      ///< number of bodies
  int islands = 0;                     ///< number of islands this step
  int64_t step = 0;                    ///< step index
  float msPerStep = 0.f;               ///< time of the current step (ms)
  std::vector<std::string> extraLines; ///< more text lines printed under the standard ones
  int window = 240;                    ///< how many of the latest history entries are charted
  std::vector<float> iterations;       ///< iterations chosen per step, oldest first (only the last `window` are used)
  float iMin = 0.f;                    ///< controller lower bound, drawn dashed
  float iMax = 0.f;                    ///< controller upper bound, drawn dashed
  std::vector<float> collisionMs;      ///< collision time per step (ms), aligned with iterations
  std::vector<float> solveMs;          ///< solve time per step (ms), stacked on collision
  float budgetMs = 0.f;                ///< step time budget (ms), drawn as a line; <= 0 hides it
};

/// Everything needed to draw one frame.
struct FrameInput {
  Camera camera;                        ///< view
  ViewMode mode = ViewMode::Normal;     ///< colouring
  std::vector<Instance> instances;      ///< bodies and static shapes (reuse the vector across frames)
  bool showContacts = false;            ///< draw `contacts`
  std::vector<ContactMarker> contacts;  ///< contact points + normals overlay
  float contactScale = 0.f;             ///< marker size in metres; <= 0 picks one from the scene size
  Overlay overlay;                      ///< heads-up panel
};

}  // namespace haif::render
