// The mesh assets of assets/: what each file is and how it is made, so `haif assets` can (re)write them
// and tests can check that the committed files are what the code makes.
#pragma once

#include "scene/procedural_mesh.h"

#include <string>
#include <vector>

namespace haif {

struct GeneratedAsset {
  std::string file;     ///< name in assets/, e.g. "rock_a.ply"
  std::string purpose;  ///< one line for assets/README.md
  TriangleSoup mesh;
};

/// Every generated asset, in a fixed order.
std::vector<GeneratedAsset> generatedAssets();

/// Writes every generated asset into `dir` (created if needed): all files are written to a temporary
/// folder inside `dir` first and moved into place only when every one succeeded. Returns false with one
/// error line otherwise.
bool writeGeneratedAssets(const std::string& dir, std::string& error);

}  // namespace haif
