#include "scene/asset_import.h"

#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

namespace haif {

bool importMeshAsset(const std::string& path, const Vec3& scale, std::vector<Vec3>& vertices,
                     std::vector<uint32_t>& indices, std::string& error) {
  vertices.clear();
  indices.clear();
  // The C API keeps assimp's C++ types (and its exceptions) out of our headers. Only positions matter
  // here: normals, texture coordinates and colours are dropped first, so that vertices which differ only
  // in those (every corner of an STL file carries its face normal) are joined into one.
  aiPropertyStore* props = aiCreatePropertyStore();
  const int dropped = aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                      aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS | aiComponent_TEXTURES |
                      aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS;
  aiSetImportPropertyInteger(props, AI_CONFIG_PP_RVC_FLAGS, dropped);
  const aiScene* scene = aiImportFileExWithProperties(
      path.c_str(), aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                        aiProcess_PreTransformVertices | aiProcess_SortByPType,
      nullptr, props);
  aiReleasePropertyStore(props);
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
