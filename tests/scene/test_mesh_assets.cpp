// Mesh assets through assimp: generated meshes written in every supported format load back with the
// same vertices and triangles; a missing or unreadable asset is one error line naming the field and file.
#include "scene/asset_catalog.h"
#include "scene/asset_import.h"
#include "scene/mesh_export.h"
#include "scene/procedural_mesh.h"
#include "scene_test_util.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

namespace haif::test {
namespace {

namespace fs = std::filesystem;

fs::path scratchDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("haif_mesh_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Vertices sorted (x, then y, then z) so two lists compare regardless of order.
std::vector<Vec3> sorted(std::vector<Vec3> v) {
  std::sort(v.begin(), v.end(), [](const Vec3& a, const Vec3& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
  });
  return v;
}

// Triangles as sorted-corner position triples, sorted: the same surface whatever the vertex numbering.
std::vector<std::array<float, 9>> triangles(const std::vector<Vec3>& v, const std::vector<uint32_t>& idx) {
  std::vector<std::array<float, 9>> out;
  for (size_t f = 0; f < idx.size(); f += 3) {
    // Rotate the corners so the smallest comes first: keeps the winding, drops the start corner.
    int first = 0;
    for (int k = 1; k < 3; ++k) {
      const Vec3 &a = v[idx[f + k]], &b = v[idx[f + first]];
      if (a.x() < b.x() || (a.x() == b.x() && (a.y() < b.y() || (a.y() == b.y() && a.z() < b.z())))) first = k;
    }
    std::array<float, 9> t;
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) t[size_t(3 * k + c)] = v[idx[f + size_t((first + k) % 3)]][c];
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MeshAssets, EveryFormatRoundTripsTheSameMesh) {
  const TriangleSoup rock = makeRock(7, Vec3(1.2f, 0.8f, 1.0f), 1);
  const fs::path dir = scratchDir("roundtrip");
  for (const char* ext : {"obj", "stl", "ply", "gltf", "glb"}) {
    SCOPED_TRACE(ext);
    const std::string path = (dir / (std::string("rock.") + ext)).string();
    std::string error;
    ASSERT_TRUE(exportMeshAsset(path, rock.vertices, rock.indices, error)) << error;
    std::vector<Vec3> v;
    std::vector<uint32_t> idx;
    ASSERT_TRUE(importMeshAsset(path, Vec3::Ones(), v, idx, error)) << error;
    EXPECT_EQ(v.size(), rock.vertices.size()) << "identical vertices are joined again";
    EXPECT_EQ(idx.size(), rock.indices.size());
    const std::vector<Vec3> a = sorted(rock.vertices), b = sorted(v);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - b[i]).norm(), 1e-5f) << "vertex " << i;
    EXPECT_EQ(triangles(rock.vertices, rock.indices), triangles(v, idx)) << "same triangles, same winding";
  }
  fs::remove_all(dir);
}

TEST(MeshAssets, ScaleIsAppliedPerAxis) {
  const TriangleSoup t = makeTerrain(10.0f, 4);
  const fs::path dir = scratchDir("scale");
  const std::string path = (dir / "t.obj").string();
  std::string error;
  ASSERT_TRUE(exportMeshAsset(path, t.vertices, t.indices, error)) << error;
  std::vector<Vec3> v;
  std::vector<uint32_t> idx;
  ASSERT_TRUE(importMeshAsset(path, Vec3(2.0f, 0.5f, 1.0f), v, idx, error)) << error;
  float maxX = -1e9f, maxY = -1e9f;
  for (const Vec3& p : v) maxX = std::max(maxX, p.x()), maxY = std::max(maxY, p.y());
  float srcX = -1e9f, srcY = -1e9f;
  for (const Vec3& p : t.vertices) srcX = std::max(srcX, p.x()), srcY = std::max(srcY, p.y());
  EXPECT_NEAR(maxX, 2.0f * srcX, 1e-4f);
  EXPECT_NEAR(maxY, 0.5f * srcY, 1e-4f);
  fs::remove_all(dir);
}

TEST(MeshAssets, UnknownExtensionIsRefused) {
  std::string error;
  EXPECT_FALSE(exportMeshAsset("/tmp/x.fbx2", {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY()}, {0, 1, 2}, error));
  EXPECT_NE(error.find("unknown extension"), std::string::npos) << error;
}

TEST(MeshAssets, ProceduralMeshesAreClosedAndOutwardFacing) {
  for (const TriangleSoup& m : {makeRock(3, Vec3::Ones()), makePillar(4.0f, 0.4f, 12)}) {
    // Closed: every edge is used once in each direction. Outward: the signed volume is positive.
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    double volume = 0.0;
    for (size_t f = 0; f < m.indices.size(); f += 3) {
      for (int k = 0; k < 3; ++k) ++edges[{m.indices[f + size_t(k)], m.indices[f + size_t((k + 1) % 3)]}];
      const Vec3 &a = m.vertices[m.indices[f]], &b = m.vertices[m.indices[f + 1]], &c = m.vertices[m.indices[f + 2]];
      volume += double(a.dot(b.cross(c))) / 6.0;
    }
    for (const auto& e : edges) EXPECT_EQ(edges.count({e.first.second, e.first.first}), 1u);
    EXPECT_GT(volume, 0.0);
  }
}

}  // namespace
}  // namespace haif::test

