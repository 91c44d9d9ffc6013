#include "tools/diff_report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <sstream>

namespace haif {

namespace {

namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

std::string relativeTo(const std::string& path, const std::string& base) {
  std::error_code ec;
  const fs::path abs = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::path root = fs::weakly_canonical(fs::absolute(base), ec);
  const fs::path rel = abs.lexically_relative(root);
  return rel.empty() ? abs.string() : rel.generic_string();
}

OJson rectJson(const PixelRect& r) {
  if (r.empty()) return nullptr;
  return OJson{{"x0", r.x0}, {"y0", r.y0}, {"x1", r.x1}, {"y1", r.y1}};
}

std::string html(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

// A relative path as a URL: characters that would end or confuse the reference are percent-encoded.
std::string url(const std::string& path) {
  static const char* hex = "0123456789ABCDEF";
  std::string o;
  for (unsigned char c : path) {
    if (std::isalnum(c) || std::strchr("/._-~", c)) {
      o += char(c);
    } else {
      o += '%';
      o += hex[c >> 4];
      o += hex[c & 15];
    }
  }
  return o;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// Failures first, worst first; then the rest in frame order.
std::vector<size_t> reviewOrder(const std::vector<FrameVerdict>& frames) {
  std::vector<size_t> order(frames.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    const FrameVerdict &a = frames[x], &b = frames[y];
    if (a.pass != b.pass) return !a.pass;
    if (!a.pass) return a.result.diffRatio > b.result.diffRatio;
    return false;
  });
  return order;
}

}  // namespace

std::string shellQuote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

int DiffReport::failedFrames() const {
  return int(std::count_if(frames.begin(), frames.end(), [](const FrameVerdict& f) { return !f.pass; }));
}

bool DiffReport::statsPass() const {
  if (!statsCompared) return true;
  return stats.equal() && stateHashReference == stateHashTest;
}

std::string DiffReport::updateCommand() const {
  return "rm -rf " + shellQuote(reference.given) + " && cp -a " + shellQuote(test.given) + " " +
         shellQuote(reference.given);
}

std::string diffReportJson(const DiffReport& r, const std::string& outDir) {
  OJson j;
  j["verdict"] = r.pass() ? "pass" : "fail";
  j["reference"] = r.reference.given;
  j["new"] = r.test.given;
  j["reference_frames"] = r.reference.framesDir;
  j["new_frames"] = r.test.framesDir;
  j["width"] = r.reference.width;
  j["height"] = r.reference.height;
  j["update_command"] = r.updateCommand();
  j["command"] = r.commandLine;
  j["thresholds"] = {{"threshold", r.options.threshold},
                     {"max_diff_ratio", r.thresholds.maxDiffRatio},
                     {"min_ssim", r.thresholds.minSsim},
                     {"antialiasing_tolerance", r.options.detectAntialiasing},
                     {"ssim_window", r.options.ssimWindow}};
  OJson masks = OJson::array();
  for (const FrameRegion& m : r.masks) {
    if (m.rect.empty()) continue;
    masks.push_back({{"name", m.name}, {"x0", m.rect.x0}, {"y0", m.rect.y0}, {"x1", m.rect.x1}, {"y1", m.rect.y1}});
  }
  j["masks"] = masks;
  j["frames_total"] = r.frames.size();
  j["frames_failed"] = r.failedFrames();
  double worstRatio = 0.0, worstSsim = 1.0;
  for (const FrameVerdict& f : r.frames) {
    worstRatio = std::max(worstRatio, f.result.diffRatio);
    worstSsim = std::min(worstSsim, f.result.ssim);
  }
  j["max_diff_ratio_seen"] = worstRatio;
  j["min_ssim_seen"] = worstSsim;
  if (r.statsCompared) {
    OJson s;
    s["pass"] = r.statsPass();
    s["reference_rows"] = r.stats.referenceRows;
    s["new_rows"] = r.stats.testRows;
    s["state_hash_reference"] = r.stateHashReference;
    s["state_hash_new"] = r.stateHashTest;
    s["ignored_timing_columns"] = r.stats.ignoredColumns;
    s["missing_columns"] = r.stats.missingColumns;
    OJson cols = OJson::array();
    for (const ColumnDiff& c : r.stats.differing)
      cols.push_back({{"column", c.column}, {"rows", c.rows}, {"first_row", c.firstRow}, {"reference", c.reference},
                      {"new", c.test}, {"max_abs_diff", c.maxAbsDiff}});
    s["differing_columns"] = cols;
    j["stats"] = s;
  } else {
    j["stats"] = nullptr;
  }
  j["notes"] = r.notes;
  OJson frames = OJson::array();
  for (const FrameVerdict& f : r.frames) {
    const DiffResult& d = f.result;
    frames.push_back({{"frame", f.name},
                      {"pass", f.pass},
                      {"diff_ratio", d.diffRatio},
                      {"different_pixels", d.differentPixels},
                      {"antialiased_pixels", d.antialiasedPixels},
                      {"compared_pixels", d.comparedPixels},
                      {"max_colour_distance", d.maxDistance},
                      {"ssim", d.ssim},
                      {"ssim_min_window", d.ssimMin},
                      {"changed_region", rectJson(d.changed)},
                      {"reference_image", relativeTo(r.reference.framesDir + "/" + f.name, outDir)},
                      {"new_image", relativeTo(r.test.framesDir + "/" + f.name, outDir)},
                      {"diff_image", f.diffImage.empty() ? OJson(nullptr) : OJson(relativeTo(f.diffImage, outDir))}});
  }
  j["frames"] = frames;
  return j.dump(2) + "\n";
}

std::string diffReportHtml(const DiffReport& r, const std::string& outDir) {
  std::ostringstream o;
  const bool pass = r.pass();
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
    << "<title>haif diff: " << (pass ? "pass" : "FAIL") << "</title>\n<style>\n"
    << "body{font:14px/1.4 system-ui,sans-serif;margin:1.5em;color:#222}\n"
    << "pre{background:#f3f4f6;padding:.6em .8em;overflow-x:auto}\n"
    << ".verdict{font-size:1.4em;font-weight:600;padding:.3em .6em;display:inline-block;border-radius:4px}\n"
    << ".pass{background:#d7f5dd;color:#14532d}.fail{background:#fde2e1;color:#7f1d1d}\n"
    << "table{border-collapse:collapse;margin:.8em 0}td,th{border:1px solid #ddd;padding:4px 8px;vertical-align:top}\n"
    << "th{background:#f6f6f8;text-align:left}td.num{text-align:right;font-variant-numeric:tabular-nums}\n"
    << "img{max-width:400px;height:auto;display:block;image-rendering:pixelated}\n"
    << "tr.bad td:first-child{border-left:4px solid #dc2626}\n</style></head><body>\n";
  o << "<h1>haif diff</h1>\n<p>To accept the new frames as the reference:</p>\n<pre>" << html(r.updateCommand())
    << "</pre>\n";
  o << "<p><span class=\"verdict " << (pass ? "pass\">PASS" : "fail\">FAIL") << "</span> &nbsp; "
    << r.failedFrames() << " of " << r.frames.size() << " frames over the thresholds";
  if (r.statsCompared) o << "; stats.csv " << (r.statsPass() ? "equal" : "<b>differs</b>");
  o << "</p>\n<table><tr><th>reference</th><td>" << html(r.reference.given) << "</td></tr>\n<tr><th>new</th><td>"
    << html(r.test.given) << "</td></tr>\n<tr><th>frames</th><td>" << r.frames.size() << " at " << r.reference.width
    << "&times;" << r.reference.height << "</td></tr>\n<tr><th>thresholds</th><td>colour distance &gt; "
    << r.options.threshold << " counts as different"
    << (r.options.detectAntialiasing ? " (anti-aliased edges forgiven)" : "")
    << "; a frame fails when more than " << fmt("%.4g", 100.0 * r.thresholds.maxDiffRatio)
    << "% of its pixels differ or its SSIM is below " << r.thresholds.minSsim << "</td></tr>\n<tr><th>masked</th><td>";
  if (r.masks.empty()) o << "nothing";
  for (size_t i = 0; i < r.masks.size(); ++i) {
    const PixelRect& m = r.masks[i].rect;
    o << (i ? "; " : "") << html(r.masks[i].name) << ": x " << m.x0 << "&ndash;" << m.x1 << ", y " << m.y0
      << "&ndash;" << m.y1;
  }
  o << "</td></tr>\n<tr><th>command</th><td><code>" << html(r.commandLine) << "</code></td></tr>\n</table>\n";
  for (const std::string& n : r.notes) o << "<p><b>Note:</b> " << html(n) << "</p>\n";

  if (r.statsCompared) {
    o << "<h2>stats.csv (timing columns left out)</h2>\n<p>" << r.stats.referenceRows << " rows in the reference, "
      << r.stats.testRows << " in the new run; final state_hash " << html(r.stateHashReference) << " vs "
      << html(r.stateHashTest) << (r.stateHashReference == r.stateHashTest ? " (equal)" : " (<b>differs</b>)")
      << ".</p>\n";
    if (!r.stats.missingColumns.empty()) {
      o << "<p>Columns in one file only:";
      for (const std::string& c : r.stats.missingColumns) o << " " << html(c);
      o << "</p>\n";
    }
    if (!r.stats.differing.empty()) {
      o << "<table><tr><th>column</th><th>rows differing</th><th>first at step</th><th>reference</th><th>new</th>"
        << "<th>max |difference|</th></tr>\n";
      for (const ColumnDiff& c : r.stats.differing)
        o << "<tr><td>" << html(c.column) << "</td><td class=\"num\">" << c.rows << "</td><td class=\"num\">"
          << c.firstRow << "</td><td>" << html(c.reference) << "</td><td>" << html(c.test) << "</td><td class=\"num\">"
          << fmt("%.6g", c.maxAbsDiff) << "</td></tr>\n";
      o << "</table>\n";
    }
  }

  o << "<h2>Frames (failures first)</h2>\n<table>\n<tr><th>frame</th><th>verdict</th><th>differing pixels</th>"
    << "<th>SSIM</th><th>reference</th><th>new</th><th>diff</th></tr>\n";
  for (size_t i : reviewOrder(r.frames)) {
    const FrameVerdict& f = r.frames[i];
    const DiffResult& d = f.result;
    const std::string ref = url(relativeTo(r.reference.framesDir + "/" + f.name, outDir));
    const std::string neu = url(relativeTo(r.test.framesDir + "/" + f.name, outDir));
    o << "<tr" << (f.pass ? "" : " class=\"bad\"") << "><td>" << html(f.name) << "</td><td>"
      << (f.pass ? "pass" : "<b>FAIL</b>") << "</td><td class=\"num\">" << d.differentPixels << " ("
      << fmt("%.4f", 100.0 * d.diffRatio) << "%)<br>" << d.antialiasedPixels << " anti-aliased";
    if (!d.changed.empty())
      o << "<br>within x " << d.changed.x0 << "&ndash;" << d.changed.x1 << ", y " << d.changed.y0 << "&ndash;"
        << d.changed.y1;
    o << "</td><td class=\"num\">" << fmt("%.5f", d.ssim) << "</td>"
      << "<td><a href=\"" << ref << "\"><img loading=\"lazy\" src=\"" << ref << "\" alt=\"reference\"></a></td>"
      << "<td><a href=\"" << neu << "\"><img loading=\"lazy\" src=\"" << neu << "\" alt=\"new\"></a></td><td>";
    if (!f.diffImage.empty()) {
      const std::string dif = url(relativeTo(f.diffImage, outDir));
      o << "<a href=\"" << dif << "\"><img loading=\"lazy\" src=\"" << dif << "\" alt=\"diff\"></a>";
    }
    o << "</td></tr>\n";
  }
  o << "</table>\n<p>Diff images: the reference faded, differing pixels red, forgiven anti-aliasing yellow, "
    << "masked regions blue.</p>\n</body></html>\n";
  return o.str();
}

}  // namespace haif
