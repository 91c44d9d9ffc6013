// frames/masks.json: the parts of every frame that change from run to run even when the physics is
// identical (the overlay panel and charts print step timings). Written next to the frames by the
// commands that render them; `haif diff` masks these regions by default.
//
//   {"width": 1280, "height": 720, "regions": [{"name": "overlay", "x0": 12, "y0": 12, "x1": 442, "y1": 402}]}
//
// Rectangles are in pixels, [x0,x1) x [y0,y1), top row first.
#pragma once

#include "tools/image_diff.h"

#include <string>
#include <vector>

namespace haif {

/// A named timing-dependent region of the frames.
struct FrameRegion {
  std::string name;  ///< "overlay", "chart strip", ...
  PixelRect rect;
};

/// The masks file of a frame folder.
struct FrameMasks {
  int width = 0, height = 0;          ///< frame size the rectangles refer to
  std::vector<FrameRegion> regions;
};

/// File name inside a frame folder.
inline constexpr const char* kFrameMasksFile = "masks.json";

/// JSON text of `masks`.
std::string frameMasksJson(const FrameMasks& masks);

/// Reads `path`; false with one error line naming the file and the problem.
bool readFrameMasks(const std::string& path, FrameMasks& out, std::string& error);

}  // namespace haif
