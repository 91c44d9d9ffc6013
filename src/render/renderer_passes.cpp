// The GL passes of a frame: the shadow map seen from the sun, the scene into the MSAA framebuffer,
// and the sky behind it.
#include "render/renderer_impl.h"

#include <algorithm>
#include <cmath>

#include "render/palette.h"

namespace haif::render {
namespace {

constexpr int kSkyRows = 24;  // must match kRows in shaders/sky.vert
// The sky's gradient (linear); the scene's fog fades into its horizon.
const LinearColor kHorizon{srgbToLinear(0.80f), srgbToLinear(0.85f), srgbToLinear(0.90f)};
const LinearColor kZenith{srgbToLinear(0.38f), srgbToLinear(0.56f), srgbToLinear(0.80f)};

}  // namespace

// The shadow map from the sun, of the first `casterGroups` groups that cast and the boxes' sunward
// faces; cleared once while nothing casts. Sets the depth state the scene pass keeps.
Renderer::Impl::ShadowView Renderer::Impl::drawShadowMap(const SceneBounds& bounds, size_t casterGroups) {
  ShadowView shadow;
  bool shadows = boxStream.shadowFaces() > 0;
  for (size_t i = 0; i < casterGroups; ++i) shadows |= groups[i].castsShadow;
  shadow.drawn = shadows && opt.shadowMapSize > 0;
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthMask(GL_TRUE);
  gl.DepthFunc(GL_LESS);
  gl.CullFace(GL_BACK);
  if (shadow.drawn) {
    shadow.lightViewProj = lightMatrix(bounds, &shadow.texelWorld);
    gl.BindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
    gl.Viewport(0, 0, opt.shadowMapSize, opt.shadowMapSize);
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_POLYGON_OFFSET_FILL);
    gl.PolygonOffset(1.5f, 3.f);
    // Boxes: only the three faces turned to the sun (the ones culling would keep); their
    // winding is not checked, so no face culling.
    boxShadowProgram.use();
    gl.UniformMatrix4fv(boxShadowProgram.uniform("uLightViewProj"), 1, GL_FALSE, shadow.lightViewProj.m);
    gl.Disable(GL_CULL_FACE);
    drawQuads(boxShadowVao, 0, boxStream.shadowFaces());
    shadowProgram.use();
    gl.UniformMatrix4fv(shadowProgram.uniform("uLightViewProj"), 1, GL_FALSE, shadow.lightViewProj.m);
    for (size_t i = 0; i < casterGroups; ++i)
      if (groups[i].castsShadow) drawGroup(groups[i]);
    gl.Disable(GL_POLYGON_OFFSET_FILL);
    shadowMapEmpty = false;
  } else if (!shadowMapEmpty) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, shadowFbo);
    clearShadowMap();
  }
  return shadow;
}

