#include "render/png_io.h"

#include "render/png_deflate.h"

#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace haif::render {

namespace {

// libpng reports errors by longjmp: keep the jump target in a function without C++ objects that
// need destructors, and carry the message out in a plain buffer.
struct PngWriteState {
  char message[256];
};

void onPngError(png_structp png, png_const_charp text) {
  auto* state = static_cast<PngWriteState*>(png_get_error_ptr(png));
  std::snprintf(state->message, sizeof state->message, "%s", text);
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

// libpng writes the file (signature, header, chunks, checksums); the image data is compressed by
// PngDeflater, about twice as fast as zlib's level 1 on rendered frames at ~15% more size (see
// png_deflate.h). Frames are intermediate files (they go to a video encoder or a diff), so speed
// beats size. Opaque images are stored as RGB, a quarter less data to compress.
bool encodePng(FILE* file, int w, int h, const uint8_t* rgba, bool opaque, PngWriteState* state) {
  // One deflater and output buffer per thread: a frame writer reuses them for every frame.
  thread_local PngDeflater deflater;
  thread_local std::vector<uint8_t> idat;
  idat.clear();
  deflater.compress(rgba, w, h, opaque ? 3 : 4, 4, idat);

  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, state, onPngError, onPngWarning);
  if (!png) {
    std::snprintf(state->message, sizeof state->message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    if (!info) std::snprintf(state->message, sizeof state->message, "out of memory");
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8,
               opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGB_ALPHA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  // The compressed rows as IDAT chunks of at most 1 MiB each (any split is valid), then the end.
  constexpr size_t kChunk = size_t(1) << 20;
  for (size_t at = 0; at < idat.size(); at += kChunk)
    png_write_chunk(png, reinterpret_cast<png_const_bytep>("IDAT"), idat.data() + at, std::min(kChunk, idat.size() - at));
  png_write_chunk(png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
  png_destroy_write_struct(&png, &info);
  return true;
}

bool isOpaque(int w, int h, const uint8_t* rgba) {
  const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h);
  uint8_t all = 255;
  for (size_t i = 0; i < n; ++i) all &= rgba[4 * i + 3];
  return all == 255;
}

}  // namespace

bool writePng(const std::string& path, int w, int h, const uint8_t* rgba, std::string* error) {
  if (w <= 0 || h <= 0 || !rgba) {
    if (error) *error = "writePng: invalid image for '" + path + "'";
    return false;
  }
  // Process id in the temporary name: two writers of the same path never share a temp file.
  const std::string tmp = path + ".tmp" + std::to_string(static_cast<long>(getpid()));
  FILE* file = std::fopen(tmp.c_str(), "wb");
  if (!file) {
    if (error) *error = "cannot write PNG '" + path + "': " + std::strerror(errno);
    return false;
  }
  PngWriteState state{};
  const bool encoded = encodePng(file, w, h, rgba, isOpaque(w, h, rgba), &state);
  const bool closed = std::fclose(file) == 0;
  if (!encoded || !closed) {
    if (error) *error = "cannot write PNG '" + path + "': " + (encoded ? std::strerror(errno) : state.message);
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

namespace {

// Opens `path` and reads its header into `image`; on failure frees it and says why.
bool beginRead(const std::string& path, png_image& image, std::string* error) {
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, path.c_str())) return true;
  if (error) *error = "cannot read PNG '" + path + "': " + image.message;
  png_image_free(&image);
  return false;
}

}  // namespace

bool readPng(const std::string& path, int* w, int* h, std::vector<uint8_t>* rgba, std::string* error) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) {
    if (error) *error = "cannot read PNG '" + path + "': " + std::strerror(errno);
    return false;
  }
  std::vector<uint8_t> bytes;
  uint8_t buffer[1 << 16];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) bytes.insert(bytes.end(), buffer, buffer + n);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) {
    if (error) *error = "cannot read PNG '" + path + "': read error";
    return false;
  }
  return decodePng(bytes.data(), bytes.size(), path, w, h, rgba, error);
}

bool decodePng(const uint8_t* data, size_t size, const std::string& name, int* w, int* h, std::vector<uint8_t>* rgba,
               std::string* error, uint64_t maxPixels) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, data, size)) {
    if (error) *error = "cannot read PNG '" + name + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  if (uint64_t(image.width) * image.height > maxPixels) {
    if (error)
      *error = "cannot read PNG '" + name + "': " + std::to_string(image.width) + "x" + std::to_string(image.height) +
               " pixels is larger than " + std::to_string(maxPixels) + " pixels";
    png_image_free(&image);
    return false;
  }
  image.format = PNG_FORMAT_RGBA;
  rgba->resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, rgba->data(), 0, nullptr)) {
    if (error) *error = "cannot decode PNG '" + name + "': " + image.message;
    png_image_free(&image);
    return false;
  }
  *w = static_cast<int>(image.width);
  *h = static_cast<int>(image.height);
  return true;
}

bool readPngSize(const std::string& path, int* w, int* h, std::string* error) {
  png_image image;
  if (!beginRead(path, image, error)) return false;
  *w = static_cast<int>(image.width);
  *h = static_cast<int>(image.height);
  png_image_free(&image);
  return true;
}

}  // namespace haif::render
