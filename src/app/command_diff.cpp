// haif diff A B: visual regression between two runs (or two frame folders), frame by frame.
#include "app/cli.h"
#include "app/commands.h"
#include "tools/atomic_file.h"
#include "tools/diff_report.h"
#include "tools/interrupts.h"
#include "tools/progress.h"
#include "tools/staged_output.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace haif {

namespace {

constexpr int kBadInput = 2;

int fail(const std::string& message, int status) {
  waitIfInterrupted();
  const bool prefixed = message.rfind("haif diff: ", 0) == 0;  // CommandLine's messages name the command
  std::fprintf(stderr, "%s%s\n", prefixed ? "" : "haif diff: ", message.c_str());
  return status;
}

bool readText(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream ss;
  ss << in.rdbuf();
  out = ss.str();
  return true;
}

// A member of the run's summary.json ("" when there is no run, no file or no such string member).
std::string summaryString(const FrameFolder& f, const char* key) {
  std::string text;
  if (f.runDir.empty() || !readText(f.runDir + "/summary.json", text)) return "";
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains(key) || !j[key].is_string()) return "";
  return j[key].get<std::string>();
}

// "X0:Y0:X1:Y1" in pixels.
bool parseRect(const std::string& text, PixelRect& r) {
  int v[4];
  size_t pos = 0;
  for (int k = 0; k < 4; ++k) {
    const size_t end = k < 3 ? text.find(':', pos) : text.size();
    if (end == std::string::npos) return false;
    const std::string part = text.substr(pos, end - pos);
    char* stop = nullptr;
    const long x = std::strtol(part.c_str(), &stop, 10);
    if (part.empty() || *stop != '\0' || x < 0 || x > 1000000) return false;
    v[k] = int(x);
    pos = end + 1;
  }
  r = PixelRect{v[0], v[1], v[2], v[3]};
  return !r.empty();
}

// Turns --mask into named rectangles. `overlay` takes the regions the renderer recorded in each
// side's frames/masks.json (union of both sides).
bool resolveMasks(const std::string& spec, bool explicitMask, const FrameFolder& a, const FrameFolder& b,
                  std::vector<FrameRegion>& masks, std::vector<std::string>& notes, std::string& error) {
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item == "none") continue;
    if (item == "overlay") {
      if (!a.hasMasks && !b.hasMasks) {
        const std::string why = "no " + std::string(kFrameMasksFile) + " in '" + a.framesDir + "' or '" + b.framesDir +
                                "', so the overlay region is unknown";
        if (explicitMask) {
          error = "--mask overlay: " + why + " (render the runs with this haif, or give --mask X0:Y0:X1:Y1)";
          return false;
        }
        notes.push_back(why + ": nothing masked.");
        continue;
      }
      for (const FrameFolder* f : {&a, &b}) {
        if (!f->hasMasks) continue;
        if (f->masks.width != f->width || f->masks.height != f->height) {
          error = f->framesDir + "/" + kFrameMasksFile + ": written for " + std::to_string(f->masks.width) + "x" +
                  std::to_string(f->masks.height) + " frames, the frames are " + std::to_string(f->width) + "x" +
                  std::to_string(f->height);
          return false;
        }
        for (const FrameRegion& r : f->masks.regions) {
          bool seen = false;
          for (const FrameRegion& m : masks)
            seen |= m.rect.x0 == r.rect.x0 && m.rect.y0 == r.rect.y0 && m.rect.x1 == r.rect.x1 &&
                    m.rect.y1 == r.rect.y1;
          if (!seen) masks.push_back(r);
        }
      }
      continue;
    }
    PixelRect r;
    if (!parseRect(item, r)) {
      error = "--mask: expected overlay, none or X0:Y0:X1:Y1 pixel rectangles separated by commas, got '" + item + "'";
      return false;
    }
    masks.push_back({"rectangle", r});
  }
  return true;
}

}  // namespace

