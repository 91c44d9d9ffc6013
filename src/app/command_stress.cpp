// haif stress: run the stress scenes (scenes/stress/*.json), judge each by the checks in its "stress"
// block, print one line per scene and write DIR/stress.json. Exit 0 all pass, 1 some fail, 2 bad input.
#include "app/cli.h"
#include "app/commands.h"
#include "scene/scene_loader.h"
#include "tools/atomic_file.h"
#include "tools/interrupts.h"
#include "tools/staged_output.h"
#include "tools/stress_suite.h"

#include <tbb/info.h>

#include <cstdio>
#include <filesystem>

namespace haif {

namespace {

int fail(const std::string& message, int status) {
  waitIfInterrupted();
  std::fprintf(stderr, "%s\n", message.c_str());
  return status;
}

// scenes/stress here, else in the source tree (so the command works from any folder).
std::string defaultStressDir() {
  if (std::filesystem::is_directory("scenes/stress")) return "scenes/stress";
  return std::string(HAIF_SOURCE_DIR) + "/scenes/stress";
}

}  // namespace

int commandStress(int argc, char** argv) {
  CommandLine cl("stress", {"--out", "--threads"}, {"--quick"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, 2);
  int threads = int(tbb::info::default_concurrency());
  if (!cl.getInt("--threads", 1, 1024, threads, error)) return fail(error, 2);
  const bool quick = cl.has("--quick");

  // Positionals: scene files or folders of them; none: the shipped suite.
  std::vector<std::string> paths;
  std::vector<std::string> sources = cl.positional();
  if (sources.empty()) sources.push_back(defaultStressDir());
  for (const std::string& src : sources) {
    if (std::filesystem::is_directory(src)) {
      std::vector<std::string> found;
      if (!findStressScenes(src, found, error)) return fail("haif stress: " + error, 2);
      paths.insert(paths.end(), found.begin(), found.end());
    } else {
      paths.push_back(src);
    }
  }
  // Every file is checked before anything runs: a typo in the last scene must not cost the whole run.
  for (const std::string& p : paths) {
    SceneDesc scene;
    if (!loadSceneFile(p, scene, error)) return fail(error, 2);
    if (!scene.stress.given)
      return fail(p + ": no \"stress\" block: a stress scene needs {\"steps\": N, \"checks\": [...]} (docs/stress.md)",
                  2);
  }
  // Checked now, written at the end: the folder appears whole (tools/staged_output.h).
  const std::string outDir = cl.get("--out", "output/stress");
  if (!checkOutputFolder(outDir, {"stress.json"}, error)) return fail("haif stress: " + error, 2);

  std::vector<StressSceneResult> results;
  bool allPass = true;
  for (const std::string& p : paths) {
    StressSceneResult r;
    if (!runStressScene(p, quick, threads, r, error)) return fail(error, 2);
    std::printf("%s\n", stressLine(r).c_str());
    std::fflush(stdout);
    allPass = allPass && (r.skipped || r.pass);
    results.push_back(std::move(r));
  }
  StagedFolder output;
  if (!output.open(outDir, {"stress.json"}, error) ||
      !writeFileAtomic(output.path() + "/stress.json", stressJson(results, quick), error) || !output.commit(error))
    return fail("haif stress: " + error, 2);
  int failed = 0, skipped = 0;
  for (const StressSceneResult& r : results) {
    if (r.skipped) ++skipped;
    else if (!r.pass) ++failed;
  }
  std::printf("%d of %zu scenes failed, %d skipped; wrote %s/stress.json\n", failed, results.size(), skipped,
              outDir.c_str());
  return allPass ? 0 : 1;
}

}  // namespace haif
