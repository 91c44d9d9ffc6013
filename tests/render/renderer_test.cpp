// Tolerance-based image checks of the GL renderer: colours land where the geometry is, the image
// is right side up, errors are clear, and the overlay only touches its panel.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <fstream>

#include "render/overlay.h"
#include "render/png_io.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

using test::at;
using test::coloredBody;
using test::groundBox;

std::unique_ptr<Renderer> makeRenderer(int w, int h) {
  RendererOptions o;
  o.width = w;
  o.height = h;
  o.shadowMapSize = 1024;
  std::string error;
  auto r = Renderer::create(o, &error);
  EXPECT_NE(r, nullptr) << error;
  return r;
}

// A camera looking horizontally at the origin region from +z.
Camera frontCamera() {
  Camera c;
  c.automatic = false;
  c.eye[0] = 0.f, c.eye[1] = 1.5f, c.eye[2] = 8.f;
  c.target[0] = 0.f, c.target[1] = 1.5f, c.target[2] = 0.f;
  c.fovYDegrees = 45.f;
  return c;
}

TEST(Renderer, RedBoxAboveGroundAppearsWhereExpected) {
  auto r = makeRenderer(160, 120);
  ASSERT_TRUE(r);
  FrameInput f;
  f.camera = frontCamera();
  f.instances.push_back(groundBox());
  f.instances.push_back(coloredBody(ShapeKind::Box, 0.f, 1.5f, 0.f, 0.9f, 0.1f, 0.1f));
  std::vector<uint8_t> px;
  std::string error;
  ASSERT_TRUE(r->render(f, px, &error)) << error;
  ASSERT_EQ(px.size(), 160u * 120u * 4u);
  // The box is centred on the view axis: the image centre is red.
  int red = 0;
  for (int y = 52; y < 68; ++y)
    for (int x = 72; x < 88; ++x) red += test::isRed(at(px, 160, x, y));
  EXPECT_GT(red, 200) << "box colour missing at the image centre";
  // Top rows are sky (bright, blue dominant), bottom rows are the grey ground.
  for (int x : {5, 80, 150}) {
    const auto sky = at(px, 160, x, 2);
    EXPECT_GT(sky.b, sky.r) << "sky at x=" << x;
    EXPECT_GT(sky.b, 150);
    const auto ground = at(px, 160, x, 117);
    EXPECT_FALSE(test::isRed(ground));
    EXPECT_LT(std::abs(ground.r - ground.b), 40) << "ground should be grey at x=" << x;
    EXPECT_GT(ground.r, 60);
  }
  // No red away from the box.
  EXPECT_FALSE(test::isRed(at(px, 160, 10, 60)));
  EXPECT_FALSE(test::isRed(at(px, 160, 150, 60)));
}

TEST(Renderer, HighObjectLandsInUpperRowsOfPng) {
  auto r = makeRenderer(160, 120);
  ASSERT_TRUE(r);
  FrameInput f;
  f.camera = frontCamera();
  f.instances.push_back(groundBox());
  Instance s = coloredBody(ShapeKind::Sphere, 0.f, 3.2f, 0.f, 0.1f, 0.8f, 0.1f);
  s.radius = 0.6f;
  f.instances.push_back(s);
  const std::string path = test::tempDir() + "/yflip.png";
  std::string error;
  ASSERT_TRUE(r->renderToPng(f, path, &error)) << error;
  int w = 0, h = 0;
  std::vector<uint8_t> px;
  ASSERT_TRUE(readPng(path, &w, &h, &px, &error)) << error;
  ASSERT_EQ(w, 160);
  ASSERT_EQ(h, 120);
  long sumRow = 0, count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (test::isGreen(at(px, w, x, y))) sumRow += y, ++count;
  ASSERT_GT(count, 50);
  EXPECT_LT(sumRow / count, h / 3) << "the high sphere must be near the top of the PNG";
  // The ground (below the horizon) fills the bottom rows.
  EXPECT_LT(std::abs(at(px, w, 80, h - 2).r - at(px, w, 80, h - 2).b), 40);
}

