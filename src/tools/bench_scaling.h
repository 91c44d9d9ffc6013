// haif bench --scaling: how the cost of a step grows with the world. Stacks of ten boxes and poured
// mixed piles are generated at each size (10^3 to 10^5 bodies by default), stepped a few dozen times,
// and their median ms/step and the memory the world holds are fitted to a power law in the body
// count: cost ~ bodies^k. A k above 1 is the price of a world outgrowing the caches.
#pragma once

#include <string>
#include <vector>

namespace haif {

/// One world of the sweep: a family ("stacks", "pile") at a size.
struct ScalingResult {
  std::string family;
  int bodies = 0;  ///< dynamic bodies asked for (the generator places exactly these)
  int steps = 0;
  int threads = 0;
  double msMedian = 0.0, msP95 = 0.0;
  double worldMb = 0.0;  ///< heap memory the world holds after its last step (NaN: the allocator does not say)
  bool nan = false;
};

/// The scene text of a family at a size: "stacks" (stacks of 10 unit boxes on a grid) or "pile"
/// (spheres, boxes, capsules and hulls in ten layers over a square, falling onto the ground).
/// Empty for an unknown family.
std::string scalingSceneJson(const std::string& family, int bodies, int steps);

/// Builds and steps the world; false with `error` if the scene does not build.
bool runScalingPoint(const std::string& family, int bodies, int steps, int threads, ScalingResult& out,
                     std::string& error);

/// Least-squares slope of log(y) against log(x): the exponent k of y ~ x^k (NaN with fewer than two
/// positive points).
double powerLawExponent(const std::vector<double>& x, const std::vector<double>& y);

/// scaling.csv: one row per world.
std::string scalingCsv(const std::vector<ScalingResult>& rows);
/// The report: the table and, per family, the fitted exponents of time and memory.
std::string scalingMarkdown(const std::vector<ScalingResult>& rows, const std::string& plot);
/// DIR/scaling.png: ms/step and memory against bodies on log axes, one curve per family (nothing is
/// written by a build without the renderer; `written` then stays empty).
bool writeScalingPlot(const std::string& dir, const std::vector<ScalingResult>& rows, std::string& written,
                      std::string& error);

}  // namespace haif
