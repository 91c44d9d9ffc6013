// The frames of `haif suite` render jobs: the renderer and FrameBuilder that `haif run` draws with,
// behind the runner's SuiteFramePainter interface (tools/suite_runner.h). No overlay panel: it shows
// timings, which differ from run to run, and the frames are compared with stored references.
#pragma once

#include "tools/suite_runner.h"

#include <memory>

namespace haif {

/// A painter drawing with this build's renderer; null in builds without one.
std::unique_ptr<SuiteFramePainter> makeSuiteFramePainter();

}  // namespace haif
