#include "scene/asset_import.h"

#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace haif {

bool importMeshAsset(const std::string& path, const Vec3& scale, std::vector<Vec3>& vertices,
                     std::vector<uint32_t>& indices, std::string& error) {
  vertices.clear();
  indices.clear();
  // The C API keeps assimp's C++ types (and its exceptions) out of our headers.
  const aiScene* scene = aiImportFile(path.c_str(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                        aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene) {
    error = std::string("cannot read mesh asset '") + path + "' (" + aiGetErrorString() + ")";
    return false;
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;  // points and lines carry no surface
    const uint32_t base = static_cast<uint32_t>(vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      vertices.push_back(Vec3(p.x, p.y, p.z).cwiseProduct(scale));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) indices.push_back(base + face.mIndices[k]);
    }
  }
  aiReleaseImport(scene);
  if (indices.empty()) {
    error = "mesh asset '" + path + "' contains no triangles";
    return false;
  }
  return true;
}

}  // namespace haif