// The main pass into the MSAA framebuffer: the box face streams, then the groups.
void Renderer::Impl::drawScene(const ViewSetup& view, const SceneBounds& bounds, const ShadowView& shadow) {
  const Vec3 focus = bounds.valid ? bounds.center() : Vec3{0.f, 0.f, 0.f};
  const float sceneR = bounds.valid ? std::max(bounds.radius(), 1.f) : 5.f;
  const float eyeDist = length(view.eye - focus);
  gl.BindFramebuffer(GL_FRAMEBUFFER, msaaFbo);
  gl.Viewport(0, 0, opt.width, opt.height);
  // No colour clear: the sky pass fills every pixel that geometry left empty, and an MSAA clear is
  // expensive on llvmpipe.
  gl.Clear(GL_DEPTH_BUFFER_BIT);
  for (const ShaderProgram& sp : sceneProgram) {
    sp.use();
    gl.UniformMatrix4fv(sp.uniform("uViewProj"), 1, GL_FALSE, view.viewProj.m);
    gl.UniformMatrix4fv(sp.uniform("uLightViewProj"), 1, GL_FALSE, shadow.lightViewProj.m);
    gl.Uniform1f(sp.uniform("uShadowNormalOffset"), 1.5f * shadow.texelWorld);
    gl.Uniform1i(sp.uniform("uShadowMap"), 0);
    gl.Uniform3f(sp.uniform("uSunDir"), kSunDir.x, kSunDir.y, kSunDir.z);
    gl.Uniform3f(sp.uniform("uSunColor"), 1.25f, 1.18f, 1.05f);
    gl.Uniform3f(sp.uniform("uSkyAmbient"), 0.30f, 0.36f, 0.46f);
    gl.Uniform3f(sp.uniform("uGroundAmbient"), 0.16f, 0.14f, 0.12f);
    gl.Uniform3f(sp.uniform("uEye"), view.eye.x, view.eye.y, view.eye.z);
    gl.Uniform3f(sp.uniform("uFogColor"), kHorizon.r, kHorizon.g, kHorizon.b);
    gl.Uniform1f(sp.uniform("uFogDistance"), (eyeDist + 2.f * sceneR) * 2.5f);
    gl.Uniform3f(sp.uniform("uGroundColor"), srgbToLinear(0.70f), srgbToLinear(0.70f), srgbToLinear(0.68f));
    gl.Uniform1f(sp.uniform("uGridSpacing"), 1.f);
    gl.Uniform1f(sp.uniform("uGridFade"), eyeDist + 3.f * sceneR);
  }
  gl.ActiveTexture(GL_TEXTURE0);
  gl.BindTexture(GL_TEXTURE_2D, shadowTex);
  // The ground gets the shadow lookup only inside the rectangle where shadows can fall.
  PixelRect shade{0, 0, opt.width, opt.height};
  if (shadow.drawn) {
    PixelRect u{opt.width, opt.height, 0, 0};
    for (const GroundFace& face : groundFaces) {
      const PixelRect r =
          groundShadowRect(view, opt.width, opt.height, bounds, kSunDir, face, 6.f * shadow.texelWorld);
      u = {std::min(u.x0, r.x0), std::min(u.y0, r.y0), std::max(u.x1, r.x1), std::max(u.y1, r.y1)};
    }
    shade = u;
  } else {
    shade = PixelRect{};
  }
  gl.Enable(GL_CULL_FACE);
  sceneProgram[kSurfaceBox].use();
  drawQuads(boxVao, 0, boxStream.sunwardFaces());
  sceneProgram[kSurfaceBoxAway].use();
  drawQuads(boxVao, boxStream.sunwardFaces(), boxStream.awayFaces());
  int bound = kSurfaceBoxAway;
  for (const DrawGroup& g : groups) {
    if (g.surface == kSurfaceGround) {
      drawGroundGroup(g, shade);
      bound = -1;
      continue;
    }
    if (g.surface != bound) sceneProgram[g.surface].use(), bound = g.surface;
    drawGroup(g);
  }
}

// The sky where nothing was drawn (depth test against the far plane, no depth writes).
void Renderer::Impl::drawSky(const ViewSetup& view) {
  gl.Disable(GL_CULL_FACE);
  gl.DepthFunc(GL_LEQUAL);
  gl.DepthMask(GL_FALSE);
  skyProgram.use();
  gl.Uniform3f(skyProgram.uniform("uForward"), view.forward.x, view.forward.y, view.forward.z);
  gl.Uniform3f(skyProgram.uniform("uRight"), view.right.x, view.right.y, view.right.z);
  gl.Uniform3f(skyProgram.uniform("uUp"), view.up.x, view.up.y, view.up.z);
  gl.Uniform2f(skyProgram.uniform("uTanHalfFov"), view.tanHalfFovY * view.aspect, view.tanHalfFovY);
  gl.Uniform3f(skyProgram.uniform("uHorizon"), kHorizon.r, kHorizon.g, kHorizon.b);
  gl.Uniform3f(skyProgram.uniform("uZenith"), kZenith.r, kZenith.g, kZenith.b);
  const float skyBottom = skyStartNdc(view, opt.height, groundFaces);
  gl.Uniform1f(skyProgram.uniform("uBottom"), skyBottom);
  gl.BindVertexArray(emptyVao);
  if (skyBottom < 1.f) gl.DrawArrays(GL_TRIANGLE_STRIP, 0, 2 * (kSkyRows + 1));
  gl.DepthMask(GL_TRUE);
  gl.DepthFunc(GL_LESS);
  gl.BindVertexArray(0);
}

// One non-instanced draw of quads [first, first + faces) of vao.
void Renderer::Impl::drawQuads(GLuint vao, size_t first, size_t faces) {
  if (!faces) return;
  gl.BindVertexArray(vao);
  gl.DrawElements(GL_TRIANGLES, static_cast<GLsizei>(6 * faces), GL_UNSIGNED_INT,
                  reinterpret_cast<void*>(6 * first * sizeof(uint32_t)));
}