namespace haif::test {
namespace {

TEST(MeshAssets, CommittedAssetsAreWhatTheCodeMakes) {
  for (const GeneratedAsset& a : generatedAssets()) {
    SCOPED_TRACE(a.file);
    std::vector<Vec3> v;
    std::vector<uint32_t> idx;
    std::string error;
    ASSERT_TRUE(importMeshAsset(sourceDir() + "/assets/" + a.file, Vec3::Ones(), v, idx, error)) << error;
    ASSERT_EQ(v.size(), a.mesh.vertices.size()) << "regenerate with: haif assets --out assets";
    ASSERT_EQ(idx.size(), a.mesh.indices.size());
    const std::vector<Vec3> x = sorted(a.mesh.vertices), y = sorted(v);
    float worst = 0.0f;
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, (x[i] - y[i]).norm());
    EXPECT_LT(worst, 1e-4f);
  }
}

TEST(MeshAssets, WriteGeneratedAssetsWritesEveryFileAndNothingElse) {
  const fs::path dir = scratchDir("catalog");
  std::string error;
  ASSERT_TRUE(writeGeneratedAssets(dir.string(), error)) << error;
  std::set<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  std::set<std::string> expected;
  for (const GeneratedAsset& a : generatedAssets()) expected.insert(a.file);
  expected.insert("rock_d.bin");  // the .gltf's buffer
  EXPECT_EQ(names, expected) << "no temporary folder may be left behind";
  fs::remove_all(dir);
}

// A scene next to the given asset file, with one body using it as `field`.
std::string assetScene(const std::string& field, const std::string& asset) {
  if (field == "render_mesh")
    return "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"sphere\"},\n     \"render_mesh\": {\"asset\": \"" + asset +
           "\"}}\n  ]\n}\n";
  return "{\n  \"bodies\": [\n    {\"shape\": {\"type\": \"hull\", \"asset\": \"" + asset + "\"}}\n  ]\n}\n";
}

std::string loadError(const fs::path& scenePath, const std::string& text) {
  std::ofstream(scenePath) << text;
  SceneDesc s;
  std::string error;
  EXPECT_FALSE(loadSceneFile(scenePath.string(), s, error));
  return error;
}

TEST(MeshAssets, BadAssetsGiveOneLineNamingTheFieldAndTheFile) {
  const fs::path dir = scratchDir("bad");
  const fs::path scene = dir / "scene.json";
  std::ofstream(dir / "garbage.obj") << "this is not a mesh\n\x01\x02\x03";
  std::ofstream(dir / "lines.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n";
  fs::create_directories(dir / "folder.glb");
  const std::string base = scene.string() + ":4:";

  std::string e = loadError(scene, assetScene("hull", "missing.ply"));
  EXPECT_EQ(e.rfind(scene.string() + ":3:", 0), 0u) << e;
  EXPECT_NE(e.find("bodies[0].shape.asset: cannot open asset file '" + (dir / "missing.ply").string() +
                   "' (No such file or directory)"),
            std::string::npos)
      << e;

  e = loadError(scene, assetScene("hull", "garbage.obj"));
  EXPECT_NE(e.find("bodies[0].shape.asset: "), std::string::npos) << e;
  EXPECT_NE(e.find((dir / "garbage.obj").string()), std::string::npos) << e;

  e = loadError(scene, assetScene("hull", "lines.obj"));
  EXPECT_NE(e.find("bodies[0].shape.asset: "), std::string::npos) << e;
  EXPECT_NE(e.find("contains no triangles"), std::string::npos) << e;

  e = loadError(scene, assetScene("hull", "folder.glb"));
  EXPECT_NE(e.find("is a directory, not a mesh file"), std::string::npos) << e;

  e = loadError(scene, assetScene("render_mesh", "missing.glb"));
  EXPECT_EQ(e.rfind(base, 0), 0u) << e;
  EXPECT_NE(e.find("bodies[0].render_mesh.asset: cannot open asset file '" + (dir / "missing.glb").string()), std::string::npos)
      << e;
  for (const std::string& line : {e}) EXPECT_EQ(line.find('\n'), std::string::npos);
  fs::remove_all(dir);
}

// The same rule as for inline meshes: a collision mesh needs a triangle with area.
TEST(MeshAssets, AnAssetOfOnlyDegenerateTrianglesIsRefused) {
  const fs::path dir = scratchDir("degenerate");
  std::ofstream(dir / "flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  const std::string e = loadError(dir / "scene.json", "{\"bodies\": [{\"type\": \"static\", \"shape\": {\"type\": \"mesh\", "
                                                      "\"asset\": \"flat.obj\"}}]}");
  EXPECT_NE(e.find("bodies[0].shape.asset: all 1 triangles are degenerate (zero area)"), std::string::npos) << e;
  fs::remove_all(dir);
}

TEST(MeshAssets, RenderMeshIsReadRelativeToTheScene) {
  const fs::path dir = scratchDir("render");
  const TriangleSoup pillar = makePillar(2.0f, 0.3f, 8);
  std::string error;
  ASSERT_TRUE(exportMeshAsset((dir / "p.glb").string(), pillar.vertices, pillar.indices, error)) << error;
  std::ofstream(dir / "s.json") << "{\"bodies\": [{\"shape\": {\"type\": \"box\"}, \"render_mesh\": {\"asset\": \"p.glb\", "
                                   "\"scale\": 2}}]}";
  SceneDesc s;
  ASSERT_TRUE(loadSceneFile((dir / "s.json").string(), s, error)) << error;
  EXPECT_EQ(s.bodies[0].renderMesh.asset, "p.glb");
  EXPECT_EQ(s.bodies[0].renderMesh.vertices.size(), pillar.vertices.size());
  float top = -1e9f;
  for (const Vec3& v : s.bodies[0].renderMesh.vertices) top = std::max(top, v.y());
  EXPECT_NEAR(top, 2.0f, 1e-4f) << "scale 2 on a column 2 m tall centred on its origin";
  fs::remove_all(dir);
}

TEST(MeshAssets, ShowcaseSceneLoadsEveryFormat) {
  const SceneDesc s = loadReferenceScene("mesh_showcase.json");
  std::set<std::string> extensions;
  int hulls = 0, meshes = 0, renderMeshes = 0;
  for (const BodyDesc& b : s.bodies) {
    if (!b.shape.asset.empty()) extensions.insert(fs::path(b.shape.asset).extension().string());
    hulls += b.shape.type == ShapeType::ConvexHull && !b.shape.asset.empty();
    meshes += b.shape.type == ShapeType::TriangleMesh && !b.shape.asset.empty();
    renderMeshes += !b.renderMesh.asset.empty();
  }
  EXPECT_EQ(extensions, (std::set<std::string>{".obj", ".ply", ".stl", ".glb", ".gltf"}));
  EXPECT_EQ(meshes, 1);
  EXPECT_GE(hulls, 8);
  EXPECT_GE(renderMeshes, hulls + 1);
}

}  // namespace
}  // namespace haif::test
