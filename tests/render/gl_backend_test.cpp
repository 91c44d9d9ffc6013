// The two GL back ends: OSMesa and EGL (surfaceless) draw the same frame alike, each names itself
// in errors, and --gl values parse.
#include <gtest/gtest.h>

#include <cstdlib>

#include "render/gl_context.h"
#include "render/renderer.h"
#include "render_test_util.h"

namespace haif::render {
namespace {

using test::coloredBody;
using test::groundBox;

bool drawWith(GlBackend backend, std::vector<uint8_t>& px, std::string& error) {
  RendererOptions o;
  o.width = 200;
  o.height = 150;
  o.gl = backend;
  auto r = Renderer::create(o, &error);
  if (!r) return false;
  FrameInput f;  // automatic camera
  f.instances.push_back(groundBox());
  f.instances.push_back(coloredBody(ShapeKind::Box, 0.f, 1.5f, 0.f, 0.9f, 0.1f, 0.1f));
  f.instances.push_back(coloredBody(ShapeKind::Sphere, 1.5f, 0.5f, 0.5f, 0.1f, 0.7f, 0.2f));
  f.instances.push_back(coloredBody(ShapeKind::Capsule, -1.5f, 0.8f, -0.5f, 0.2f, 0.3f, 0.9f));
  return r->render(f, px, &error);
}

TEST(GlBackends, OsMesaAndEglDrawTheSameFrame) {
  if (!glBackendBuilt(GlBackend::OsMesa) || !glBackendBuilt(GlBackend::Egl))
    GTEST_SKIP() << "this build has only one GL back end";
  std::vector<uint8_t> osmesa, egl;
  std::string error;
  ASSERT_TRUE(drawWith(GlBackend::OsMesa, osmesa, error)) << error;
  ASSERT_TRUE(drawWith(GlBackend::Egl, egl, error)) << error;
  ASSERT_EQ(osmesa.size(), egl.size());
  // Both are llvmpipe here; the frames may differ only where rounding differs: no pixel by more
  // than a few levels, and hardly any at all (haif diff's default threshold is 16 levels).
  size_t differing = 0;
  int worst = 0;
  for (size_t i = 0; i < osmesa.size(); ++i) {
    const int d = std::abs(int(osmesa[i]) - int(egl[i]));
    worst = std::max(worst, d);
    differing += d > 0 ? 1 : 0;
  }
  EXPECT_LE(worst, 8);
  EXPECT_LE(differing, osmesa.size() / 1000);
  // And the frame is not empty: the red box is there.
  size_t red = 0;
  for (size_t i = 0; i + 3 < egl.size(); i += 4) red += egl[i] > 150 && egl[i + 1] < 80 && egl[i + 2] < 80;
  EXPECT_GT(red, 100u);
}

TEST(GlBackends, AutoGivesAContextAndValuesParse) {
  std::string error;
  auto ctx = createGlContext(GlBackend::Auto, &error);
  ASSERT_NE(ctx, nullptr) << error;
  EXPECT_TRUE(std::string(ctx->backendName()) == "OSMesa" || std::string(ctx->backendName()) == "EGL");
  GlBackend b = GlBackend::Auto;
  EXPECT_TRUE(parseGlBackend("egl", b));
  EXPECT_EQ(b, GlBackend::Egl);
  EXPECT_TRUE(parseGlBackend("osmesa", b));
  EXPECT_EQ(b, GlBackend::OsMesa);
  EXPECT_TRUE(parseGlBackend("auto", b));
  EXPECT_EQ(b, GlBackend::Auto);
  EXPECT_FALSE(parseGlBackend("vulkan", b));
  EXPECT_FALSE(parseGlBackend("EGL", b));
}

}  // namespace
}  // namespace haif::render
