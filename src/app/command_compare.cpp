// haif compare SCENE --left SPEC --right SPEC: one scene under two solver set-ups, side by side in one video.
#include "app/cli.h"
#include "app/commands.h"
#include "tools/interrupts.h"

#ifdef HAIF_HAVE_RENDER
#include "app/comparison_clip.h"
#include "app/frame_builder.h"
#include "tools/atomic_file.h"
#include "tools/progress.h"
#include "tools/video.h"
#endif

#include <tbb/info.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <numeric>

namespace haif {

namespace {

int fail(const std::string& message, int status) {
  waitIfInterrupted();
  const bool prefixed = message.rfind("haif compare: ", 0) == 0;
  std::fprintf(stderr, "%s%s\n", prefixed ? "" : "haif compare: ", message.c_str());
  return status;
}

}  // namespace

int commandCompare(int argc, char** argv) {
#ifndef HAIF_HAVE_RENDER
  (void)argc, (void)argv;
  return fail("this build has no renderer (configure with -DHAIF_BUILD_RENDER=ON)", 2);
#else
  CommandLine cl(
      "compare",
      {"--left", "--right", "--frames", "--frame-every", "--out", "--width", "--height", "--threads", "--view", "--gl"},
      {"--no-overlay"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, 2);
  if (cl.positional().size() != 1) return fail("expected exactly one SCENE file (see 'haif help')", 2);
  if (!cl.has("--left") || !cl.has("--right"))
    return fail("--left and --right are required, e.g. --left fixed:10 --right adaptive:4", 2);
  const std::string scenePath = cl.positional()[0];
  ComparisonOptions opt;
  opt.threads = int(tbb::info::default_concurrency());
  if (!cl.getInt("--frames", 1, 1000000, opt.frames, error) ||
      !cl.getInt("--frame-every", 1, 100000, opt.frameEvery, error) ||
      !cl.getInt("--width", 128, 8192, opt.width, error) || !cl.getInt("--height", 200, 8192, opt.height, error) ||
      !cl.getInt("--threads", 1, 1024, opt.threads, error))
    return fail(error, 2);
  if (!applyGlOption(cl.get("--gl", "auto"), error)) return fail(error, 2);
  if (!parseViewMode(cl.get("--view", "normal"), opt.view))
    return fail("--view: expected normal, island, sleep or heat, got '" + cl.get("--view") + "'", 2);
  opt.overlay = !cl.has("--no-overlay");
  const std::string out =
      cl.get("--out", "output/" + std::filesystem::path(scenePath).stem().string() + "_compare.mp4");
  if (std::filesystem::path(out).extension() != ".mp4")
    return fail("--out: expected a .mp4 file, got '" + out + "'", 2);
  if (!checkOutputFile(out, error)) return fail("--out: " + error, 2);

  ComparisonClip clip;
  if (!clip.open(scenePath, cl.get("--left"), cl.get("--right"), opt, error)) return fail(error, 1);

  // Real time: one video frame per frameEvery steps of dt seconds.
  const double fps = 1.0 / (clip.left().stepSeconds() * opt.frameEvery);
  std::string notice;
  std::unique_ptr<FrameSink> sink = openVideoOrFrames(out, opt.width, opt.height, fps, notice, error);
  if (!sink) return fail(error, 1);
  if (!notice.empty()) std::fprintf(stderr, "haif compare: %s\n", notice.c_str());

  clip.holdWhileStepping(sink.get());
  Progress progress("compare", "frame", clip.frameCount());
  std::vector<uint8_t> rgba;
  for (int f = 0; f < clip.frameCount(); ++f) {
    if (!clip.next(rgba, error) || !sink->write(rgba.data(), error)) return fail(error, 1);
    progress.advance(f + 1);
  }
  progress.finish();
  if (const auto* frames = dynamic_cast<const PngFrameSink*>(sink.get())) {
    // PNG frames instead of a video: say where the timing-dependent regions are, for haif diff.
    FrameMasks masks;
    masks.width = opt.width;
    masks.height = opt.height;
    masks.regions = clip.timingRegions();
    if (!writeFileAtomic(frames->stagingDir() + "/" + kFrameMasksFile, frameMasksJson(masks), error))
      return fail(error, 1);
  }
  if (!sink->finish(error)) return fail(error, 1);

  for (const SimulatedScene* side : {&clip.left(), &clip.right()}) {
    std::vector<float> ms = side->history().totalMs;
    std::sort(ms.begin(), ms.end());
    const std::vector<float>& it = side->history().iterations;
    const double meanIt = it.empty() ? 0.0 : std::accumulate(it.begin(), it.end(), 0.0) / double(it.size());
    std::printf("%-12s median %.3f ms/step, mean %.1f iterations (%s)\n", side->spec().c_str(),
                ms.empty() ? 0.0 : double(ms[ms.size() / 2]), meanIt, side->description().c_str());
  }
  std::printf("wrote %s (%d frames, %dx%d)\n", sink->where().c_str(), clip.frameCount(), opt.width, opt.height);
  return 0;
#endif
}

}  // namespace haif
