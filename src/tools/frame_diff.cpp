#include "tools/frame_diff.h"

#include "render/png_io.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <mutex>

namespace haif {

namespace fs = std::filesystem;

bool openFrameFolder(const std::string& path, const std::string& label, FrameFolder& out, std::string& error) {
  FrameFolder f;
  f.given = path;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    error = label + " '" + path + "': no such folder";
    return false;
  }
  if (!fs::is_directory(path, ec)) {
    error = label + " '" + path + "': not a folder (expected a run folder or a folder of PNG frames)";
    return false;
  }
  if (fs::is_directory(fs::path(path) / "frames", ec)) {
    f.runDir = path;
    f.framesDir = (fs::path(path) / "frames").string();
  } else {
    f.framesDir = path;
  }
  for (const auto& entry : fs::directory_iterator(f.framesDir, ec)) {
    const std::string name = entry.path().filename().string();
    // Hidden names are temporaries of a writer that has not finished.
    if (entry.is_regular_file() && entry.path().extension() == ".png" && name[0] != '.') f.frames.push_back(name);
  }
  if (ec) {
    error = label + " '" + f.framesDir + "': cannot list the folder (" + ec.message() + ")";
    return false;
  }
  if (f.frames.empty()) {
    error = label + " '" + f.framesDir + "': no PNG frames in the folder";
    return false;
  }
  std::sort(f.frames.begin(), f.frames.end());
  std::string why;
  if (!render::readPngSize(f.framesDir + "/" + f.frames[0], &f.width, &f.height, &why)) {
    error = label + ": " + why;
    return false;
  }
  const std::string masksPath = f.framesDir + "/" + kFrameMasksFile;
  if (fs::exists(masksPath, ec)) {
    if (!readFrameMasks(masksPath, f.masks, error)) return false;
    f.hasMasks = true;
  }
  out = std::move(f);
  return true;
}

bool checkFramePairs(const FrameFolder& a, const FrameFolder& b, std::string& error) {
  if (a.frames != b.frames) {
    // Name the first frame that one side lacks: the most useful clue to what went wrong.
    std::string missing, side;
    for (const std::string& n : a.frames)
      if (!std::binary_search(b.frames.begin(), b.frames.end(), n)) {
        missing = n, side = "new";
        break;
      }
    if (missing.empty())
      for (const std::string& n : b.frames)
        if (!std::binary_search(a.frames.begin(), a.frames.end(), n)) {
          missing = n, side = "reference";
          break;
        }
    error = "frame lists differ: reference '" + a.framesDir + "' has " + std::to_string(a.frames.size()) +
            " frames, new '" + b.framesDir + "' has " + std::to_string(b.frames.size()) + " (" + missing +
            " is missing from the " + side + " side)";
    return false;
  }
  for (const std::string& n : a.frames) {
    int wa = 0, ha = 0, wb = 0, hb = 0;
    std::string why;
    if (!render::readPngSize(a.framesDir + "/" + n, &wa, &ha, &why) ||
        !render::readPngSize(b.framesDir + "/" + n, &wb, &hb, &why)) {
      error = why;
      return false;
    }
    if (wa != wb || ha != hb) {
      error = "size mismatch at " + n + ": reference is " + std::to_string(wa) + "x" + std::to_string(ha) +
              ", new is " + std::to_string(wb) + "x" + std::to_string(hb) +
              " (render both at the same --width/--height)";
      return false;
    }
  }
  return true;
}

bool diffFrameFolders(const FrameFolder& a, const FrameFolder& b, const DiffOptions& options,
                      const FrameThresholds& thresholds, const std::string& diffDir, std::vector<FrameVerdict>& out,
                      std::string& error, const std::function<void(int)>& onFrame) {
  std::vector<FrameVerdict> verdicts(a.frames.size());
  std::atomic<int> done{0};
  std::mutex mutex;  // guards `error`, `failed` and the progress callback
  bool failed = false;
  tbb::parallel_for(size_t(0), a.frames.size(), [&](size_t i) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (failed) return;
    }
    const std::string& name = a.frames[i];
    Image ra, rb;
    std::string why;
    bool ok = render::readPng(a.framesDir + "/" + name, &ra.width, &ra.height, &ra.rgba, &why) &&
              render::readPng(b.framesDir + "/" + name, &rb.width, &rb.height, &rb.rgba, &why);
    if (ok && (ra.width != rb.width || ra.height != rb.height)) {
      ok = false;
      why = "size mismatch at " + name + " (a frame changed while it was compared)";
    }
    FrameVerdict v;
    if (ok) {
      v.name = name;
      Image diff;
      v.result = compareImages(ra, rb, options, diffDir.empty() ? nullptr : &diff);
      v.pass = v.result.diffRatio <= thresholds.maxDiffRatio && v.result.ssim >= thresholds.minSsim;
      if (!diffDir.empty()) {
        v.diffImage = diffDir + "/" + name;
        ok = render::writePng(v.diffImage, diff.width, diff.height, diff.rgba.data(), &why);
      }
    }
    std::lock_guard<std::mutex> lock(mutex);
    if (!ok) {
      if (!failed) error = why;
      failed = true;
      return;
    }
    verdicts[i] = std::move(v);
    if (onFrame) onFrame(++done);
  });
  if (failed) return false;
  out = std::move(verdicts);
  return true;
}

}  // namespace haif