TEST(Renderer, AutomaticCameraFramesEveryBodyAndIgnoresGround) {
  auto r = makeRenderer(200, 150);
  ASSERT_TRUE(r);
  FrameInput f;  // camera.automatic defaults to true
  f.instances.push_back(groundBox());
  f.instances.push_back(coloredBody(ShapeKind::Box, -20.f, 0.5f, 0.f, 0.9f, 0.1f, 0.1f));
  f.instances.push_back(coloredBody(ShapeKind::Box, 20.f, 0.5f, 0.f, 0.1f, 0.8f, 0.1f));
  std::vector<uint8_t> px;
  std::string error;
  ASSERT_TRUE(r->render(f, px, &error)) << error;
  int red = 0, green = 0;
  for (int y = 0; y < 150; ++y)
    for (int x = 0; x < 200; ++x) red += test::isRed(at(px, 200, x, y)), green += test::isGreen(at(px, 200, x, y));
  EXPECT_GT(red, 4) << "left box out of view";
  EXPECT_GT(green, 4) << "right box out of view";
}

TEST(Renderer, ViewModesRecolourBodies) {
  auto r = makeRenderer(160, 120);
  ASSERT_TRUE(r);
  FrameInput f;
  f.camera = frontCamera();
  Instance b = coloredBody(ShapeKind::Box, 0.f, 1.5f, 0.f, 0.9f, 0.1f, 0.1f);
  b.sleeping = true;
  b.heat = 1.f;
  f.instances.push_back(b);
  std::vector<uint8_t> normal, sleep, heat;
  std::string error;
  ASSERT_TRUE(r->render(f, normal, &error)) << error;
  f.mode = ViewMode::Sleep;
  ASSERT_TRUE(r->render(f, sleep, &error)) << error;
  f.mode = ViewMode::Heat;
  ASSERT_TRUE(r->render(f, heat, &error)) << error;
  const auto n = at(normal, 160, 80, 60), s = at(sleep, 160, 80, 60), h = at(heat, 160, 80, 60);
  EXPECT_TRUE(test::isRed(n));
  EXPECT_GT(s.b, s.r) << "sleeping bodies are blue-grey";
  EXPECT_GT(h.g, h.b) << "heat 1 is yellow";
  EXPECT_GT(h.r, h.b);
}

TEST(Renderer, ContactMarkersAreDrawn) {
  auto r = makeRenderer(160, 120);
  ASSERT_TRUE(r);
  FrameInput f;
  f.camera = frontCamera();
  f.instances.push_back(groundBox());
  ContactMarker m;
  m.point[1] = 1.5f;
  f.contacts.push_back(m);
  f.contactScale = 0.2f;
  std::vector<uint8_t> without, with;
  std::string error;
  ASSERT_TRUE(r->render(f, without, &error)) << error;
  f.showContacts = true;
  ASSERT_TRUE(r->render(f, with, &error)) << error;
  EXPECT_FALSE(test::isRed(at(without, 160, 80, 60)));
  EXPECT_TRUE(test::isRed(at(with, 160, 80, 60))) << "contact dot at the image centre";
}

TEST(Renderer, OverlayTogglesOnlyThePanelRegion) {
  const int w = 320, h = 240;
  auto r = makeRenderer(w, h);
  ASSERT_TRUE(r);
  FrameInput f;
  f.instances.push_back(groundBox());
  for (int i = 0; i < 10; ++i) {
    Instance b;
    b.bodyId = static_cast<uint32_t>(i);
    b.position[0] = static_cast<float>(i % 5) * 1.5f;
    b.position[1] = 0.5f + static_cast<float>(i / 5);
    f.instances.push_back(b);
  }
  f.overlay.corner = Corner::BottomRight;
  f.overlay.scene = "test";
  f.overlay.iMin = 4, f.overlay.iMax = 20, f.overlay.budgetMs = 8.f;
  for (int i = 0; i < 300; ++i) {
    f.overlay.iterations.push_back(10.f + static_cast<float>(i % 5));
    f.overlay.collisionMs.push_back(1.f);
    f.overlay.solveMs.push_back(3.f);
  }
  std::vector<uint8_t> off, on;
  std::string error;
  ASSERT_TRUE(r->render(f, off, &error)) << error;
  f.overlay.enabled = true;
  ASSERT_TRUE(r->render(f, on, &error)) << error;
  const PanelRect panel = overlayPanelRect(f.overlay, w, h);
  ASSERT_GT(panel.x1 - panel.x0, 50);
  EXPECT_GT(panel.x0, w / 4) << "bottom-right panel starts right of the left quarter";
  int inside = 0, outside = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = 4 * (static_cast<size_t>(y) * w + x);
      const bool differs = std::memcmp(&off[i], &on[i], 4) != 0;
      const bool inPanel = x >= panel.x0 && x < panel.x1 && y >= panel.y0 && y < panel.y1;
      (inPanel ? inside : outside) += differs;
    }
  EXPECT_EQ(outside, 0) << "overlay changed pixels outside its panel";
  EXPECT_GT(inside, (panel.x1 - panel.x0) * (panel.y1 - panel.y0) / 2) << "panel should be visible";
}

