// Reading back a video with ffprobe: frame count, size, codec, pixel format, and whether the index
// (moov) comes before the data (mdat), which is what +faststart does.
#pragma once

#include "haif_process.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

namespace haif::test {

struct VideoInfo {
  bool ok = false;
  int width = 0, height = 0, frames = 0;
  std::string codec, pixelFormat;
  bool indexFirst = false;  ///< moov before mdat
};

inline bool haveProgram(const char* name) {
  const std::string cmd = std::string("command -v ") + name + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

inline VideoInfo probeVideo(const std::filesystem::path& video) {
  VideoInfo v;
  const std::string cmd = "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                          "stream=codec_name,pix_fmt,width,height,nb_read_frames -of default=nw=1 '" +
                          video.string() + "'";
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return v;
  std::string text;
  char buf[256];
  while (std::fgets(buf, sizeof buf, p)) text += buf;
  if (::pclose(p) != 0) return v;
  std::stringstream ss(text);
  for (std::string line; std::getline(ss, line);) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "codec_name") v.codec = value;
    else if (key == "pix_fmt") v.pixelFormat = value;
    else if (key == "width") v.width = std::atoi(value.c_str());
    else if (key == "height") v.height = std::atoi(value.c_str());
    else if (key == "nb_read_frames") v.frames = std::atoi(value.c_str());
  }
  const std::string bytes = readWholeFile(video);
  const size_t moov = bytes.find("moov"), mdat = bytes.find("mdat");
  v.indexFirst = moov != std::string::npos && mdat != std::string::npos && moov < mdat;
  v.ok = v.frames > 0;
  return v;
}

}  // namespace haif::test
