// PNG files via libpng. Writes go to a temporary name in the same directory and are renamed into
// place, so a reader never sees a half-written frame.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace haif::render {

/// Writes w*h RGBA8 pixels, top row first, to path. False and *error on any failure (and no file
/// left at path or at the temporary name).
bool writePng(const std::string& path, int w, int h, const uint8_t* rgba, std::string* error);

/// The largest image readPng decodes, in pixels: the renderer's largest frame (8192 x 8192). A
/// header may claim up to 1e6 x 1e6 pixels, and the 4 TB buffer for it was allocated before a byte of
/// image data was read.
constexpr uint64_t kMaxPngPixels = uint64_t(8192) * 8192;

/// Reads any PNG as RGBA8, top row first. False and *error on failure.
bool readPng(const std::string& path, int* w, int* h, std::vector<uint8_t>* rgba, std::string* error);

/// Decodes PNG bytes as readPng does a file's; `name` names them in errors. Images of more than
/// `maxPixels` pixels are refused before their buffer is allocated.
bool decodePng(const uint8_t* data, size_t size, const std::string& name, int* w, int* h, std::vector<uint8_t>* rgba,
               std::string* error, uint64_t maxPixels = kMaxPngPixels);

/// Reads only the header of a PNG: its size. False and *error when it is not a readable PNG.
bool readPngSize(const std::string& path, int* w, int* h, std::string* error);

}  // namespace haif::render