TEST(Renderer, MissingShaderDirectoryGivesClearError) {
  RendererOptions o;
  o.width = 64, o.height = 64;
  o.shaderDir = "/nonexistent/haif_shaders";
  std::string error;
  auto r = Renderer::create(o, &error);
  EXPECT_EQ(r, nullptr);
  EXPECT_NE(error.find("/nonexistent/haif_shaders/scene.vert"), std::string::npos) << error;
}

TEST(Renderer, BrokenShaderReportsFileAndGlslLog) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(test::tempDir()) / "broken_shaders";
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(fs::path(HAIF_SHADER_DIR)))
    fs::copy_file(e.path(), dir / e.path().filename(), fs::copy_options::overwrite_existing);
  std::ofstream(dir / "scene.frag") << "#version 330 core\nvoid main() { this is not glsl; }\n";
  RendererOptions o;
  o.width = 64, o.height = 64;
  o.shaderDir = dir.string();
  std::string error;
  auto r = Renderer::create(o, &error);
  EXPECT_EQ(r, nullptr);
  EXPECT_NE(error.find("scene.frag"), std::string::npos) << error;
  EXPECT_NE(error.find("compile"), std::string::npos) << error;
  EXPECT_GT(error.size(), (dir / "scene.frag").string().size() + 30) << "GLSL log missing: " << error;
}

TEST(Renderer, UnregisteredMeshIsAnErrorAndRegisteredMeshDraws) {
  auto r = makeRenderer(160, 120);
  ASSERT_TRUE(r);
  FrameInput f;
  f.camera = frontCamera();
  Instance hull = coloredBody(ShapeKind::ConvexHull, 0.f, 1.5f, 0.f, 0.9f, 0.1f, 0.1f);
  hull.meshId = 42;
  f.instances.push_back(hull);
  std::vector<uint8_t> px;
  std::string error;
  EXPECT_FALSE(r->render(f, px, &error));
  EXPECT_NE(error.find("42"), std::string::npos) << error;
  // A tetrahedron around the origin, counter-clockwise from outside.
  const std::vector<float> pos = {-1, -1, -1, 1, -1, -1, 0, -1, 1, 0, 1, 0};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 3, 1, 1, 3, 2, 2, 3, 0};
  ASSERT_TRUE(r->registerMesh(42, pos, idx, &error)) << error;
  EXPECT_TRUE(r->hasMesh(42));
  ASSERT_TRUE(r->render(f, px, &error)) << error;
  EXPECT_TRUE(test::isRed(at(px, 160, 80, 62)));
  EXPECT_FALSE(r->registerMesh(43, pos, {0, 1, 99}, &error)) << "out-of-range indices leave nothing";
}

// Counts pixels whose largest channel difference exceeds 8 (out of 255).
int differingPixels(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  int n = 0;
  for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4) {
    int d = 0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a[i + c]) - int(b[i + c])));
    n += d > 8;
  }
  return n;
}

