// Which engine and solver set-up a run uses, as written on the command line ("fixed:10",
// "haif:adaptive:4", "bullet:10"), and the factory that starts such a run on a scene.
#pragma once

#include "tools/engine_run.h"
#include "tools/simulation.h"

#include <memory>
#include <string>

namespace haif {

struct EngineSpec {
  std::string engine = "haif";  ///< haif | bullet
  SolverSpec solver;            ///< bullet: mode "fixed" only
};

/// Parses "haif", "haif:fixed:10", "fixed:10", "adaptive:4", "model:4", "bullet", "bullet:10",
/// "bullet:fixed:10". Bullet has no adaptive iteration control: only fixed counts.
bool parseEngineSpec(const std::string& text, EngineSpec& out, std::string& error);

/// Whether this build has the Bullet baseline (libbullet-dev found by CMake).
bool bulletAvailable();

/// Loads `scenePath` into the engine of `spec` (`threads` is HAIF's; Bullet runs on one thread).
/// One error line on failure, e.g. when Bullet was asked for but not built.
std::unique_ptr<EngineRun> makeEngineRun(const EngineSpec& spec, const std::string& scenePath, int threads,
                                         std::string& error);

}  // namespace haif
