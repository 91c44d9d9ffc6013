// haif run SCENE: simulate, optionally render frames, write stats.csv and summary.json.
#include "app/cli.h"
#include "app/commands.h"
#include "app/frame_builder.h"
#include "tools/atomic_file.h"
#include "tools/frame_masks.h"
#include "tools/progress.h"
#include "tools/interrupts.h"
#include "tools/run_report.h"
#include "tools/simulation.h"
#include "tools/staged_output.h"
#include "tools/start_overlaps.h"
#include "tools/video.h"

#ifdef HAIF_HAVE_RENDER
#include "render/async_png_writer.h"
#include "render/overlay.h"
#include "render/run_charts.h"
#endif

#include "scene/scene_loader.h"

#include <tbb/info.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>

namespace haif {

namespace {

int fail(const std::string& message, int status = 1) {
  waitIfInterrupted();
  std::fprintf(stderr, "%s\n", message.c_str());
  return status;
}

}  // namespace

int commandRun(int argc, char** argv) {
  CommandLine cl("run",
                 {"--frames", "--out", "--threads", "--mode", "--iterations", "--budget-ms", "--width", "--height",
                  "--replay", "--calibration", "--i-min", "--view", "--overlay-corner", "--frame-every",
                  "--error-every", "--video", "--gl"},
                 {"--no-render", "--contacts", "--no-overlay", "--render-phases"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, 2);
  if (cl.positional().size() != 1) return fail("haif run: expected exactly one SCENE file (see 'haif help')", 2);
  const std::string scenePath = cl.positional()[0];

  int frames = -1, threads = int(tbb::info::default_concurrency()), width = 1280, height = 720, frameEvery = 1;
  int iterations = -1, iMin = 4, errorEvery = 10;
  double budget = 4.0;
  if (!cl.getInt("--frames", 1, 10000000, frames, error) || !cl.getInt("--threads", 1, 1024, threads, error) ||
      !cl.getInt("--width", 16, 8192, width, error) || !cl.getInt("--height", 16, 8192, height, error) ||
      !cl.getInt("--frame-every", 1, 100000, frameEvery, error) ||
      !cl.getInt("--iterations", 1, 100000, iterations, error) || !cl.getInt("--i-min", 1, 1000, iMin, error) ||
      !cl.getInt("--error-every", 0, 1000000, errorEvery, error) ||
      !cl.getDouble("--budget-ms", 0.001, 1e6, budget, error))
    return fail(error, 2);

  SolverSpec spec;
  spec.mode = cl.get("--mode", cl.has("--replay") ? "replay" : "fixed");
  if (spec.mode != "fixed" && spec.mode != "adaptive" && spec.mode != "model" && spec.mode != "replay")
    return fail("haif run: --mode: expected fixed, adaptive, model or replay, got '" + spec.mode + "'", 2);
  if (spec.mode == "replay" && !cl.has("--replay"))
    return fail("haif run: --mode replay needs --replay RUN/stats.csv", 2);
  spec.iterations = iterations;
  spec.budgetMs = budget;
  spec.iMin = iMin;
  spec.replayPath = cl.get("--replay");
  spec.calibrationPath = cl.get("--calibration");

  const bool render = !cl.has("--no-render");
#ifndef HAIF_HAVE_RENDER
  if (render) return fail("haif run: this build has no renderer; use --no-render", 2);
#endif
  const bool renderPhases = cl.has("--render-phases");
  if (renderPhases && !render) return fail("haif run: --render-phases needs rendering (drop --no-render)", 2);
  const std::string video = cl.get("--video");
  if (!video.empty() && !render) return fail("haif run: --video needs rendering (drop --no-render)", 2);
  // Every option is checked before anything is created.
#ifdef HAIF_HAVE_RENDER
  if (!applyGlOption(cl.get("--gl", "auto"), error)) return fail("haif run: " + error, 2);
#endif
  const std::string view = cl.get("--view", "normal");
  if (view != "normal" && view != "island" && view != "sleep" && view != "heat")
    return fail("haif run: --view: expected normal, island, sleep or heat, got '" + view + "'", 2);
  const std::string corner = cl.get("--overlay-corner", "tl");
  if (corner != "tl" && corner != "tr" && corner != "bl" && corner != "br")
    return fail("haif run: --overlay-corner: expected tl, tr, bl or br, got '" + corner + "'", 2);
  if (!video.empty() && std::filesystem::path(video).extension() != ".mp4")
    return fail("haif run: --video: expected a .mp4 file, got '" + video + "'", 2);
  if (!video.empty() && !checkOutputFile(video, error)) return fail("haif run: --video: " + error, 2);

  Simulation sim;
  if (!makeSimulation(scenePath, spec, threads, sim, error)) return fail(error);
  World& world = *sim.world;
  if (frames < 0) frames = sim.scene.settings.frames;
  if (!checkReplayLength(sim, spec, frames, error)) return fail(error);
  world.setSolveErrorInterval(errorEvery);

  // Check the output folder before spending time on the simulation. It is written whole or not at
  // all: into a temporary folder beside it, moved into place when the run is complete.
  if (!cl.has("--out") && !sceneNameProblem(sim.scene.name).empty())
    return fail("haif run: " + scenePath + ": scene name '" + sim.scene.name +
                "' cannot name a folder under output/; give --out DIR");
  const std::string outDir = cl.get("--out", "output/" + sim.scene.name);
  const std::vector<std::string> runMarkers = {"summary.json", "stats.csv", "frames"};
  if (!checkOutputFolder(outDir, runMarkers, error)) return fail("haif run: " + error);
  // A video inside the output folder is written into the temporary folder with the rest.
  std::string videoInOut;
  const bool videoInside = !video.empty() && isInside(video, outDir, videoInOut);

  RunInfo info = runInfoFor(sim, budget, threads);

  std::vector<StepStats> stats;
  RunMetrics metrics;
  metrics.begin(world, uint64_t(frames));
  std::vector<double> renderMs;
  // --render-phases: per phase, its name and its time in each frame (a glFinish per phase).
  std::vector<std::pair<std::string, std::vector<double>>> phaseMs;
  bool renderFailed = false;

  Progress progress("run", "step", frames);
  // After the first step the contacts are those of the starting state.
  auto warnStartOverlaps = [&](const World& w) {
    if (w.lastStats().step != 0) return;
    const std::string text =
        describeStartOverlaps(sim.scene, deepContacts(w, kStartOverlapWarningDepth), /*maxPairs=*/5);
    if (!text.empty()) std::fputs(text.c_str(), stderr);
  };
#ifdef HAIF_HAVE_RENDER
  std::unique_ptr<render::Renderer> renderer;
  FrameBuilder builder;
  render::FrameInput frame;
  if (render) {
    render::RendererOptions ro;
    ro.width = width;
    ro.height = height;
    ro.timePhases = renderPhases;
    renderer = render::Renderer::create(ro, &error);
    if (!renderer) return fail("haif run: renderer: " + error);
    if (!builder.registerMeshes(world, sim.scene, *renderer, error))
      return fail("haif run: " + scenePath + ": " + error);
    parseViewMode(view, frame.mode);
    frame.showContacts = cl.has("--contacts");
    frame.overlay.enabled = !cl.has("--no-overlay");
    if (corner == "tl") frame.overlay.corner = render::Corner::TopLeft;
    else if (corner == "tr") frame.overlay.corner = render::Corner::TopRight;
    else if (corner == "bl") frame.overlay.corner = render::Corner::BottomLeft;
    else frame.overlay.corner = render::Corner::BottomRight;
    frame.overlay.scene = sim.scene.name;
    frame.overlay.mode = sim.mode;
    frame.overlay.bodies = int(world.bodyCount());
    frame.overlay.iMin = float(world.controller().iMin);
    frame.overlay.iMax = float(std::min(world.controller().iMax, 1000));
    frame.overlay.budgetMs = float(info.budgetMs);
  }
#endif
  std::function<void(bool)> holdBeside;  // the encoders, held while each step runs
  StagedFolder output;
  if (!output.open(outDir, runMarkers, error)) return fail("haif run: " + error);
  const std::string stage = output.path();
  const std::string framesDir = stage + "/frames";
  if (render && !ensureWritableDir(framesDir, error)) return fail("haif run: " + error);
#ifdef HAIF_HAVE_RENDER
  // With --video the frames stream into ffmpeg as they are rendered (and are still written as PNGs).
  VideoEncoder encoder;
  const bool encoding = !video.empty() && ffmpegAvailable();
  if (!video.empty() && !encoding)
    std::fprintf(stderr, "haif run: ffmpeg not found on PATH (apt-get install ffmpeg): no %s; the frames are in %s\n",
                 video.c_str(), (outDir + "/frames").c_str());
  const std::string videoPath = videoInside ? stage + "/" + videoInOut : video;
  if (encoding && !encoder.open(videoPath, width, height, 60.0 / frameEvery, error)) return fail("haif run: " + error);
  // PNG encoding runs on one writer thread, overlapping the next steps and frames.
  std::unique_ptr<render::AsyncPngWriter> pngWriter;
  if (render) pngWriter = std::make_unique<render::AsyncPngWriter>();
  // Both encoders wait while a step runs, and work while the frames are drawn (EncodingHold).
  holdBeside = [&](bool held) {
    if (encoding) encoder.hold(held);
    if (pngWriter) pngWriter->hold(held);
  };
  std::vector<uint8_t> pixels;
  int frameIndex = 0;
  auto afterStep = [&](const World& w) {
    warnStartOverlaps(w);
    progress.advance(int(w.lastStats().step) + 1);
    if (!render || renderFailed) return;
    const StepStats& s = w.lastStats();
    frame.overlay.iterations.push_back(float(s.iterationsChosen));
    frame.overlay.collisionMs.push_back(float(s.collisionMs));
    frame.overlay.solveMs.push_back(float(s.solveMs));
    if ((s.step % uint64_t(frameEvery)) != 0) return;
    const auto t0 = std::chrono::steady_clock::now();
    builder.build(w, sim.scene.camera, frame);
    frame.overlay.islands = int(s.islands);
    frame.overlay.step = int64_t(s.step);
    frame.overlay.msPerStep = float(s.totalMs);
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%05d.png", frameIndex++);
    std::string why;
    if (!renderer->render(frame, pixels, &why) || (encoding && !encoder.write(pixels.data(), why)) ||
        !pngWriter->submit(framesDir + name, width, height, pixels, &why)) {
      error = "haif run: frame " + std::to_string(frameIndex - 1) + ": " + why;
      renderFailed = true;
    }
    renderMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    if (renderPhases) {
      const auto phases = renderer->lastPhaseTimes().inOrder();
      if (phaseMs.empty())  // the names once; each frame adds its times
        for (const auto& phase : phases) phaseMs.emplace_back(phase.first, std::vector<double>{});
      for (size_t i = 0; i < phases.size(); ++i) phaseMs[i].second.push_back(phases[i].second);
    }
  };
#else
  auto afterStep = [&](const World& w) {
    warnStartOverlaps(w);
    progress.advance(int(w.lastStats().step) + 1);
  };
#endif

  const bool finite = runSteps(sim, frames, stats, metrics, afterStep, holdBeside);
  progress.finish();
  if (renderFailed) return fail(error);
#ifdef HAIF_HAVE_RENDER
  if (pngWriter && !pngWriter->finish(&error)) return fail("haif run: frames: " + error);
#endif
  info.stateHash = world.stateHash();
  if (!renderMs.empty()) info.renderMsPerFrameMedian = quantile(renderMs, 0.5);
  for (const auto& [name, ms] : phaseMs) info.renderPhaseMsMedian.emplace_back(name, quantile(ms, 0.5));

  if (!writeFileAtomic(stage + "/stats.csv", statsCsv(stats), error)) return fail(error);
  if (!writeFileAtomic(stage + "/summary.json", summaryJson(info, stats, metrics, world), error)) return fail(error);

#ifdef HAIF_HAVE_RENDER
  if (render) {
    render::RunSeries series;
    series.scene = sim.scene.name;
    series.mode = sim.mode;
    series.iMin = float(world.controller().iMin);
    series.iMax = float(std::min(world.controller().iMax, 1000));
    series.budgetMs = float(info.budgetMs);
    series.errorName = "residual (last velocity correction)";
    series.errorUnit = "m/s";
    for (const StepStats& s : stats) {
      series.iterations.push_back(float(s.iterationsChosen));
      series.collisionMs.push_back(float(s.collisionMs));
      series.solveMs.push_back(float(s.solveMs));
      series.totalMs.push_back(float(s.totalMs));
      series.error.push_back(std::max(1e-9f, s.residual));
    }
    const std::string chartsDir = stage + "/charts";
    if (!ensureWritableDir(chartsDir, error)) return fail(error);
    if (!render::writeRunCharts(chartsDir, series, render::RunChartOptions{}, &error))
      return fail("haif run: charts: " + error);
    // The overlay prints timings: record where it is so `haif diff` can leave it out.
    FrameMasks masks;
    masks.width = width;
    masks.height = height;
    if (frame.overlay.enabled) {
      const render::PanelRect r = render::overlayPanelRect(frame.overlay, width, height);
      masks.regions.push_back({"overlay", PixelRect{r.x0, r.y0, r.x1, r.y1}});
    }
    if (!writeFileAtomic(framesDir + "/" + kFrameMasksFile, frameMasksJson(masks), error)) return fail(error);
    if (encoding && !encoder.finish(error)) return fail("haif run: " + error);
  }
#endif
  if (!output.commit(error)) {
    if (!video.empty() && !videoInside) std::remove(video.c_str());  // no video of a run that is not there
    return fail("haif run: " + error);
  }

  std::vector<double> stepMs;
  for (const StepStats& s : stats) stepMs.push_back(s.totalMs);
  std::printf("%s: %zu steps, %u bodies, %d threads, mode %s: median %.3f ms/step, state_hash %016llx%s\n",
              sim.scene.name.c_str(), stats.size(), world.bodyCount(), threads, sim.mode.c_str(), quantile(stepMs, 0.5),
              (unsigned long long)info.stateHash, finite ? "" : " (NaN detected: run stopped)");
  std::printf("wrote %s/stats.csv, %s/summary.json%s\n", outDir.c_str(), outDir.c_str(),
              render ? ", frames/, charts/" : "");
  return finite ? 0 : 3;
}

}  // namespace haif
