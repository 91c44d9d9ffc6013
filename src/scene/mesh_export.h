// Writing a triangle mesh to a file through assimp's exporter: the format follows the extension
// (.obj, .stl (binary), .ply, .gltf (with a .bin beside it), .glb). Used by `haif assets` and tests.
#pragma once

#include "core/math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// Writes one mesh (one node, one material). Returns false with a one-line reason on failure.
bool exportMeshAsset(const std::string& path, const std::vector<Vec3>& vertices, const std::vector<uint32_t>& indices,
                     std::string& error);

/// The assimp export format id for a path's extension, or "" when the extension is not supported.
std::string exportFormatFor(const std::string& path);

}  // namespace haif
