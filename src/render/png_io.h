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

/// Reads any PNG as RGBA8, top row first. False and *error on failure.
bool readPng(const std::string& path, int* w, int* h, std::vector<uint8_t>* rgba, std::string* error);

/// Reads only the header of a PNG: its size. False and *error when it is not a readable PNG.
bool readPngSize(const std::string& path, int* w, int* h, std::string* error);

}  // namespace haif::render
