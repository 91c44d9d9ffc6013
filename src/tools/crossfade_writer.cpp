#include "tools/crossfade_writer.h"

#include <cstring>

namespace haif {

CrossfadeWriter::CrossfadeWriter(FrameSink& out, int width, int height)
    : out_(out), frameBytes_(size_t(width) * size_t(height) * 4) {}

std::vector<uint8_t> CrossfadeWriter::takeBuffer() {
  if (spare_.empty()) return std::vector<uint8_t>(frameBytes_);
  std::vector<uint8_t> b = std::move(spare_.back());
  spare_.pop_back();
  return b;
}

bool CrossfadeWriter::emit(const uint8_t* rgba, std::string& error) {
  if (!out_.write(rgba, error)) return false;
  ++framesOut_;
  return true;
}

bool CrossfadeWriter::beginClip(int fadeIn, int holdOut, std::string& error) {
  // Leftovers of a previous fade (a clip shorter than promised) go out as they are.
  for (; !fading_.empty(); fading_.pop_front()) {
    if (!emit(fading_.front().data(), error)) return false;
    spare_.push_back(std::move(fading_.front()));
  }
  // Only the last `fadeIn` held frames blend; any earlier ones are emitted unchanged.
  while (int(held_.size()) > std::max(0, fadeIn)) {
    if (!emit(held_.front().data(), error)) return false;
    spare_.push_back(std::move(held_.front()));
    held_.pop_front();
  }
  fading_.swap(held_);
  fadeDone_ = 0;
  fadeTotal_ = int(fading_.size());
  hold_ = std::max(0, holdOut);
  return true;
}

bool CrossfadeWriter::write(const uint8_t* rgba, std::string& error) {
  if (!fading_.empty()) {
    // Weight of the new clip rises linearly and never reaches 0 or 1 inside the fade.
    const float t = float(fadeDone_ + 1) / float(fadeTotal_ + 1);
    const uint8_t* old = fading_.front().data();
    blended_.resize(frameBytes_);
    for (size_t i = 0; i < frameBytes_; ++i)
      blended_[i] = uint8_t(float(old[i]) + (float(rgba[i]) - float(old[i])) * t + 0.5f);
    spare_.push_back(std::move(fading_.front()));
    fading_.pop_front();
    ++fadeDone_;
    return emit(blended_.data(), error);
  }
  if (hold_ == 0) return emit(rgba, error);
  std::vector<uint8_t> copy = takeBuffer();
  std::memcpy(copy.data(), rgba, frameBytes_);
  held_.push_back(std::move(copy));
  if (int(held_.size()) > hold_) {
    if (!emit(held_.front().data(), error)) return false;
    spare_.push_back(std::move(held_.front()));
    held_.pop_front();
  }
  return true;
}

bool CrossfadeWriter::finish(std::string& error) {
  for (auto* queue : {&fading_, &held_})
    for (; !queue->empty(); queue->pop_front())
      if (!emit(queue->front().data(), error)) return false;
  return true;
}

}  // namespace haif