// Unit boxes added to a frame, ids from 1 (the ground is instance 0); returns the instance index.
struct BoxScene {
  FrameInput frame;
  uint32_t nextId = 1;
  BoxScene() { frame.instances.push_back(groundBox()); }
  size_t add(float x, float y, float z) {
    Instance b;
    b.bodyId = nextId++;
    b.position[0] = x, b.position[1] = y, b.position[2] = z;
    frame.instances.push_back(b);
    return frame.instances.size() - 1;
  }
};

// Renders `f` from `eye` towards `target` with two renderers whose options differ only in `off`'s
// switched-off feature; calls check(on, off) with both images.
template <class Check>
void compareFromEye(const RendererOptions& on, const RendererOptions& off, FrameInput& f, const float eye[3],
                    const float target[3], Check&& check) {
  std::string error;
  auto a = Renderer::create(on, &error);
  auto b = Renderer::create(off, &error);
  ASSERT_TRUE(a && b) << error;
  f.camera.automatic = false;
  for (int k = 0; k < 3; ++k) f.camera.eye[k] = eye[k], f.camera.target[k] = target[k];
  std::vector<uint8_t> ia, ib;
  ASSERT_TRUE(a->render(f, ia, &error)) << error;
  ASSERT_TRUE(b->render(f, ib, &error)) << error;
  check(ia, ib);
}

TEST(Renderer, DroppingHiddenBoxFacesKeepsThePicture) {
  // Boxes side by side, stacked, on the ground, one tilted and one lifted by a visible gap, seen
  // from several sides: dropping the faces HiddenBoxFaces finds must change at most the odd
  // anti-aliased sample on a seam. A wrong face bit in the shaders would remove whole faces.
  BoxScene scene;
  for (int x = 0; x < 3; ++x)
    for (int z = 0; z < 2; ++z) scene.add(static_cast<float>(x), 0.5f, static_cast<float>(z));
  scene.add(0.f, 1.5f, 0.f), scene.add(1.f, 1.5f, 0.f), scene.add(0.f, 2.5f, 0.f);
  scene.add(2.f, 1.6f, 1.f);  // a 10 cm gap one can see through
  Instance& tilted = scene.frame.instances[scene.add(4.f, 0.75f, 0.f)];
  tilted.orientation[2] = std::sin(0.2f), tilted.orientation[3] = std::cos(0.2f);
  RendererOptions on, off;
  on.width = off.width = 320, on.height = off.height = 240;
  off.cullHiddenBoxFaces = false;
  const float eyes[4][3] = {{-4.f, 4.f, 7.f}, {8.f, 3.f, -5.f}, {1.f, 9.f, 0.5f}, {6.f, 1.2f, 6.f}};
  const float target[3] = {1.5f, 1.f, 0.5f};
  for (const auto& eye : eyes)
    compareFromEye(on, off, scene.frame, eye, target, [&](const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
      EXPECT_LE(differingPixels(a, b), 6) << "eye " << eye[0] << "," << eye[1] << "," << eye[2];
    });
}

TEST(Renderer, CullingOccludedBoxesKeepsThePicture) {
  // Rows of touching stacks (hidden faces dropped too), a tilted box, a box floating in a gap and
  // one resting askew on a stack, seen from several sides: boxes and faces behind others are left
  // out of the main pass (BoxOcclusion), which must not change a single pixel; the shadow pass
  // still draws them, so the shadows they cast stay too.
  BoxScene scene;
  for (int sx = 0; sx < 4; ++sx)
    for (int sz = 0; sz < 3; ++sz)
      for (int h = 0; h < 2 + (sx + sz) % 4; ++h) scene.add(1.6f * sx, 0.5f + h, 1.6f * sz);
  scene.add(0.8f, 2.2f, 1.6f);  // floating between two stacks
  Instance& tilted = scene.frame.instances[scene.add(2.4f, 0.8f, -1.6f)];
  tilted.orientation[0] = std::sin(0.3f), tilted.orientation[3] = std::cos(0.3f);
  Instance& askew = scene.frame.instances[scene.add(3.2f, 3.6f, 1.6f)];
  askew.orientation[1] = std::sin(0.4f), askew.orientation[3] = std::cos(0.4f);
  RendererOptions on, off;
  on.width = off.width = 320, on.height = off.height = 240;
  off.cullOccludedBoxes = false;
  const float eyes[5][3] = {{-6.f, 4.f, 12.f}, {14.f, 3.f, -6.f}, {2.4f, 14.f, 1.f}, {-8.f, 1.f, 1.6f}, {12.f, 6.f, 12.f}};
  const float target[3] = {2.4f, 1.f, 1.6f};
  for (const auto& eye : eyes)
    compareFromEye(on, off, scene.frame, eye, target, [&](const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
      ASSERT_EQ(a.size(), b.size());
      size_t differentBytes = 0;
      for (size_t i = 0; i < a.size(); ++i) differentBytes += a[i] != b[i];
      EXPECT_EQ(differentBytes, 0u) << "eye " << eye[0] << "," << eye[1] << "," << eye[2];
    });
}

