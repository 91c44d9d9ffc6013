#include "scene/asset_catalog.h"

#include "scene/mesh_export.h"

#include <filesystem>
#include <system_error>

namespace haif {

std::vector<GeneratedAsset> generatedAssets() {
  return {
      {"terrain.obj",
       "terrain, 40 m square: a hillside down towards +x and a valley floor (static triangle-mesh collider)",
       makeTerrain(40.0f, 40)},
      {"rock_a.ply", "rock, radius about 1 (convex-hull collider; also its own render mesh)",
       makeRock(1, Vec3(1.3f, 0.8f, 1.0f))},
      {"rock_b.stl", "rock (binary STL)", makeRock(2, Vec3(1.0f, 0.9f, 1.2f))},
      {"rock_c.glb", "rock (binary glTF)", makeRock(3, Vec3(1.1f, 1.0f, 0.8f))},
      {"rock_d.gltf", "rock (glTF with rock_d.bin)", makeRock(4, Vec3(1.4f, 0.7f, 0.9f))},
      {"pillar.glb", "fluted column, 2.4 m tall, centred (render mesh on a box collider)", makePillar(2.4f, 0.33f, 12)},
  };
}

bool writeGeneratedAssets(const std::string& dir, std::string& error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    error = dir + ": cannot create folder (" + ec.message() + ")";
    return false;
  }
  const fs::path tmp = fs::path(dir) / ".assets.tmp";
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) {
    error = tmp.string() + ": cannot create folder (" + ec.message() + ")";
    return false;
  }
  const std::vector<GeneratedAsset> assets = generatedAssets();
  for (const GeneratedAsset& a : assets)
    if (!exportMeshAsset((tmp / a.file).string(), a.mesh.vertices, a.mesh.indices, error)) {
      fs::remove_all(tmp, ec);
      return false;
    }
  // Everything was written: move each file (a .gltf comes with its .bin) into place.
  for (const fs::directory_entry& e : fs::directory_iterator(tmp)) {
    fs::rename(e.path(), fs::path(dir) / e.path().filename(), ec);
    if (ec) {
      error = (fs::path(dir) / e.path().filename()).string() + ": cannot write (" + ec.message() + ")";
      return false;
    }
  }
  fs::remove_all(tmp, ec);
  return true;
}

}  // namespace haif
