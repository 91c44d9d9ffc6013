// A clip: a run of rendered frames of one size (a simulated scene, a side-by-side comparison, a
// title card). `haif compare` encodes one; `haif reel` strings several together.
#pragma once

#ifdef HAIF_HAVE_RENDER
#include "tools/frame_masks.h"
#include "tools/video.h"

#include <cstdint>
#include <string>
#include <vector>

namespace haif {

class Clip {
 public:
  virtual ~Clip() = default;
  /// Number of frames next() will produce.
  virtual int frameCount() const = 0;
  /// Renders the next frame into rgba (width*height*4, top row first). One error line on failure.
  virtual bool next(std::vector<uint8_t>& rgba, std::string& error) = 0;
  /// Regions whose pixels depend on wall-clock timings (for frames/masks.json).
  virtual std::vector<FrameRegion> timingRegions() const = 0;
  /// Lowest row of the picture proper: captions sit just above it (charts below stay visible).
  virtual int captionBottom() const = 0;
  /// The sink this clip's frames go to, held while its simulations step (EncodingHold); null: none.
  void holdWhileStepping(FrameSink* sink) { holdWhileStepping_ = sink; }

 protected:
  FrameSink* holdWhileStepping_ = nullptr;
};

}  // namespace haif
#endif