int commandDiff(int argc, char** argv) {
  CommandLine cl("diff", {"--threshold", "--max-diff-ratio", "--min-ssim", "--mask", "--out", "--ssim-window"},
                 {"--no-aa", "--allow-adaptive", "--no-diff-images"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, kBadInput);
  if (cl.positional().size() != 2)
    return fail("expected two runs or frame folders: haif diff REFERENCE NEW [options] (see 'haif help')", kBadInput);

  DiffReport report;
  FrameThresholds& limits = report.thresholds;
  DiffOptions& options = report.options;
  if (!cl.getDouble("--threshold", 0.0, 1.0, options.threshold, error) ||
      !cl.getDouble("--max-diff-ratio", 0.0, 1.0, limits.maxDiffRatio, error) ||
      !cl.getDouble("--min-ssim", -1.0, 1.0, limits.minSsim, error) ||
      !cl.getInt("--ssim-window", 2, 256, options.ssimWindow, error))
    return fail(error, kBadInput);
  options.detectAntialiasing = !cl.has("--no-aa");

  if (!openFrameFolder(cl.positional()[0], "reference", report.reference, error) ||
      !openFrameFolder(cl.positional()[1], "new", report.test, error) ||
      !checkFramePairs(report.reference, report.test, error))
    return fail(error, kBadInput);

  // Wall-clock adaptive runs differ from run to run by design: nothing to regress against.
  for (const FrameFolder* f : {&report.reference, &report.test})
    if (summaryString(*f, "mode") == "adaptive" && !cl.has("--allow-adaptive"))
      return fail("'" + f->given + "' is an adaptive (wall-clock) run, whose frames change from run to run; " +
                      "diff runs made in fixed, model or replay mode (or pass --allow-adaptive)",
                  kBadInput);

  if (!resolveMasks(cl.get("--mask", "overlay"), cl.has("--mask"), report.reference, report.test, report.masks,
                    report.notes, error))
    return fail(error, kBadInput);
  for (const FrameRegion& m : report.masks) options.masks.push_back(m.rect);

  const FrameFolder &a = report.reference, &b = report.test;
  if (!a.runDir.empty() && !b.runDir.empty()) {
    std::string ta, tb;
    if (readText(a.runDir + "/stats.csv", ta) && readText(b.runDir + "/stats.csv", tb)) {
      if (!compareStatsCsv(ta, tb, a.runDir + "/stats.csv", b.runDir + "/stats.csv", report.stats, error))
        return fail(error, kBadInput);
      report.statsCompared = true;
      report.stateHashReference = summaryString(a, "state_hash");
      report.stateHashTest = summaryString(b, "state_hash");
    }
  }
  if (!report.statsCompared) report.notes.push_back("stats.csv not compared: both sides must be run folders with one.");
  report.commandLine = commandLineOf(argc, argv);

  // The report folder is built beside its place and moved there when complete: a frame that
  // cannot be read half-way leaves no diff images, and an earlier report is replaced as a whole.
  const std::string outDir = cl.get("--out", "output/diff");
  StagedFolder output;
  if (!output.open(outDir, {"report.json", "report.html"}, error)) return fail(error, kBadInput);
  const std::string diffDir = cl.has("--no-diff-images") ? "" : output.path() + "/diff";
  if (!diffDir.empty() && !ensureWritableDir(diffDir, error)) return fail(error, kBadInput);

  Progress progress("diff", "frame", int(a.frames.size()));
  const auto onFrame = [&](int done) { progress.advance(done); };
  if (!diffFrameFolders(a, b, options, limits, diffDir, report.frames, error, onFrame))
    return fail(error, kBadInput);
  progress.finish();
  for (FrameVerdict& f : report.frames)  // where the images will be once the folder is in place
    if (!f.diffImage.empty()) f.diffImage = outDir + "/diff/" + f.name;

  if (!writeFileAtomic(output.path() + "/report.json", diffReportJson(report, outDir), error) ||
      !writeFileAtomic(output.path() + "/report.html", diffReportHtml(report, outDir), error) ||
      !output.commit(error))
    return fail(error, kBadInput);

  double worstRatio = 0.0, worstSsim = 1.0;
  for (const FrameVerdict& f : report.frames) {
    worstRatio = std::max(worstRatio, f.result.diffRatio);
    worstSsim = std::min(worstSsim, f.result.ssim);
  }
  std::printf("diff: %s: %d of %zu frames over the thresholds (worst %.4f%% pixels differ, lowest SSIM %.5f)%s\n",
              report.pass() ? "pass" : "FAIL", report.failedFrames(), report.frames.size(), 100.0 * worstRatio,
              worstSsim,
              !report.statsCompared ? "" : report.statsPass() ? "; stats.csv equal" : "; stats.csv differs");
  std::printf("wrote %s/report.html, %s/report.json\n", outDir.c_str(), outDir.c_str());
  return report.pass() ? 0 : 1;
}

}  // namespace haif
