// Shared chart colours so the overlay and the run charts read the same.
#pragma once

#include "render/canvas.h"

namespace haif::render::chart_colors {

inline constexpr Rgba kIterations{31, 119, 180, 255};   // blue
inline constexpr Rgba kIMin{44, 160, 44, 255};          // green, dashed
inline constexpr Rgba kIMax{214, 39, 40, 255};          // red, dashed
inline constexpr Rgba kCollision{120, 170, 220, 255};   // light blue area
inline constexpr Rgba kSolve{250, 170, 90, 255};        // orange area
inline constexpr Rgba kTotal{40, 40, 50, 255};          // dark line
inline constexpr Rgba kBudget{214, 39, 40, 255};        // red
inline constexpr Rgba kError{148, 103, 189, 255};       // purple

}  // namespace haif::render::chart_colors
