// The compressed image data of a PNG (its IDAT payload: a zlib stream of filtered scanlines), made
// by a deflate coder written for rendered frames. zlib's own deflate, even at level 1, spent ~30 ms
// on a 1280x720 frame, a fifth of the CPU of a rendering run on two cores, where it competes with
// the rasteriser. Rendered frames are mostly flat shading, gradients and runs, so after the PNG
// "sub" filter nearly all of their redundancy is a repeat of the pixel to the left or of the row
// above: this coder looks for matches at just those two distances, with Huffman codes fitted to each
// block (RFC 1951 dynamic blocks). Output is a standard stream any PNG reader decodes.
// Against Debian's libdeflate 1.14 on the same sub-filtered scanlines of 30 demo frames (1280x720,
// session 18): this coder 6.4 ms a frame, 512 KB; libdeflate level 1 12.2 ms (1.2 ms of it the
// filter), 411 KB; level 6 25.9 ms, 378 KB. Frames are intermediate files, so speed decides.
#pragma once

#include <cstdint>
#include <vector>

namespace haif::render {

class PngDeflater {
 public:
  /// Appends to `out` the zlib stream of the image's scanlines: `height` rows of `width` pixels of
  /// `channels` bytes (3: RGB, 4: RGBA) each, read from `pixels` with `pixelStride` bytes a pixel
  /// (≥ channels; extra bytes are skipped, e.g. RGBA input written as RGB), top row first.
  /// Buffers are kept between calls, so a writer that reuses one deflater allocates only at first.
  void compress(const uint8_t* pixels, int width, int height, int channels, int pixelStride,
                std::vector<uint8_t>& out);

 private:
  std::vector<uint8_t> filtered_;  // filter byte + "sub"-filtered bytes, row after row
  std::vector<uint32_t> tokens_;   // literals and matches of one block
};

}  // namespace haif::render
