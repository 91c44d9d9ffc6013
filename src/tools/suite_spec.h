// Suite files of `haif suite` (docs/suites.md): a JSON list of jobs, each a scene file with a solver
// set-up, a length and what to check. Reading one checks everything that can be checked without
// simulating (every key, every scene file, every check against its scene, every reference folder),
// so a mistake in the last job stops the suite before the first job runs.
#pragma once

#include "scene/stress_desc.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

/// One check of a run or render job. Either a stress check (docs/stress.md: max_drop_m with a body,
/// peak_speed, ...) judged by the stress machinery, or a bound on a number of summary.json.
struct SuiteCheck {
  std::string where;      ///< "jobs[2].checks[0]"
  bool stress = false;    ///< a stress check: `stressCheck` holds it
  StressCheck stressCheck;
  std::string key;        ///< summary.json key (stress == false)
  bool hasMin = false, hasMax = false;
  double min = 0.0, max = 0.0;
};

/// How a render job's frames are compared with its reference, as in `haif diff`.
struct SuiteDiffSpec {
  double threshold = 0.1;       ///< colour distance above which a pixel differs
  double maxDiffRatio = 0.001;  ///< differing / compared pixels a frame may have
  double minSsim = 0.98;        ///< mean SSIM a frame must reach
  bool antialiasing = true;     ///< forgive anti-aliased edge pixels
  struct Rect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  std::vector<Rect> masks;      ///< pixel rectangles left out of the comparison
};

enum class SuiteJobKind : uint8_t { Run, Render, Stress };

/// "run", "render", "stress".
const char* suiteJobKindName(SuiteJobKind kind);

struct SuiteJob {
  size_t index = 0;        ///< position in the suite's job list, from 0
  std::string where;       ///< "jobs[2]"
  std::string name;        ///< unique in the suite; also its folder under the report's jobs/
  SuiteJobKind kind = SuiteJobKind::Run;
  std::string sceneGiven;  ///< the scene path as written
  std::string scenePath;   ///< resolved against the suite file's folder
  // Set-up (run and render jobs; stress jobs run their scene's own fixed set-up).
  std::string mode = "fixed";  ///< fixed | adaptive | model
  int iterations = -1;         ///< fixed: count (-1: the scene's); adaptive/model: I_max if > 0
  double budgetMs = 4.0;       ///< adaptive/model
  int threads = 0;             ///< 0: the command's --threads
  int frames = -1;             ///< steps to simulate (-1: the scene's "frames")
  int errorEvery = 0;          ///< measure the solve error every K steps (0: never)
  std::vector<SuiteCheck> checks;
  // Render jobs.
  int width = 320, height = 240, frameEvery = 10;
  std::string referenceGiven, referencePath;  ///< folder of reference PNG frames
  SuiteDiffSpec diff;
  // Stress jobs.
  bool quick = false;      ///< the scene's quick_steps (and SKIP when it is out of the quick set)
};

struct SuiteSpec {
  std::string path;        ///< the suite file
  std::string name;        ///< "name", default the file's stem
  std::string hash;        ///< FNV-1a of the file's bytes (16 hex digits): shards of one suite share it
  std::vector<SuiteJob> jobs;
};

/// What reading a suite may skip.
struct SuiteLoadOptions {
  /// Render jobs may name reference folders that do not exist yet (`--update-references` writes them).
  bool referencesMayBeMissing = false;
};

/// Reads and checks the suite file at `path`. One error line on failure: "FILE:LINE:COL: PLACE: what is
/// wrong", e.g. "suite.json:12:17: jobs[3].frames: must be in [1, 10000000] (got 0)".
bool loadSuiteFile(const std::string& path, const SuiteLoadOptions& options, SuiteSpec& out, std::string& error);

/// Same for suite text in memory; `path` names it in messages and scene paths are relative to its folder.
bool parseSuiteText(const std::string& text, const std::string& path, const SuiteLoadOptions& options, SuiteSpec& out,
                    std::string& error);

}  // namespace haif
