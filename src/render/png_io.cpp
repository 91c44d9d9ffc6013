#include "render/png_io.h"

#include <png.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace haif::render {

bool writePng(const std::string& path, int w, int h, const uint8_t* rgba, std::string* error) {
  if (w <= 0 || h <= 0 || !rgba) {
    if (error) *error = "writePng: invalid image for '" + path + "'";
    return false;
  }
  // Process id in the temporary name: two writers of the same path never share a temp file.
  const std::string tmp = path + ".tmp" + std::to_string(static_cast<long>(getpid()));
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGBA;
  if (!png_image_write_to_file(&image, tmp.c_str(), 0, rgba, w * 4, nullptr)) {
    if (error) *error = "cannot write PNG '" + path + "': " + image.message;
    png_image_free(&image);
    std::remove(tmp.c_str());
    return false;
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    if (error) *error = "cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno);
    std::remove(tmp.c_str());
    return false;
  }
  return true;
}

bool readPng(const std::string& path, int* w, int* h, std::vector<uint8_t>* rgba, std::string* error) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    if (error) *error = "cannot read PNG '" + path + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  image.format = PNG_FORMAT_RGBA;
  rgba->resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba->data(), 0, nullptr)) {
    if (error) *error = "cannot decode PNG '" + path + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  *w = static_cast<int>(image.width);
  *h = static_cast<int>(image.height);
  return true;
}

bool readPngSize(const std::string& path, int* w, int* h, std::string* error) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) {
    if (error) *error = "cannot read PNG '" + path + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  *w = static_cast<int>(image.width);
  *h = static_cast<int>(image.height);
  png_image_free(&image);
  return true;
}

}  // namespace haif::render