TEST(Renderer, EveryPixelIsRepaintedEachFrame) {
  // The colour buffer is never cleared: the sky strip (which starts at the ground's far edge) and
  // the geometry must together paint every pixel. A frame filled with a red box, then an ordinary
  // frame, must look exactly like that ordinary frame from a fresh renderer.
  auto used = makeRenderer(320, 240);
  auto fresh = makeRenderer(320, 240);
  ASSERT_TRUE(used && fresh);
  FrameInput wall;
  wall.camera = frontCamera();
  Instance red = coloredBody(ShapeKind::Box, 0.f, 1.5f, 0.f, 0.9f, 0.1f, 0.1f);
  red.halfExtents[0] = red.halfExtents[1] = 50.f;
  wall.instances.push_back(red);
  std::vector<uint8_t> a, b;
  std::string error;
  ASSERT_TRUE(used->render(wall, a, &error)) << error;
  for (const float eyeY : {1.5f, 6.f, 40.f}) {
    FrameInput f;
    f.camera = frontCamera();
    f.camera.eye[1] = eyeY;
    f.instances.push_back(groundBox());
    f.instances.push_back(coloredBody(ShapeKind::Box, 0.f, 1.f, 0.f, 0.2f, 0.8f, 0.2f));
    ASSERT_TRUE(used->render(f, a, &error)) << error;
    ASSERT_TRUE(fresh->render(f, b, &error)) << error;
    EXPECT_EQ(differingPixels(a, b), 0) << "eye height " << eyeY;
    ASSERT_TRUE(used->render(wall, a, &error)) << error;
  }
}

// A renderer with a shadow map and one without (shadowMapSize 0), both w x h; error says why one
// could not be made.
struct ShadowPair {
  std::string error;
  std::unique_ptr<Renderer> lit, flat;
  ShadowPair(int w, int h) {
    RendererOptions o;
    o.width = w, o.height = h;
    lit = Renderer::create(o, &error);
    o.shadowMapSize = 0;
    if (lit) flat = Renderer::create(o, &error);
  }
};

TEST(Renderer, ShadowsOnlyDarkenTheGroundWhereTheyFall) {
  // The same scene with and without a shadow map: the ground away from the shadow is drawn by a
  // variant without the shadow lookup, so it must match exactly; the shadow itself is darker.
  const ShadowPair pair(320, 240);
  ASSERT_TRUE(pair.lit && pair.flat) << pair.error;
  std::string error;
  FrameInput f;
  f.camera = frontCamera();
  f.camera.eye[1] = 5.f;
  f.instances.push_back(groundBox());
  f.instances.push_back(coloredBody(ShapeKind::Box, -1.f, 2.f, 0.f, 0.2f, 0.3f, 0.9f));
  std::vector<uint8_t> pa, pb;
  ASSERT_TRUE(pair.lit->render(f, pa, &error)) << error;
  ASSERT_TRUE(pair.flat->render(f, pb, &error)) << error;
  int darker = 0, brighter = 0, same = 0;
  for (size_t i = 0; i < pa.size(); i += 4) {
    const int d = (pa[i] + pa[i + 1] + pa[i + 2]) - (pb[i] + pb[i + 1] + pb[i + 2]);
    darker += d < -30, brighter += d > 3, same += d == 0;
  }
  EXPECT_GT(darker, 150) << "the box casts a visible shadow";
  EXPECT_EQ(brighter, 0) << "shadows never brighten";
  EXPECT_GT(same, 320 * 240 * 8 / 10) << "most of the picture is untouched by the shadow";
}