void Renderer::Impl::drawGroup(const DrawGroup& g) {
  gl.BindVertexArray(g.mesh->vao);
  gl.BindBuffer(GL_ARRAY_BUFFER, instanceVbo);
  const size_t base = g.first * kInstanceStride;
  auto at = [&](size_t floats) { return reinterpret_cast<void*>(base + floats * sizeof(float)); };
  gl.VertexAttribPointer(3, 3, GL_FLOAT, GL_FALSE, kInstanceStride, at(0));
  gl.VertexAttribPointer(4, 4, GL_FLOAT, GL_FALSE, kInstanceStride, at(3));
  gl.VertexAttribPointer(5, 3, GL_FLOAT, GL_FALSE, kInstanceStride, at(7));
  gl.VertexAttribPointer(6, 1, GL_FLOAT, GL_FALSE, kInstanceStride, at(10));
  gl.VertexAttribPointer(7, 4, GL_FLOAT, GL_FALSE, kInstanceStride, at(11));
  gl.VertexAttribPointer(8, 1, GL_FLOAT, GL_FALSE, kInstanceStride, at(15));
  if (g.cull)
    gl.Enable(GL_CULL_FACE);
  else
    gl.Disable(GL_CULL_FACE);
  gl.DrawElementsInstanced(GL_TRIANGLES, g.mesh->indexCount, GL_UNSIGNED_INT, nullptr,
                           static_cast<GLsizei>(g.count));
}

// A ground group: the shadowed variant inside `shade`, the unshadowed one in up to four bands
// around it (scissored, so each pixel is drawn by exactly one of them).
void Renderer::Impl::drawGroundGroup(const DrawGroup& g, const PixelRect& shade) {
  const int w = opt.width, h = opt.height;
  if (shade.empty()) {
    sceneProgram[kSurfaceGroundUnshadowed].use();
    drawGroup(g);
    return;
  }
  gl.Enable(GL_SCISSOR_TEST);
  sceneProgram[kSurfaceGround].use();
  gl.Scissor(shade.x0, shade.y0, shade.x1 - shade.x0, shade.y1 - shade.y0);
  drawGroup(g);
  sceneProgram[kSurfaceGroundUnshadowed].use();
  const PixelRect bands[4] = {{0, 0, w, shade.y0},
                              {0, shade.y1, w, h},
                              {0, shade.y0, shade.x0, shade.y1},
                              {shade.x1, shade.y0, w, shade.y1}};
  for (const PixelRect& b : bands) {
    if (b.empty()) continue;
    gl.Scissor(b.x0, b.y0, b.x1 - b.x0, b.y1 - b.y0);
    drawGroup(g);
  }
  gl.Disable(GL_SCISSOR_TEST);
}

// Orthographic sun view fitted to the casters' box as seen from the sun (tighter than their
// bounding sphere, so a smaller map gives the same texel size). Extents are quantised and the
// centre snapped to whole texels so shadows do not shimmer when the framing moves a little.
Mat4 Renderer::Impl::lightMatrix(const SceneBounds& casters, float* texelWorld) const {
  const Vec3 f = kSunDir * -1.f;
  const Vec3 s = normalize(cross(f, {0.f, 1.f, 0.f}));
  const Vec3 u = cross(s, f);
  float lo[2] = {1e30f, 1e30f}, hi[2] = {-1e30f, -1e30f};
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p{(corner & 1) ? casters.max.x : casters.min.x, (corner & 2) ? casters.max.y : casters.min.y,
                 (corner & 4) ? casters.max.z : casters.min.z};
    const float ps[2] = {dot(p, s), dot(p, u)};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], ps[k]), hi[k] = std::max(hi[k], ps[k]);
  }
  const auto quantise = [](float half) {  // texel size changes in steps of 2^(1/4)
    return std::pow(2.f, std::ceil(std::log2(std::max(half, 0.5f)) * 4.f) / 4.f);
  };
  const float hw = quantise(0.5f * (hi[0] - lo[0])), hh = quantise(0.5f * (hi[1] - lo[1]));
  const float texelS = 2.f * hw / static_cast<float>(opt.shadowMapSize);
  const float texelU = 2.f * hh / static_cast<float>(opt.shadowMapSize);
  const float sx = std::round(0.5f * (lo[0] + hi[0]) / texelS) * texelS;
  const float sy = std::round(0.5f * (lo[1] + hi[1]) / texelU) * texelU;
  const Vec3 c = casters.center();
  const Vec3 center = s * sx + u * sy + f * dot(c, f);
  // Depth: the casters' sphere in front, and room behind it for the ground they shade.
  const float r = std::max(casters.radius(), 0.5f);
  *texelWorld = std::max(texelS, texelU);
  return ortho(-hw, hw, -hh, hh, r, 9.f * r) * lookAt(center - f * (3.f * r), center, u);
}

}  // namespace haif::render
