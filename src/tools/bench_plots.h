// The benchmark's Pareto plots: for each scene one PNG with a panel per error metric, error
// against ms/step on log axes, one curve per engine, mode and thread count, the front marked.
#pragma once

#include "tools/bench_sweep.h"

#include <string>
#include <vector>

namespace haif {

/// Whether this build can draw plots (the renderer's chart code is built).
bool benchPlotsAvailable();

/// Writes DIR/pareto_<scene>.png for every scene in `rows`; `written` gets the file names.
bool writeBenchPlots(const std::string& dir, const std::vector<BenchResult>& rows, std::vector<std::string>& written,
                     std::string& error);

}  // namespace haif
