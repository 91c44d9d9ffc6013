// haif reel PLAYLIST.json: title cards, scenes and comparisons in sequence in one video.
#include "app/cli.h"
#include "app/commands.h"
#include "tools/interrupts.h"
#include "app/reel_playlist.h"

#ifdef HAIF_HAVE_RENDER
#include "app/comparison_clip.h"
#include "app/frame_builder.h"
#include "app/scene_clip.h"
#include "app/title_card.h"
#include "tools/crossfade_writer.h"
#include "tools/progress.h"
#include "tools/video.h"
#endif

#include <tbb/info.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

namespace haif {

namespace {

int fail(const std::string& message, int status) {
  waitIfInterrupted();
  const bool prefixed = message.rfind("haif reel: ", 0) == 0;
  std::fprintf(stderr, "%s%s\n", prefixed ? "" : "haif reel: ", message.c_str());
  return status;
}

#ifdef HAIF_HAVE_RENDER
/// One stretch of the video: a title card or an item's clip.
struct Segment {
  const ReelItem* item = nullptr;
  bool card = false;  ///< the title card of `item` (or a title item)
  int frames = 0;
  int fadeIn = 0, holdOut = 0;
};

int fadeTotal(const std::vector<Segment>& segments) {
  int n = 0;
  for (const Segment& s : segments) n += s.fadeIn;
  return n;
}

std::unique_ptr<Clip> openSegment(const Segment& seg, const ReelPlaylist& p, int threads, std::string& error) {
  const ReelItem& item = *seg.item;
  if (seg.card) {
    auto card = std::make_unique<TitleCardClip>();
    if (!card->open(item.text, item.subtitle, p.width, p.height, seg.frames, error)) return nullptr;
    return card;
  }
  // Whole steps per video frame, as close to real time as the frame rate allows.
  const int frameEvery = std::max(1, int(std::lround(1.0 / (p.fps * item.stepSeconds))));
  render::ViewMode view = render::ViewMode::Normal;
  parseViewMode(item.view, view);
  if (item.kind == ReelItem::Kind::Compare) {
    ComparisonOptions o;
    o.width = p.width, o.height = p.height, o.frames = seg.frames, o.frameEvery = frameEvery;
    o.threads = threads, o.overlay = item.overlay, o.view = view;
    auto clip = std::make_unique<ComparisonClip>();
    if (!clip->open(item.scenePath, item.left, item.right, o, error)) return nullptr;
    return clip;
  }
  SceneClipOptions o;
  o.width = p.width, o.height = p.height, o.frames = seg.frames, o.frameEvery = frameEvery;
  o.threads = threads, o.overlay = item.overlay, o.view = view;
  auto clip = std::make_unique<SceneClip>();
  if (!clip->open(item.scenePath, item.solver, o, error)) return nullptr;
  return clip;
}
#endif

}  // namespace

int commandReel(int argc, char** argv) {
#ifndef HAIF_HAVE_RENDER
  (void)argc, (void)argv;
  return fail("this build has no renderer (configure with -DHAIF_BUILD_RENDER=ON)", 2);
#else
  CommandLine cl("reel", {"--out", "--width", "--height", "--fps", "--threads", "--gl"}, {"--check"});
  std::string error;
  if (!cl.parse(argc, argv, 2, error)) return fail(error, 2);
  if (cl.positional().size() != 1) return fail("expected exactly one PLAYLIST.json (see 'haif help')", 2);
  const std::string playlistPath = cl.positional()[0];
  int threads = int(tbb::info::default_concurrency()), width = -1, height = -1;
  double fps = -1.0;
  if (!cl.getInt("--width", 128, 8192, width, error) || !cl.getInt("--height", 200, 8192, height, error) ||
      !cl.getDouble("--fps", 1.0, 240.0, fps, error) || !cl.getInt("--threads", 1, 1024, threads, error))
    return fail(error, 2);
  if (!applyGlOption(cl.get("--gl", "auto"), error)) return fail(error, 2);
  const std::string out =
      cl.get("--out", "output/" + std::filesystem::path(playlistPath).stem().string() + ".mp4");
  if (std::filesystem::path(out).extension() != ".mp4")
    return fail("--out: expected a .mp4 file, got '" + out + "'", 2);
  if (!cl.has("--check") && !checkOutputFile(out, error)) return fail("--out: " + error, 2);

  ReelPlaylist p;
  if (!loadReelPlaylist(playlistPath, p, error)) return fail(error, 1);
  if (width > 0) p.width = width;
  if (height > 0) p.height = height;
  if (fps > 0) p.fps = fps;

  // The timeline: each item, preceded by its title card when it has a title.
  std::vector<Segment> segments;
  auto framesFor = [&](double seconds) { return std::max(1, int(std::lround(seconds * p.fps))); };
  for (const ReelItem& item : p.items) {
    if (item.kind == ReelItem::Kind::Title) {
      segments.push_back({&item, true, framesFor(item.seconds)});
      continue;
    }
    if (!item.text.empty()) segments.push_back({&item, true, framesFor(p.titleSeconds)});
    segments.push_back({&item, false, framesFor(item.seconds)});
  }
  // A cross-fade takes at most half of either neighbour.
  const int fade = int(std::lround(p.crossfadeSeconds * p.fps));
  int toRender = 0;
  for (size_t i = 0; i < segments.size(); ++i) {
    if (i + 1 < segments.size()) {
      const int f = std::min({fade, segments[i].frames / 2, segments[i + 1].frames / 2});
      segments[i].holdOut = segments[i + 1].fadeIn = f;
    }
    toRender += segments[i].frames;
  }

  if (cl.has("--check")) {
    // The timeline without rendering: what would be made, and that the playlist is sound.
    for (const Segment& seg : segments) {
      const ReelItem& it = *seg.item;
      const std::string what = seg.card ? "title card '" + it.text + "'"
                               : it.kind == ReelItem::Kind::Compare
                                   ? "compare " + it.scenePath + " " + it.left + " vs " + it.right
                                   : "scene " + it.scenePath + " " + it.solver;
      const std::string view = seg.card || it.view == "normal" ? "" : ", " + it.view + " view";
      std::printf("%-10s %4d frames  %s%s\n", it.place.c_str(), seg.frames, what.c_str(), view.c_str());
    }
    std::printf("%s: %d frames (%.1f s at %g fps), %dx%d\n", playlistPath.c_str(), toRender - fadeTotal(segments),
                (toRender - fadeTotal(segments)) / p.fps, p.fps, p.width, p.height);
    return 0;
  }

  std::string notice;
  std::unique_ptr<FrameSink> sink = openVideoOrFrames(out, p.width, p.height, p.fps, notice, error);
  if (!sink) return fail(error, 1);
  if (!notice.empty()) std::fprintf(stderr, "haif reel: %s\n", notice.c_str());
  auto text = render::TextRenderer::create(render::RendererOptions{}.fontPath, &error);
  if (!text) return fail(error, 1);

  CrossfadeWriter writer(*sink, p.width, p.height);
  Progress progress("reel", "frame", toRender);
  std::vector<uint8_t> rgba;
  int rendered = 0;
  for (const Segment& seg : segments) {
    // One clip at a time: its renderer and worlds are freed before the next opens.
    std::unique_ptr<Clip> clip = openSegment(seg, p, threads, error);
    if (!clip) return fail(p.path + ": " + seg.item->place + ": " + error, 1);
    clip->holdWhileStepping(sink.get());
    if (!writer.beginClip(seg.fadeIn, seg.holdOut, error)) return fail(error, 1);
    for (int f = 0; f < seg.frames; ++f) {
      if (!clip->next(rgba, error)) return fail(p.path + ": " + seg.item->place + ": " + error, 1);
      if (!seg.card && !seg.item->caption.empty()) {
        render::Canvas canvas(rgba.data(), p.width, p.height);
        drawCaption(canvas, *text, seg.item->caption, clip->captionBottom());
      }
      if (!writer.write(rgba.data(), error)) return fail(error, 1);
      progress.advance(++rendered);
    }
  }
  if (!writer.finish(error) || !sink->finish(error)) return fail(error, 1);
  progress.finish();
  std::printf("wrote %s: %d frames (%.1f s at %g fps) from %zu items, %dx%d\n", sink->where().c_str(),
              writer.framesOut(), writer.framesOut() / p.fps, p.fps, p.items.size(), p.width, p.height);
  return 0;
#endif
}

}  // namespace haif
