#include "render/png_deflate.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <type_traits>

namespace haif::render {

namespace {

// ---- deflate's fixed tables (RFC 1951 §3.2.5) ----------------------------------------------
constexpr int kLengthCodes = 29;
constexpr uint16_t kLengthBase[kLengthCodes] = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr uint8_t kLengthExtra[kLengthCodes] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr int kLitLenSymbols = 286;  // 0-255 literals, 256 end of block, 257-285 lengths
constexpr int kDistSymbols = 30;
constexpr int kCodeLengthSymbols = 19;
constexpr uint8_t kCodeLengthOrder[kCodeLengthSymbols] = {16, 17, 18, 0, 8,  7, 9,  6, 10, 5,
                                                          11, 4,  12, 3, 13, 2, 14, 1, 15};
constexpr int kMinMatch = 3, kMaxMatch = 258;
constexpr size_t kWindow = 32768;
constexpr int kEndOfBlock = 256;

// Length (3..258) -> index into kLengthBase, built once.
struct LengthTable {
  uint8_t code[kMaxMatch + 1] = {};
  LengthTable() {
    for (int c = 0; c < kLengthCodes; ++c) {
      const int last = c + 1 < kLengthCodes ? kLengthBase[c + 1] - 1 : kMaxMatch;
      for (int len = kLengthBase[c]; len <= last; ++len) code[len] = uint8_t(c);  // 258: a code of its own
    }
  }
};
const LengthTable kLengths;

// Distance (1..32768) -> distance symbol and its extra bits.
inline int distSymbol(uint32_t d) {
  if (d <= 4) return int(d) - 1;
  const uint32_t v = d - 1;
  const int top = 31 - __builtin_clz(v);  // ≥ 2
  return 2 * top + int((v >> (top - 1)) & 1u);
}
inline int distExtraBits(int sym) { return sym < 4 ? 0 : sym / 2 - 1; }
inline uint32_t distBase(int sym) { return sym < 4 ? uint32_t(sym) + 1 : ((2u + uint32_t(sym & 1)) << (sym / 2 - 1)) + 1; }

// ---- Huffman codes ----------------------------------------------------------------------------

// Code lengths for `freq` of n symbols, none longer than `limit`. The code is complete (what zlib's
// inflate requires) because it comes from a Huffman tree of at least two leaves: callers give two
// or more symbols a non-zero count. Too long a code is fixed by flattening the counts and building
// again, which costs a little size on pathological blocks and nothing on ordinary ones.
void huffmanLengths(const uint32_t* freq, int n, int limit, uint8_t* lengths) {
  std::array<uint32_t, kLitLenSymbols> f{};
  std::copy(freq, freq + n, f.begin());
  std::fill(lengths, lengths + n, uint8_t(0));
  // Leaves sorted by count, then internal nodes in creation order (their counts never decrease):
  // the two-queue construction.
  std::array<uint32_t, 2 * kLitLenSymbols> weight{};
  std::array<int, 2 * kLitLenSymbols> parent{};
  std::array<int, kLitLenSymbols> leaves{};
  for (;;) {
    int count = 0;
    for (int s = 0; s < n; ++s)
      if (f[size_t(s)] > 0) leaves[size_t(count++)] = s;
    std::sort(leaves.begin(), leaves.begin() + count, [&](int a, int b) {
      return f[size_t(a)] != f[size_t(b)] ? f[size_t(a)] < f[size_t(b)] : a < b;
    });
    for (int i = 0; i < count; ++i) weight[size_t(i)] = f[size_t(leaves[size_t(i)])];
    int nextLeaf = 0, nextNode = count, made = count;
    auto takeSmallest = [&]() {
      if (nextLeaf < count && (nextNode == made || weight[size_t(nextLeaf)] <= weight[size_t(nextNode)]))
        return nextLeaf++;
      return nextNode++;
    };
    while (made < 2 * count - 1) {
      const int a = takeSmallest(), b = takeSmallest();
      weight[size_t(made)] = weight[size_t(a)] + weight[size_t(b)];
      parent[size_t(a)] = parent[size_t(b)] = made;
      ++made;
    }
    // Depths top-down: the root is the last node made, and every parent was made after its children.
    std::array<uint8_t, 2 * kLitLenSymbols> depth{};
    depth[size_t(made - 1)] = 0;
    int deepest = 0;
    for (int i = made - 2; i >= 0; --i) {
      depth[size_t(i)] = uint8_t(depth[size_t(parent[size_t(i)])] + 1);
      if (i < count) deepest = std::max(deepest, int(depth[size_t(i)]));
    }
    if (deepest <= limit) {
      for (int i = 0; i < count; ++i) lengths[leaves[size_t(i)]] = depth[size_t(i)];
      return;
    }
    for (int s = 0; s < n; ++s)
      if (f[size_t(s)] > 0) f[size_t(s)] = (f[size_t(s)] + 1) / 2;
  }
}

// Canonical codes for the lengths (RFC 1951 §3.2.2), bit-reversed: deflate sends a Huffman code's
// first bit first into a stream packed from each byte's least significant bit.
void canonicalCodes(const uint8_t* lengths, int n, uint16_t* codes) {
  uint16_t count[16] = {}, next[16] = {};
  for (int s = 0; s < n; ++s) ++count[lengths[s]];
  count[0] = 0;
  uint16_t code = 0;
  for (int len = 1; len < 16; ++len) {
    code = uint16_t((code + count[len - 1]) << 1);
    next[len] = code;
  }
  for (int s = 0; s < n; ++s) {
    const int len = lengths[s];
    if (len == 0) continue;
    uint16_t c = next[len]++, reversed = 0;
    for (int b = 0; b < len; ++b, c >>= 1) reversed = uint16_t((reversed << 1) | (c & 1u));
    codes[s] = reversed;
  }
}

struct HuffmanCode {
  uint8_t lengths[kLitLenSymbols];
  uint16_t codes[kLitLenSymbols];
  void build(const uint32_t* freq, int n, int limit) {
    huffmanLengths(freq, n, limit, lengths);
    canonicalCodes(lengths, n, codes);
  }
};

// ---- bits out ---------------------------------------------------------------------------------

class BitWriter {
 public:
  explicit BitWriter(uint8_t* out) : out_(out) {}
  // n ≤ 16 bits a call. Branch-free: the whole accumulator is stored every time and the pointer
  // moves by the bytes completed, which needs 8 bytes of slack after the data.
  void put(uint32_t value, int n) {
    acc_ |= uint64_t(value) << bits_;
    bits_ += n;
    std::memcpy(out_, &acc_, 8);  // little-endian: the stream's byte order
    out_ += bits_ >> 3;
    acc_ >>= bits_ & ~7;
    bits_ &= 7;
  }
  // Pads to a byte boundary and returns the end of the data.
  uint8_t* finish() {
    if (bits_ > 0) *out_++ = uint8_t(acc_);
    acc_ = 0;
    bits_ = 0;
    return out_;
  }

