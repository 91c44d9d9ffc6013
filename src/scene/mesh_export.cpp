#include "scene/mesh_export.h"

#include <assimp/Exporter.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <memory>

namespace haif {

std::string exportFormatFor(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == "obj") return "objnomtl";
  if (ext == "stl") return "stlb";
  if (ext == "ply") return "ply";
  if (ext == "gltf") return "gltf2";
  if (ext == "glb") return "glb2";
  return "";
}

bool exportMeshAsset(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<uint32_t>& indices,
                     std::string& error) {
  const std::string format = exportFormatFor(path);
  if (format.empty()) {
    error = "cannot write mesh '" + path + "': unknown extension (use .obj, .stl, .ply, .gltf or .glb)";
    return false;
  }
  if (vertices.empty() || indices.empty() || indices.size() % 3 != 0) {
    error = "cannot write mesh '" + path + "': it needs vertices and 3 indices per triangle";
    return false;
  }
  // An aiScene owns what it points to and frees it with delete[] / delete in its destructor.
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("root");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh* mesh = scene->mMeshes[0];
  mesh->mMaterialIndex = 0;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = static_cast<unsigned>(vertices.size());
  mesh->mVertices = new aiVector3D[vertices.size()];
  for (size_t i = 0; i < vertices.size(); ++i)
    mesh->mVertices[i] = aiVector3D(vertices[i].x(), vertices[i].y(), vertices[i].z());
  mesh->mNumFaces = static_cast<unsigned>(indices.size() / 3);
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    aiFace& face = mesh->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (unsigned k = 0; k < 3; ++k) {
      const uint32_t v = indices[3 * f + k];
      if (v >= vertices.size()) {
        error = "cannot write mesh '" + path + "': index " + std::to_string(v) + " is out of range";
        return false;
      }
      face.mIndices[k] = v;
    }
  }
  Assimp::Exporter exporter;
  if (exporter.Export(scene.get(), format, path) != aiReturn_SUCCESS) {
    error = "cannot write mesh '" + path + "' (" + exporter.GetErrorString() + ")";
    return false;
  }
  return true;
}

}  // namespace haif
