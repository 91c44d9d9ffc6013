#include "tools/frame_masks.h"

#include <nlohmann/json.hpp>

#include <fstream>
#include <sstream>

namespace haif {

std::string frameMasksJson(const FrameMasks& masks) {
  nlohmann::ordered_json j;
  j["width"] = masks.width;
  j["height"] = masks.height;
  j["regions"] = nlohmann::ordered_json::array();
  for (const FrameRegion& r : masks.regions)
    j["regions"].push_back(
        {{"name", r.name}, {"x0", r.rect.x0}, {"y0", r.rect.y0}, {"x1", r.rect.x1}, {"y1", r.rect.y1}});
  return j.dump(2) + "\n";
}

bool readFrameMasks(const std::string& path, FrameMasks& out, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open the masks file";
    return false;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(ss.str(), nullptr, false);
  if (j.is_discarded()) {
    error = path + ": not valid JSON";
    return false;
  }
  auto isInt = [](const nlohmann::json& v) { return v.is_number_integer(); };
  if (!j.is_object() || !j.contains("width") || !isInt(j["width"]) || !j.contains("height") ||
      !isInt(j["height"]) || !j.contains("regions") || !j["regions"].is_array()) {
    error = path + ": expected {\"width\": W, \"height\": H, \"regions\": [...]}";
    return false;
  }
  FrameMasks m;
  m.width = j["width"].get<int>();
  m.height = j["height"].get<int>();
  for (size_t i = 0; i < j["regions"].size(); ++i) {
    const nlohmann::json& r = j["regions"][i];
    const std::string place = path + ": regions[" + std::to_string(i) + "]";
    if (!r.is_object()) {
      error = place + ": expected an object";
      return false;
    }
    FrameRegion fr;
    fr.name = r.contains("name") && r["name"].is_string() ? r["name"].get<std::string>() : "region";
    int* fields[4] = {&fr.rect.x0, &fr.rect.y0, &fr.rect.x1, &fr.rect.y1};
    const char* keys[4] = {"x0", "y0", "x1", "y1"};
    for (int k = 0; k < 4; ++k) {
      if (!r.contains(keys[k]) || !isInt(r[keys[k]])) {
        error = place + "." + keys[k] + ": expected an integer pixel coordinate";
        return false;
      }
      *fields[k] = r[keys[k]].get<int>();
    }
    m.regions.push_back(fr);
  }
  out = std::move(m);
  return true;
}

}  // namespace haif