 private:
  uint8_t* out_;
  uint64_t acc_ = 0;
  int bits_ = 0;
};

// ---- matches ----------------------------------------------------------------------------------

// Bytes from p that equal those from p - dist, up to max.
inline size_t matchLength(const uint8_t* p, size_t dist, size_t max) {
  const uint8_t* q = p - dist;
  size_t n = 0;
  while (n + 8 <= max) {
    uint64_t a, b;
    std::memcpy(&a, p + n, 8);
    std::memcpy(&b, q + n, 8);
    if (const uint64_t x = a ^ b) return n + size_t(__builtin_ctzll(x)) / 8;
    n += 8;
  }
  while (n < max && p[n] == q[n]) ++n;
  return n;
}

// Bit k (k < 6) set when the 3 bytes from p + k equal those from p + k - dist: where a match can
// start. Needs 8 bytes readable from p and from p - dist.
inline uint32_t matchStarts(const uint8_t* p, size_t dist) {
  uint64_t a, b;
  std::memcpy(&a, p, 8);
  std::memcpy(&b, p - dist, 8);
  const uint64_t x = a ^ b;
  constexpr uint64_t kLow7 = 0x7f7f7f7f7f7f7f7full;
  const uint64_t zero = ~(((x & kLow7) + kLow7) | x | kLow7);  // 0x80 in each byte of x that is 0
  const uint64_t run3 = zero & (zero >> 8) & (zero >> 16);
  // Bit 7 of byte k to bit k: the multiply moves each byte's bit to its own place in the top
  // byte, with no two products overlapping (so no carries).
  return uint32_t((((run3 >> 7) & 0x010101010101ull) * 0x0102040810204080ull) >> 56) & 0x3fu;
}

// Rows of the image, each its filter byte (1: "sub") and each byte minus the same channel of the
// pixel to its left. The common layouts come as std::integral_constant, so their inner loops have
// fixed sizes.
template <class Channels, class Stride>
void subFilter(const uint8_t* pixels, int width, int height, Channels channels, Stride stride, uint8_t* out) {
  for (int y = 0; y < height; ++y) {
    const uint8_t* src = pixels + size_t(y) * size_t(width) * size_t(stride);
    *out++ = 1;
    for (int c = 0; c < channels; ++c) out[c] = src[c];
    out += channels;
    for (int x = 1; x < width; ++x, out += channels, src += stride)
      for (int c = 0; c < channels; ++c) out[c] = uint8_t(src[stride + c] - src[c]);
  }
}

constexpr uint32_t kMatchFlag = 1u << 31;

// Writes one dynamic block of `tokens` with the counts gathered while making them.
void writeBlock(BitWriter& bw, const uint32_t* tokens, size_t tokenCount, uint32_t* litFreq, uint32_t* distFreq,
                bool last) {
  litFreq[kEndOfBlock] = 1;
  // Two symbols at least in each code keep it complete; a block without matches gets two dummy
  // distance codes that are never sent.
  if (std::count_if(litFreq, litFreq + kLitLenSymbols, [](uint32_t f) { return f > 0; }) < 2) litFreq[0] += 1;
  int distUsed = int(std::count_if(distFreq, distFreq + kDistSymbols, [](uint32_t f) { return f > 0; }));
  for (int s = 0; distUsed < 2; ++s)
    if (distFreq[s] == 0) {
      distFreq[s] = 1;
      ++distUsed;
    }
  HuffmanCode lit, dist;
  lit.build(litFreq, kLitLenSymbols, 15);
  dist.build(distFreq, kDistSymbols, 15);
  int hlit = kLitLenSymbols, hdist = kDistSymbols;
  while (hlit > 257 && lit.lengths[hlit - 1] == 0) --hlit;
  while (hdist > 1 && dist.lengths[hdist - 1] == 0) --hdist;

  // The two code-length lists, run-length coded (RFC 1951 §3.2.7): symbol | extra value << 8.
  uint8_t all[kLitLenSymbols + kDistSymbols];
  std::copy(lit.lengths, lit.lengths + hlit, all);
  std::copy(dist.lengths, dist.lengths + hdist, all + hlit);
  const int total = hlit + hdist;
  uint16_t runs[kLitLenSymbols + kDistSymbols];
  int runCount = 0;
  uint32_t clFreq[kCodeLengthSymbols] = {};
  auto emit = [&](int sym, int extra) {
    runs[runCount++] = uint16_t(sym | (extra << 8));
    ++clFreq[sym];
  };
  for (int i = 0; i < total;) {
    const uint8_t v = all[i];
    int run = 1;
    while (i + run < total && all[i + run] == v) ++run;
    i += run;
    if (v == 0) {
      for (; run >= 11; run -= std::min(run, 138)) emit(18, std::min(run, 138) - 11);
      if (run >= 3) emit(17, run - 3);
      else
        for (; run > 0; --run) emit(0, 0);
    } else {
      emit(v, 0);
      for (--run; run >= 3; run -= std::min(run, 6)) emit(16, std::min(run, 6) - 3);
      for (; run > 0; --run) emit(v, 0);
    }
  }
  if (std::count_if(clFreq, clFreq + kCodeLengthSymbols, [](uint32_t f) { return f > 0; }) < 2)
    ++clFreq[clFreq[0] == 0 ? 0 : 1];
  HuffmanCode cl;
  cl.build(clFreq, kCodeLengthSymbols, 7);
  int hclen = kCodeLengthSymbols;
  while (hclen > 4 && cl.lengths[kCodeLengthOrder[hclen - 1]] == 0) --hclen;

  bw.put(last ? 1u : 0u, 1);
  bw.put(2, 2);  // dynamic Huffman codes
  bw.put(uint32_t(hlit - 257), 5);
  bw.put(uint32_t(hdist - 1), 5);
  bw.put(uint32_t(hclen - 4), 4);
  for (int i = 0; i < hclen; ++i) bw.put(cl.lengths[kCodeLengthOrder[i]], 3);
  static constexpr int kRunExtraBits[3] = {2, 3, 7};  // symbols 16, 17, 18
  for (int i = 0; i < runCount; ++i) {
    const int sym = runs[i] & 0xff, extra = runs[i] >> 8;
    bw.put(cl.codes[sym], cl.lengths[sym]);
    if (sym >= 16) bw.put(uint32_t(extra), kRunExtraBits[sym - 16]);
  }

  for (size_t t = 0; t < tokenCount; ++t) {
    const uint32_t tok = tokens[t];
    if (!(tok & kMatchFlag)) {
      bw.put(lit.codes[tok], lit.lengths[tok]);
      continue;
    }
    const uint32_t len = (tok >> 16) & 0x1ff, d = tok & 0xffff;
    const int lc = kLengths.code[len];
    bw.put(lit.codes[257 + lc], lit.lengths[257 + lc]);
    if (kLengthExtra[lc]) bw.put(len - kLengthBase[lc], kLengthExtra[lc]);
    const int ds = distSymbol(d);
    bw.put(dist.codes[ds], dist.lengths[ds]);
    if (const int eb = distExtraBits(ds)) bw.put(d - distBase(ds), eb);
  }
  bw.put(lit.codes[kEndOfBlock], lit.lengths[kEndOfBlock]);
}

}  // namespace

void PngDeflater::compress(const uint8_t* pixels, int width, int height, int channels, int pixelStride,
                           std::vector<uint8_t>& out) {
  const size_t bpp = size_t(channels);
  const size_t rowBytes = 1 + size_t(width) * bpp;
  const size_t total = rowBytes * size_t(height);

  // "Sub" filter: each byte minus the same channel of the pixel to its left.
  filtered_.resize(total);
  using Three = std::integral_constant<int, 3>;
  using Four = std::integral_constant<int, 4>;
  uint8_t* f = filtered_.data();
  if (channels == 3 && pixelStride == 4) subFilter(pixels, width, height, Three{}, Four{}, f);
  else if (channels == 4 && pixelStride == 4) subFilter(pixels, width, height, Four{}, Four{}, f);
  else if (channels == 3 && pixelStride == 3) subFilter(pixels, width, height, Three{}, Three{}, f);
  else subFilter(pixels, width, height, channels, pixelStride, f);

  // Blocks of about 128 KiB of scanlines each get their own codes; a match may reach back into the
  // block before. Bound on the output: no token costs more than 16 bits per byte it covers (a
  // 15-bit literal; a match of ≥ 3 bytes in ≤ 48 bits), a block's header and end fit in 640 bytes,
  // plus the zlib header, the checksum and the bit writer's 8 bytes of slack.
  constexpr size_t kBlockBytes = 1u << 17;
  const size_t start = out.size();
  out.resize(start + 2 + 2 * total + 640 * (total / kBlockBytes + 1) + 4 + 8);
  uint8_t* o = out.data() + start;
  *o++ = 0x78;  // deflate, 32 KiB window
  *o++ = 0x01;  // fastest level; (0x78 * 256 + 0x01) is a multiple of 31, as zlib's check requires
  BitWriter bw(o);
  tokens_.resize(kBlockBytes);
  const uint8_t* data = filtered_.data();
  const bool rowMatches = rowBytes <= kWindow;
  size_t i = 0;
  do {
    const size_t blockEnd = std::min(total, i + kBlockBytes);
    uint32_t litFreq[kLitLenSymbols] = {}, distFreq[kDistSymbols] = {};
    size_t n = 0;
    while (i < blockEnd) {
      // Most bytes of a shaded frame are literals: find where the next match of 3 or more can
      // start, 8 bytes at a time, and pass the literals before it without a branch each.
      if (i >= rowBytes && i + 8 <= total) {
        const uint32_t starts = matchStarts(data + i, bpp) | (rowMatches ? matchStarts(data + i, rowBytes) : 0u);
        const size_t literals = std::min<size_t>(starts ? size_t(__builtin_ctz(starts)) : 6, blockEnd - i);
        for (size_t k = 0; k < literals; ++k) {
          tokens_[n++] = data[i + k];
          ++litFreq[data[i + k]];
        }
        i += literals;
        if (!starts || i >= blockEnd) continue;
      }
      const size_t max = std::min<size_t>(kMaxMatch, total - i);
      size_t len = i >= bpp ? matchLength(data + i, bpp, max) : 0, dist = bpp;
      if (rowMatches && i >= rowBytes && len < max) {
        const size_t up = matchLength(data + i, rowBytes, max);
        if (up > len) {
          len = up;
          dist = rowBytes;
        }
      }
      if (len >= size_t(kMinMatch)) {
        tokens_[n++] = kMatchFlag | uint32_t(len << 16) | uint32_t(dist);
        ++litFreq[257 + kLengths.code[len]];
        ++distFreq[distSymbol(uint32_t(dist))];
        i += len;
      } else {
        tokens_[n++] = data[i];
        ++litFreq[data[i]];
        ++i;
      }
    }
    writeBlock(bw, tokens_.data(), n, litFreq, distFreq, i >= total);
  } while (i < total);
  o = bw.finish();
  const uint32_t adler = uint32_t(adler32_z(adler32(0, nullptr, 0), data, total));
  for (int s = 24; s >= 0; s -= 8) *o++ = uint8_t(adler >> s);
  out.resize(size_t(o - out.data()));
}

}  // namespace haif::render