TEST(Renderer, TiltedBoxCastsTheSameShadowAsTheSameHull) {
  // The shadow pass draws boxes from their three sun-facing faces (mirrored in the shader); a
  // convex hull of the same box takes the general path. The camera sees the shadow on the ground
  // but not the caster, so the two pictures must match, and show a shadow.
  const float hx = 0.8f, hy = 0.4f, hz = 0.6f;
  const float q[4] = {0.3f, 0.5f, 0.2f, 0.787401f};  // unit: 0.09 + 0.25 + 0.04 + 0.62
  std::vector<float> corners;
  for (int c = 0; c < 8; ++c) corners.insert(corners.end(), {c & 1 ? hx : -hx, c & 2 ? hy : -hy, c & 4 ? hz : -hz});
  const std::vector<uint32_t> faces = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                       2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
  const ShadowPair pair(240, 180);
  ASSERT_TRUE(pair.lit && pair.flat) << pair.error;
  std::string error;
  ASSERT_TRUE(pair.lit->registerMesh(7, corners, faces, &error)) << error;
  ASSERT_TRUE(pair.flat->registerMesh(7, corners, faces, &error)) << error;
  std::vector<uint8_t> images[3];
  for (int k = 0; k < 3; ++k) {
    FrameInput f;
    f.camera.automatic = false;
    f.camera.fovYDegrees = 30.f;
    const float eye[3] = {1.4f, 1.2f, 3.9f}, target[3] = {1.4f, 0.f, 0.9f};
    for (int i = 0; i < 3; ++i) f.camera.eye[i] = eye[i], f.camera.target[i] = target[i];
    f.instances.push_back(groundBox());
    Instance caster = coloredBody(k == 0 ? ShapeKind::Box : ShapeKind::ConvexHull, 0.f, 2.5f, 0.f, 0.8f, 0.2f, 0.2f);
    caster.halfExtents[0] = hx, caster.halfExtents[1] = hy, caster.halfExtents[2] = hz;
    caster.meshId = 7;
    for (int i = 0; i < 4; ++i) caster.orientation[i] = q[i];
    f.instances.push_back(caster);
    ASSERT_TRUE((k == 2 ? pair.flat : pair.lit)->render(f, images[k], &error)) << error;
  }
  int shadowed = 0;
  for (size_t i = 0; i < images[0].size(); i += 4)
    shadowed += images[0][i] + 30 < images[2][i] && images[0][i + 1] + 30 < images[2][i + 1];
  EXPECT_GT(shadowed, 300) << "the shadow is in view";
  EXPECT_LE(differingPixels(images[0], images[1]), 12) << "box and hull cast the same shadow";
}

// The renderer's performance target (2000 boxes, 1280x720, shadows, 4x MSAA; timed by
// tests/bench/render_bench.cpp, not here) renders, and the overlay charts draw in a band of the
// frame: they change pixels, and leave most of the scene as it was.
TEST(RendererFrame, Stacks2000WithAndWithoutTheOverlay) {
  RendererOptions o;  // defaults: 1280x720, 4x MSAA, 1024 shadow map
  std::string error;
  auto r = Renderer::create(o, &error);
  ASSERT_TRUE(r) << error;
  FrameInput f = test::stacks2000Frame();
  std::vector<uint8_t> plain, charted;
  f.overlay.enabled = false;
  ASSERT_TRUE(r->render(f, plain, &error)) << error;
  f.overlay.enabled = true;
  ASSERT_TRUE(r->render(f, charted, &error)) << error;
  ASSERT_EQ(plain.size(), size_t(1280) * 720 * 4);
  const int changed = differingPixels(plain, charted), total = 1280 * 720;
  std::printf("overlay changed %d of %d pixels\n", changed, total);
  EXPECT_GT(changed, total / 100) << "the charts are drawn";
  EXPECT_LT(changed, total / 3) << "and only in their band";
}

}  // namespace
}  // namespace haif::render
