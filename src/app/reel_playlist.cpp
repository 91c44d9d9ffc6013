#include "app/reel_playlist.h"

#include "app/simulated_scene.h"
#include "scene/json_document.h"
#include "scene/json_positions.h"
#include "scene/json_reader.h"
#include "scene/scene_loader.h"
#include "scene/text_file.h"

#include <filesystem>

namespace haif {

namespace {

// Checks a solver set-up as makeSimulatedScene will read it (without loading anything).
void checkSpec(const JsonNode& node, const std::string& spec) {
  std::string why;
  if (!checkSimulationSpec(spec, why)) fail(node, why);
}

std::string viewOf(const JsonNode& item) {
  const JsonNode v = item.member("view");
  if (!v.present()) return "normal";
  const std::string s = readString(v);
  if (s != "normal" && s != "island" && s != "sleep" && s != "heat")
    fail(v, "expected normal, island, sleep or heat (got '" + s + "')");
  return s;
}

void parseItem(const JsonNode& node, const std::string& baseDir, ReelItem& item) {
  requireObject(node);
  item.place = node.place;
  const std::string type = readString(requireMember(node, "type", "title, scene or compare"));
  if (type == "title") {
    checkKeys(node, {"type", "text", "subtitle", "seconds"});
    item.kind = ReelItem::Kind::Title;
    item.text = readString(requireMember(node, "text"));
    if (node.member("subtitle").present()) item.subtitle = readString(node.member("subtitle"));
    item.seconds = optPositive(node, "seconds", 3.0f);
    return;
  }
  if (type == "scene") {
    checkKeys(node, {"type", "scene", "solver", "title", "subtitle", "caption", "view", "overlay", "seconds"});
    item.kind = ReelItem::Kind::Scene;
    if (node.member("solver").present()) item.solver = readString(node.member("solver"));
    checkSpec(node.member("solver"), item.solver);
  } else if (type == "compare") {
    checkKeys(node, {"type", "scene", "left", "right", "title", "subtitle", "caption", "view", "overlay", "seconds"});
    item.kind = ReelItem::Kind::Compare;
    item.left = readString(requireMember(node, "left", "e.g. \"fixed:10\""));
    item.right = readString(requireMember(node, "right", "e.g. \"adaptive:4\""));
    checkSpec(node.member("left"), item.left);
    checkSpec(node.member("right"), item.right);
  } else {
    fail(node.member("type"), "expected title, scene or compare (got '" + type + "')");
  }
  const JsonNode scene = requireMember(node, "scene", "a scene file, relative to the playlist");
  const std::filesystem::path p(readString(scene));
  item.scenePath = p.is_absolute() || baseDir.empty() ? p.string() : (std::filesystem::path(baseDir) / p).string();
  if (node.member("title").present()) item.text = readString(node.member("title"));
  if (node.member("subtitle").present()) item.subtitle = readString(node.member("subtitle"));
  if (node.member("caption").present()) item.caption = readString(node.member("caption"));
  if (node.member("overlay").present()) item.overlay = readBool(node.member("overlay"));
  item.view = viewOf(node);
  item.seconds = optPositive(node, "seconds", 5.0f);
  // The scene file is read now so that its mistakes stop the reel before anything is rendered.
  SceneDesc desc;
  std::string why;
  if (!loadSceneFile(item.scenePath, desc, why)) fail(scene, why);
  item.stepSeconds = desc.settings.world.dt;
}

void parseDocument(const JsonNode& root, const std::string& baseDir, ReelPlaylist& p) {
  requireObject(root);
  checkKeys(root, {"title", "width", "height", "fps", "crossfade_s", "title_card_s", "items"});
  p.width = optInt(root, "width", p.width, 128, 8192);
  p.height = optInt(root, "height", p.height, 200, 8192);
  p.fps = optPositive(root, "fps", float(p.fps));
  if (p.fps > 240.0) fail(root.member("fps"), "must be <= 240 (got " + formatNumber(p.fps) + ")");
  p.crossfadeSeconds = optNonNegative(root, "crossfade_s", float(p.crossfadeSeconds));
  p.titleSeconds = optPositive(root, "title_card_s", float(p.titleSeconds));
  const JsonNode items = requireMember(root, "items", "an array of title, scene and compare entries");
  requireArray(items);
  if (items.size() == 0) fail(items, "is empty: nothing to put in the reel");
  for (size_t i = 0; i < items.size(); ++i) {
    ReelItem item;
    parseItem(items.element(i), baseDir, item);
    p.items.push_back(std::move(item));
  }
}

}  // namespace

bool loadReelPlaylist(const std::string& path, ReelPlaylist& out, std::string& error) {
  std::string text;
  if (!readTextFile(path, "playlist", text, error)) return false;
  return parseReelPlaylistText(text, path, out, error);
}

bool parseReelPlaylistText(const std::string& text, const std::string& path, ReelPlaylist& out, std::string& error) {
  auto at = [&](size_t offset) {
    const TextLocation loc = locationOfOffset(text, offset);
    return path + ":" + std::to_string(loc.line) + ":" + std::to_string(loc.column) + ": ";
  };
  Json doc;
  JsonPositions positions;
  if (!parseJsonDocument(text, path, doc, positions, error)) return false;
  ReelPlaylist p;
  p.path = path;
  JsonNode root;
  root.value = &doc;
  try {
    parseDocument(root, std::filesystem::path(path).parent_path().string(), p);
  } catch (const SceneError& e) {
    size_t offset = e.atKey ? positions.keyOffset(e.pointer) : std::string::npos;
    if (offset == std::string::npos) offset = positions.nearestValueOffset(e.pointer);
    error = at(offset) + (e.place == "scene" ? "playlist" : e.place) + ": " + e.message;
    return false;
  }
  out = std::move(p);
  return true;
}

}  // namespace haif
