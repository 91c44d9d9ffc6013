// Mesh assets (OBJ, STL, PLY, glTF, ... anything assimp reads) for triangle-mesh and hull shapes.
#pragma once

#include "core/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// Reads every mesh in the file, triangulated, with identical vertices joined, scaled per axis and
/// merged into one vertex/index list. Returns false with a one-line reason on failure.
bool importMeshAsset(const std::string& path, const Vec3& scale, std::vector<Vec3>& vertices,
                     std::vector<uint32_t>& indices, std::string& error);

}  // namespace haif
