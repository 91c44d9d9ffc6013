// Playlists of `haif reel`: a JSON file listing title cards, scenes and comparisons to string
// together into one video (docs/reel_format.md). Scene paths are relative to the playlist's folder.
#pragma once

#include <string>
#include <vector>

namespace haif {

/// One entry of the playlist.
struct ReelItem {
  enum class Kind { Title, Scene, Compare };
  Kind kind = Kind::Scene;
  std::string place;             ///< "items[2]", for messages
  std::string text, subtitle;    ///< title: the card's text; scene/compare: an optional card before it
  std::string scenePath;         ///< scene/compare: resolved path of the scene file
  std::string solver = "model:4";  ///< scene: solver set-up
  std::string left, right;       ///< compare: the two set-ups
  std::string caption;           ///< scene/compare: line shown along the bottom of the picture
  std::string view = "normal";   ///< scene/compare: normal | island | sleep | heat
  bool overlay = true;           ///< scene/compare: overlay panels
  double seconds = 5.0;          ///< how long the item plays
  double stepSeconds = 1.0 / 60; ///< scene/compare: the scene's dt (read when the playlist is checked)
};

/// The whole playlist.
struct ReelPlaylist {
  std::string path;                 ///< the file it came from
  int width = 1280, height = 720;   ///< video size
  double fps = 30.0;                ///< video frame rate
  double crossfadeSeconds = 0.5;    ///< cross-fade between items (0: hard cuts)
  double titleSeconds = 2.0;        ///< length of the card shown before an item with a title
  std::vector<ReelItem> items;
};

/// Reads and checks `path`: the JSON, every field, every scene file and solver set-up, so that a
/// mistake is reported before any rendering. One error line "FILE:LINE:COL: PLACE: what is wrong".
bool loadReelPlaylist(const std::string& path, ReelPlaylist& out, std::string& error);

/// Same for playlist text already in memory; `path` names it in errors and scene paths are relative
/// to its folder.
bool parseReelPlaylistText(const std::string& text, const std::string& path, ReelPlaylist& out, std::string& error);

}  // namespace haif
