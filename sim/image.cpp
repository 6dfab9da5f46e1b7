#include "sim/image.h"

#include <fmt/format.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>

#include "model/error.h"
#include "sim/output_file.h"

namespace phongsim {

Image::Image(int width, int height, Rgb8 fill) {
  if (width < 0 || height < 0 || width > kMaxSize || height > kMaxSize) {
    throw Error(fmt::format("image size {}x{} is out of range (0..{})", width, height, kMaxSize));
  }
  width_ = width;
  height_ = height;
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

Rgb8& Image::at(int x, int y) {
  assert(contains(x, y));
  return pixels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)];
}

const Rgb8& Image::at(int x, int y) const {
  assert(contains(x, y));
  return pixels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                 static_cast<std::size_t>(x)];
}

void fill_rect(Image& img, int x, int y, int w, int h, Rgb8 colour) {
  const int x0 = std::max(x, 0);
  const int y0 = std::max(y, 0);
  const int x1 = static_cast<int>(std::min<long>(static_cast<long>(x) + w, img.width()));
  const int y1 = static_cast<int>(std::min<long>(static_cast<long>(y) + h, img.height()));
  for (int yy = y0; yy < y1; ++yy) {
    for (int xx = x0; xx < x1; ++xx) img.at(xx, yy) = colour;
  }
}

// ---- PNG ----

namespace {

constexpr std::array<std::uint8_t, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr int kBytesPerPixel = 3;
// IDAT payloads are split so no chunk approaches the 2^31 - 1 length limit.
constexpr std::size_t kIdatChunk = std::size_t{1} << 16;

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 24));
  out.push_back(static_cast<std::uint8_t>(v >> 16));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}

std::uint32_t get_u32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

// The CRC covers the chunk type and data, not the length.
void put_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], const std::uint8_t* data,
               std::size_t size) {
  put_u32(out, static_cast<std::uint32_t>(size));
  const std::size_t type_at = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + size);
  const auto crc = crc32(0L, out.data() + type_at, static_cast<uInt>(4 + size));
  put_u32(out, static_cast<std::uint32_t>(crc));
}

std::uint8_t paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a);
  const int pb = std::abs(p - b);
  const int pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return static_cast<std::uint8_t>(a);
  return static_cast<std::uint8_t>(pb <= pc ? b : c);
}

// The filtered byte of `type` for raw byte i of `row`, given the previous raw row (zeros for
// the first row). Bytes left of the row count as zero.
std::uint8_t filter_byte(int type, const std::uint8_t* row, const std::uint8_t* prev,
                         std::size_t i) {
  const int x = row[i];
  const int a = i >= kBytesPerPixel ? row[i - kBytesPerPixel] : 0;
  const int b = prev[i];
  const int c = i >= kBytesPerPixel ? prev[i - kBytesPerPixel] : 0;
  switch (type) {
    case 0:
      return static_cast<std::uint8_t>(x);
    case 1:
      return static_cast<std::uint8_t>(x - a);
    case 2:
      return static_cast<std::uint8_t>(x - b);
    case 3:
      return static_cast<std::uint8_t>(x - (a + b) / 2);
    default:
      return static_cast<std::uint8_t>(x - paeth(a, b, c));
  }
}

// Scanlines with a filter byte each; the filter per row is the one minimising the sum of the
// bytes taken as signed values (the usual heuristic: it favours runs of small residues).
std::vector<std::uint8_t> filtered_scanlines(const Image& img) {
  const std::size_t stride = static_cast<std::size_t>(img.width()) * kBytesPerPixel;
  const std::vector<std::uint8_t> zeros(stride, 0);
  std::vector<std::uint8_t> out;
  out.reserve((stride + 1) * static_cast<std::size_t>(img.height()));
  std::vector<std::uint8_t> prev(stride, 0);
  std::vector<std::uint8_t> row(stride);
  std::vector<std::uint8_t> best(stride);
  std::vector<std::uint8_t> trial(stride);
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      const Rgb8 p = img.at(x, y);
      row[3 * x] = p.r;
      row[3 * x + 1] = p.g;
      row[3 * x + 2] = p.b;
    }
    long best_cost = -1;
    int best_type = 0;
    for (int type = 0; type <= 4; ++type) {
      long cost = 0;
      for (std::size_t i = 0; i < stride; ++i) {
        trial[i] = filter_byte(type, row.data(), y == 0 ? zeros.data() : prev.data(), i);
        cost += std::abs(static_cast<int>(static_cast<std::int8_t>(trial[i])));
      }
      if (best_cost < 0 || cost < best_cost) {
        best_cost = cost;
        best_type = type;
        best.swap(trial);
      }
    }
    out.push_back(static_cast<std::uint8_t>(best_type));
    out.insert(out.end(), best.begin(), best.end());
    prev.swap(row);
  }
  return out;
}

std::vector<std::uint8_t> encode_png(const Image& img) {
  std::vector<std::uint8_t> out(kPngSignature.begin(), kPngSignature.end());
  std::vector<std::uint8_t> ihdr;
  put_u32(ihdr, static_cast<std::uint32_t>(img.width()));
  put_u32(ihdr, static_cast<std::uint32_t>(img.height()));
  // Bit depth 8, colour type 2 (RGB), deflate, adaptive filtering, no interlace.
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
  put_chunk(out, "IHDR", ihdr.data(), ihdr.size());

  const std::vector<std::uint8_t> raw = filtered_scanlines(img);
  uLongf size = compressBound(raw.size());
  std::vector<std::uint8_t> z(size);
  if (compress2(z.data(), &size, raw.data(), raw.size(), Z_DEFAULT_COMPRESSION) != Z_OK) {
    throw Error("zlib could not compress the image");
  }
  for (std::size_t at = 0; at < size; at += kIdatChunk) {
    put_chunk(out, "IDAT", z.data() + at, std::min<std::size_t>(kIdatChunk, size - at));
  }
  put_chunk(out, "IEND", nullptr, 0);
  return out;
}

}  // namespace

void write_png(const Image& img, const std::filesystem::path& path) {
  // PNG has no empty images; refuse before anything touches the file system.
  if (img.empty()) {
    throw Error(fmt::format("cannot write {}: the image is empty ({}x{})", path.string(),
                            img.width(), img.height()));
  }
  const std::vector<std::uint8_t> bytes = encode_png(img);
  OutputFile out(path);
  if (std::fwrite(bytes.data(), 1, bytes.size(), out.get()) != bytes.size()) {
    throw Error(fmt::format("cannot write {}: {}", path.string(), std::strerror(errno)));
  }
  out.commit();
}

namespace {

// Reads a PNG held in memory; `fail` formats the file's name into every message.
class PngDecoder {
 public:
  PngDecoder(const std::vector<std::uint8_t>& data, std::string name)
      : data_(data), name_(std::move(name)) {}

  Image decode() {
    if (data_.size() < kPngSignature.size() ||
        !std::equal(kPngSignature.begin(), kPngSignature.end(), data_.begin())) {
      fail("not a PNG file");
    }
    pos_ = kPngSignature.size();
    int width = 0;
    int height = 0;
    bool seen_header = false;
    std::vector<std::uint8_t> idat;
    for (;;) {
      const Chunk chunk = next_chunk();
      if (!seen_header) {
        if (chunk.type != "IHDR" || chunk.size != 13) fail("the first chunk is not IHDR");
        seen_header = true;
        read_header(chunk, width, height);
      } else if (chunk.type == "IHDR") {
        fail("a second IHDR chunk");
      } else if (chunk.type == "IDAT") {
        idat.insert(idat.end(), chunk.data, chunk.data + chunk.size);
      } else if (chunk.type == "IEND") {
        break;
      } else if (chunk.type != "PLTE" && (chunk.type[0] & 0x20) == 0) {
        // PLTE is only a suggested palette for RGB; other unknown critical chunks change the
        // meaning of the image, so they are refused. Ancillary ones are skipped.
        fail(fmt::format("unsupported critical chunk {}", chunk.type));
      }
    }
    if (idat.empty()) fail("no image data (IDAT)");
    return unfilter(inflate_all(idat, width, height), width, height);
  }

 private:
  struct Chunk {
    std::string type;
    const std::uint8_t* data = nullptr;
    std::size_t size = 0;
  };

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(fmt::format("cannot read {}: {}", name_, what));
  }

  Chunk next_chunk() {
    if (data_.size() - pos_ < 8) fail("truncated (no IEND chunk)");
    Chunk chunk;
    const std::uint32_t size = get_u32(&data_[pos_]);
    if (size > 0x7fffffffu) fail("a chunk length exceeds 2^31 - 1");
    chunk.type.assign(reinterpret_cast<const char*>(&data_[pos_ + 4]), 4);
    for (const char c : chunk.type) {
      if (!std::isalpha(static_cast<unsigned char>(c))) fail("a chunk type is not 4 letters");
    }
    if (data_.size() - pos_ - 8 < std::size_t{size} + 4)
      fail(fmt::format("truncated {} chunk", chunk.type));
    chunk.data = &data_[pos_ + 8];
    chunk.size = size;
    const auto crc = crc32(0L, &data_[pos_ + 4], static_cast<uInt>(size + 4));
    if (get_u32(&data_[pos_ + 8 + size]) != static_cast<std::uint32_t>(crc)) {
      fail(fmt::format("CRC mismatch in {} chunk", chunk.type));
    }
    pos_ += 12 + std::size_t{size};
    return chunk;
  }

  void read_header(const Chunk& chunk, int& width, int& height) const {
    const std::uint32_t w = get_u32(chunk.data);
    const std::uint32_t h = get_u32(chunk.data + 4);
    const int depth = chunk.data[8];
    const int colour = chunk.data[9];
    if (w == 0 || h == 0 || w > Image::kMaxSize || h > Image::kMaxSize) {
      fail(fmt::format("image size {}x{} is out of range (1..{})", w, h, Image::kMaxSize));
    }
    if (depth != 8 || colour != 2) {
      fail(fmt::format("unsupported bit depth {} / colour type {} (only 8-bit RGB is read)", depth,
                       colour));
    }
    if (chunk.data[10] != 0 || chunk.data[11] != 0) fail("unknown compression or filter method");
    if (chunk.data[12] != 0) fail("interlaced images are not supported");
    width = static_cast<int>(w);
    height = static_cast<int>(h);
  }

  std::vector<std::uint8_t> inflate_all(const std::vector<std::uint8_t>& z, int width,
                                        int height) const {
    const std::size_t expected =
        static_cast<std::size_t>(height) * (1 + static_cast<std::size_t>(width) * kBytesPerPixel);
    // One spare byte so that excess data is detected rather than silently dropped.
    std::vector<std::uint8_t> raw(expected + 1);
    z_stream s{};
    if (inflateInit(&s) != Z_OK) fail("zlib could not start");
    s.next_in = const_cast<Bytef*>(z.data());
    s.avail_in = static_cast<uInt>(z.size());
    s.next_out = raw.data();
    s.avail_out = static_cast<uInt>(raw.size());
    const int rc = inflate(&s, Z_FINISH);
    const std::size_t produced = s.total_out;
    inflateEnd(&s);
    if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT || rc == Z_MEM_ERROR) {
      fail("corrupt image data");
    }
    if (produced > expected) fail("more image data than its size needs");
    if (rc != Z_STREAM_END || produced < expected) fail("truncated image data");
    raw.resize(expected);
    return raw;
  }

  Image unfilter(std::vector<std::uint8_t> raw, int width, int height) const {
    const std::size_t stride = static_cast<std::size_t>(width) * kBytesPerPixel;
    const std::vector<std::uint8_t> zeros(stride, 0);
    Image img(width, height);
    for (int y = 0; y < height; ++y) {
      std::uint8_t* line = &raw[static_cast<std::size_t>(y) * (stride + 1)];
      const int type = line[0];
      std::uint8_t* row = line + 1;
      const std::uint8_t* prev = y == 0 ? zeros.data() : row - (stride + 1);
      if (type > 4) fail(fmt::format("unknown filter type {} in row {}", type, y));
      // Reconstruct in place: row[i - 3] is already a raw byte when row[i] is reached.
      for (std::size_t i = 0; i < stride; ++i) {
        const int a = i >= kBytesPerPixel ? row[i - kBytesPerPixel] : 0;
        const int b = prev[i];
        const int c = i >= kBytesPerPixel ? prev[i - kBytesPerPixel] : 0;
        int predictor = 0;
        switch (type) {
          case 1:
            predictor = a;
            break;
          case 2:
            predictor = b;
            break;
          case 3:
            predictor = (a + b) / 2;
            break;
          case 4:
            predictor = paeth(a, b, c);
            break;
          default:
            break;
        }
        row[i] = static_cast<std::uint8_t>(row[i] + predictor);
      }
      for (int x = 0; x < width; ++x) {
        img.at(x, y) = {row[3 * x], row[3 * x + 1], row[3 * x + 2]};
      }
    }
    return img;
  }

  const std::vector<std::uint8_t>& data_;
  std::string name_;
  std::size_t pos_ = 0;
};

}  // namespace

Image read_png(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("cannot read {}: {}", path.string(), std::strerror(errno)));
  std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)),
                                 std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(fmt::format("cannot read {}: read error", path.string()));
  return PngDecoder(data, path.string()).decode();
}

// ---- text ----

namespace {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 8;  // 7 rows above the baseline, 1 descender row
constexpr int kAdvance = kGlyphWidth + 1;

// Printable ASCII 32..126, one glyph per entry: 8 rows of 5 bits, top row in the high bits,
// leftmost pixel the high bit of its row (the ' separators split the rows).
constexpr std::array<std::uint64_t, 95> kFont{
    0b00000'00000'00000'00000'00000'00000'00000'00000,  // space
    0b00100'00100'00100'00100'00100'00000'00100'00000,  // !
    0b01010'01010'01010'00000'00000'00000'00000'00000,  // "
    0b01010'01010'11111'01010'11111'01010'01010'00000,  // #
    0b00100'01111'10100'01110'00101'11110'00100'00000,  // $
    0b11000'11001'00010'00100'01000'10011'00011'00000,  // %
    0b01100'10010'10100'01000'10101'10010'01101'00000,  // &
    0b00100'00100'01000'00000'00000'00000'00000'00000,  // '
    0b00010'00100'01000'01000'01000'00100'00010'00000,  // (
    0b01000'00100'00010'00010'00010'00100'01000'00000,  // )
    0b00000'00100'10101'01110'10101'00100'00000'00000,  // *
    0b00000'00100'00100'11111'00100'00100'00000'00000,  // +
    0b00000'00000'00000'00000'00000'01100'00100'01000,  // ,
    0b00000'00000'00000'11111'00000'00000'00000'00000,  // -
    0b00000'00000'00000'00000'00000'01100'01100'00000,  // .
    0b00000'00001'00010'00100'01000'10000'00000'00000,  // /
    0b01110'10001'10011'10101'11001'10001'01110'00000,  // 0
    0b00100'01100'00100'00100'00100'00100'01110'00000,  // 1
    0b01110'10001'00001'00010'00100'01000'11111'00000,  // 2
    0b11111'00010'00100'00010'00001'10001'01110'00000,  // 3
    0b00010'00110'01010'10010'11111'00010'00010'00000,  // 4
    0b11111'10000'11110'00001'00001'10001'01110'00000,  // 5
    0b00110'01000'10000'11110'10001'10001'01110'00000,  // 6
    0b11111'00001'00010'00100'01000'01000'01000'00000,  // 7
    0b01110'10001'10001'01110'10001'10001'01110'00000,  // 8
    0b01110'10001'10001'01111'00001'00010'01100'00000,  // 9
    0b00000'01100'01100'00000'01100'01100'00000'00000,  // :
    0b00000'01100'01100'00000'01100'00100'01000'00000,  // ;
    0b00010'00100'01000'10000'01000'00100'00010'00000,  // <
    0b00000'00000'11111'00000'11111'00000'00000'00000,  // =
    0b01000'00100'00010'00001'00010'00100'01000'00000,  // >
    0b01110'10001'00001'00010'00100'00000'00100'00000,  // ?
    0b01110'10001'00001'01101'10101'10101'01110'00000,  // @
    0b01110'10001'10001'11111'10001'10001'10001'00000,  // A
    0b11110'10001'10001'11110'10001'10001'11110'00000,  // B
    0b01110'10001'10000'10000'10000'10001'01110'00000,  // C
    0b11100'10010'10001'10001'10001'10010'11100'00000,  // D
    0b11111'10000'10000'11110'10000'10000'11111'00000,  // E
    0b11111'10000'10000'11110'10000'10000'10000'00000,  // F
    0b01110'10001'10000'10111'10001'10001'01111'00000,  // G
    0b10001'10001'10001'11111'10001'10001'10001'00000,  // H
    0b01110'00100'00100'00100'00100'00100'01110'00000,  // I
    0b00111'00010'00010'00010'00010'10010'01100'00000,  // J
    0b10001'10010'10100'11000'10100'10010'10001'00000,  // K
    0b10000'10000'10000'10000'10000'10000'11111'00000,  // L
    0b10001'11011'10101'10101'10001'10001'10001'00000,  // M
    0b10001'10001'11001'10101'10011'10001'10001'00000,  // N
    0b01110'10001'10001'10001'10001'10001'01110'00000,  // O
    0b11110'10001'10001'11110'10000'10000'10000'00000,  // P
    0b01110'10001'10001'10001'10101'10010'01101'00000,  // Q
    0b11110'10001'10001'11110'10100'10010'10001'00000,  // R
    0b01111'10000'10000'01110'00001'00001'11110'00000,  // S
    0b11111'00100'00100'00100'00100'00100'00100'00000,  // T
    0b10001'10001'10001'10001'10001'10001'01110'00000,  // U
    0b10001'10001'10001'10001'10001'01010'00100'00000,  // V
    0b10001'10001'10001'10101'10101'10101'01010'00000,  // W
    0b10001'10001'01010'00100'01010'10001'10001'00000,  // X
    0b10001'10001'01010'00100'00100'00100'00100'00000,  // Y
    0b11111'00001'00010'00100'01000'10000'11111'00000,  // Z
    0b01110'01000'01000'01000'01000'01000'01110'00000,  // [
    0b00000'10000'01000'00100'00010'00001'00000'00000,  // backslash
    0b01110'00010'00010'00010'00010'00010'01110'00000,  // ]
    0b00100'01010'10001'00000'00000'00000'00000'00000,  // ^
    0b00000'00000'00000'00000'00000'00000'00000'11111,  // _
    0b01000'00100'00010'00000'00000'00000'00000'00000,  // `
    0b00000'00000'01110'00001'01111'10001'01111'00000,  // a
    0b10000'10000'10110'11001'10001'10001'11110'00000,  // b
    0b00000'00000'01110'10000'10000'10001'01110'00000,  // c
    0b00001'00001'01101'10011'10001'10001'01111'00000,  // d
    0b00000'00000'01110'10001'11111'10000'01110'00000,  // e
    0b00110'01001'01000'11100'01000'01000'01000'00000,  // f
    0b00000'00000'01111'10001'10001'01111'00001'01110,  // g
    0b10000'10000'10110'11001'10001'10001'10001'00000,  // h
    0b00100'00000'01100'00100'00100'00100'01110'00000,  // i
    0b00010'00000'00110'00010'00010'00010'10010'01100,  // j
    0b10000'10000'10010'10100'11000'10100'10010'00000,  // k
    0b01100'00100'00100'00100'00100'00100'01110'00000,  // l
    0b00000'00000'11010'10101'10101'10001'10001'00000,  // m
    0b00000'00000'10110'11001'10001'10001'10001'00000,  // n
    0b00000'00000'01110'10001'10001'10001'01110'00000,  // o
    0b00000'00000'11110'10001'10001'11110'10000'10000,  // p
    0b00000'00000'01111'10001'10001'01111'00001'00001,  // q
    0b00000'00000'10110'11001'10000'10000'10000'00000,  // r
    0b00000'00000'01111'10000'01110'00001'11110'00000,  // s
    0b01000'01000'11100'01000'01000'01001'00110'00000,  // t
    0b00000'00000'10001'10001'10001'10011'01101'00000,  // u
    0b00000'00000'10001'10001'10001'01010'00100'00000,  // v
    0b00000'00000'10001'10001'10101'10101'01010'00000,  // w
    0b00000'00000'10001'01010'00100'01010'10001'00000,  // x
    0b00000'00000'10001'10001'10001'01111'00001'01110,  // y
    0b00000'00000'11111'00010'00100'01000'11111'00000,  // z
    0b00010'00100'00100'01000'00100'00100'00010'00000,  // {
    0b00100'00100'00100'00100'00100'00100'00100'00000,  // |
    0b01000'00100'00100'00010'00100'00100'01000'00000,  // }
    0b00000'00000'01000'10101'00010'00000'00000'00000,  // ~
};

// Calls f(glyph index) for each character of `text`: printable ASCII maps to its glyph, a UTF-8
// sequence (lead byte plus continuation bytes) and any other byte to '?'.
template <typename F>
void for_each_glyph(std::string_view text, F&& f) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c >= 0x80 && c < 0xc0) continue;  // UTF-8 continuation byte
    f(c >= 32 && c <= 126 ? c - 32 : '?' - 32);
  }
}

void check_scale(int scale) {
  if (scale < 1) throw Error(fmt::format("text scale {} is not a positive integer", scale));
}

}  // namespace

void draw_text(Image& img, int x, int y, std::string_view text, Rgb8 colour, int scale) {
  check_scale(scale);
  int pen = x;
  for_each_glyph(text, [&](int glyph) {
    const std::uint64_t bits = kFont[static_cast<std::size_t>(glyph)];
    for (int row = 0; row < kGlyphHeight; ++row) {
      for (int col = 0; col < kGlyphWidth; ++col) {
        const int bit = (kGlyphHeight - 1 - row) * kGlyphWidth + (kGlyphWidth - 1 - col);
        if ((bits >> bit) & 1) {
          fill_rect(img, pen + col * scale, y + row * scale, scale, scale, colour);
        }
      }
    }
    pen += kAdvance * scale;
  });
}

int text_width(std::string_view text, int scale) {
  check_scale(scale);
  int n = 0;
  for_each_glyph(text, [&](int) { ++n; });
  return n == 0 ? 0 : (n * kAdvance - 1) * scale;
}

int text_height(int scale) {
  check_scale(scale);
  return kGlyphHeight * scale;
}

void blit(Image& dst, const Image& src, int x, int y) {
  const int x0 = std::max(0, -x);
  const int y0 = std::max(0, -y);
  const int x1 = static_cast<int>(std::min<long>(src.width(), static_cast<long>(dst.width()) - x));
  const int y1 =
      static_cast<int>(std::min<long>(src.height(), static_cast<long>(dst.height()) - y));
  for (int sy = y0; sy < y1; ++sy) {
    for (int sx = x0; sx < x1; ++sx) dst.at(x + sx, y + sy) = src.at(sx, sy);
  }
}

// ---- grid ----

Image grid(const std::vector<std::vector<Image>>& cells, const std::vector<std::string>& row_labels,
           const std::vector<std::string>& col_labels, std::string_view title) {
  constexpr int kPad = 4;
  constexpr int kTitleScale = 2;
  const std::size_t rows = std::max(cells.size(), row_labels.size());
  std::size_t cols = col_labels.size();
  for (const auto& row : cells) cols = std::max(cols, row.size());
  const auto cell = [&](std::size_t r, std::size_t c) -> const Image* {
    return r < cells.size() && c < cells[r].size() ? &cells[r][c] : nullptr;
  };

  // Slot sizes: the largest cell of each column / row, widened to fit its label.
  std::vector<int> col_w(cols, 0);
  std::vector<int> row_h(rows, 0);
  for (std::size_t c = 0; c < cols; ++c) {
    if (c < col_labels.size()) col_w[c] = text_width(col_labels[c]);
  }
  int label_w = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    if (r < row_labels.size() && !row_labels[r].empty()) {
      label_w = std::max(label_w, text_width(row_labels[r]));
      row_h[r] = text_height();
    }
    for (std::size_t c = 0; c < cols; ++c) {
      if (const Image* im = cell(r, c)) {
        col_w[c] = std::max(col_w[c], im->width());
        row_h[r] = std::max(row_h[r], im->height());
      }
    }
  }
  const bool has_col_labels =
      std::any_of(col_labels.begin(), col_labels.end(), [](const auto& s) { return !s.empty(); });

  int y = kPad;
  const int title_y = y;
  if (!title.empty()) y += text_height(kTitleScale) + kPad;
  const int col_label_y = y;
  if (has_col_labels) y += text_height() + kPad;
  const int cells_y = y;
  const int cells_x = kPad + (label_w > 0 ? label_w + kPad : 0);

  long width = cells_x;
  for (const int w : col_w) width += w + kPad;
  if (cols == 0) width += kPad;
  width = std::max<long>(width, text_width(title, kTitleScale) + 2 * kPad);
  long height = cells_y;
  for (const int h : row_h) height += h + kPad;
  if (rows == 0) height += kPad;
  if (width > Image::kMaxSize || height > Image::kMaxSize) {
    throw Error(fmt::format("grid of {}x{} pixels is too large", width, height));
  }

  Image out(static_cast<int>(width), static_cast<int>(height), kWhite);
  if (!title.empty()) {
    draw_text(out, (out.width() - text_width(title, kTitleScale)) / 2, title_y, title, kBlack,
              kTitleScale);
  }
  int x = cells_x;
  for (std::size_t c = 0; c < cols; ++c) {
    if (c < col_labels.size()) {
      draw_text(out, x + (col_w[c] - text_width(col_labels[c])) / 2, col_label_y, col_labels[c],
                kBlack);
    }
    x += col_w[c] + kPad;
  }
  y = cells_y;
  for (std::size_t r = 0; r < rows; ++r) {
    if (r < row_labels.size()) {
      draw_text(out, kPad, y + (row_h[r] - text_height()) / 2, row_labels[r], kBlack);
    }
    x = cells_x;
    for (std::size_t c = 0; c < cols; ++c) {
      if (const Image* im = cell(r, c)) {
        blit(out, *im, x + (col_w[c] - im->width()) / 2, y + (row_h[r] - im->height()) / 2);
      }
      x += col_w[c] + kPad;
    }
    y += row_h[r] + kPad;
  }
  return out;
}

// ---- evaluation (Vlasic ch. 6) ----

namespace {

void check_same_size(const Image& reference, const Image& img, std::string_view what) {
  if (reference.width() != img.width() || reference.height() != img.height()) {
    throw Error(fmt::format("{}: image sizes differ ({}x{} vs {}x{})", what, reference.width(),
                            reference.height(), img.width(), img.height()));
  }
}

}  // namespace

Image difference_image(const Image& reference, const Image& img) {
  check_same_size(reference, img, "difference image");
  std::array<std::uint8_t, 256> lut{};
  for (int d = 0; d < 256; ++d) {
    lut[static_cast<std::size_t>(d)] =
        static_cast<std::uint8_t>(std::lround(255.0 * std::pow(d / 255.0, 0.1)));
  }
  const auto diff = [&](std::uint8_t a, std::uint8_t b) {
    return lut[static_cast<std::size_t>(std::abs(int{a} - int{b}))];
  };
  Image out(img.width(), img.height());
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      const Rgb8 a = reference.at(x, y);
      const Rgb8 b = img.at(x, y);
      out.at(x, y) = {diff(a.r, b.r), diff(a.g, b.g), diff(a.b, b.b)};
    }
  }
  return out;
}

ImageMetrics compare(const Image& reference, const Image& img, const std::vector<bool>& mask) {
  check_same_size(reference, img, "compare");
  const auto& ref = reference.pixels();
  const auto& got = img.pixels();
  if (!mask.empty() && mask.size() != got.size()) {
    throw Error(fmt::format("compare: the mask has {} entries for a {}x{} image", mask.size(),
                            img.width(), img.height()));
  }
  ImageMetrics m;
  std::uint64_t abs_sum = 0;
  std::uint64_t sq_sum = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (!mask.empty() && !mask[i]) continue;
    ++m.pixels;
    for (const int d :
         {int{ref[i].r} - got[i].r, int{ref[i].g} - got[i].g, int{ref[i].b} - got[i].b}) {
      abs_sum += static_cast<std::uint64_t>(std::abs(d));
      sq_sum += static_cast<std::uint64_t>(d * d);
      m.max_error = std::max(m.max_error, std::abs(d));
    }
  }
  if (m.pixels == 0) return m;
  const double channels = 3.0 * static_cast<double>(m.pixels);
  m.colour_correctness = 1.0 - static_cast<double>(abs_sum) / (255.0 * channels);
  if (sq_sum > 0) {
    const double mse = static_cast<double>(sq_sum) / channels;
    m.psnr = 10.0 * std::log10(255.0 * 255.0 / mse);
  }
  return m;
}

std::vector<double> illumination_row(const Image& img, int y) {
  if (y < 0 || y >= img.height()) {
    throw Error(
        fmt::format("illumination row {} is outside the image (height {})", y, img.height()));
  }
  std::vector<double> out(static_cast<std::size_t>(img.width()));
  for (int x = 0; x < img.width(); ++x) {
    const Rgb8 p = img.at(x, y);
    out[static_cast<std::size_t>(x)] = (p.r + p.g + p.b) / (3.0 * 255.0);
  }
  return out;
}

// ---- plot ----

Rgb8 curve_colour(std::size_t i) {
  // Tableau's 10 categorical colours: distinct, and none close to the black/grey of the axes.
  static constexpr std::array<Rgb8, 10> kPalette{{{31, 119, 180},
                                                  {255, 127, 14},
                                                  {44, 160, 44},
                                                  {214, 39, 40},
                                                  {148, 103, 189},
                                                  {140, 86, 75},
                                                  {227, 119, 194},
                                                  {188, 189, 34},
                                                  {23, 190, 207},
                                                  {127, 127, 127}}};
  return kPalette[i % kPalette.size()];
}

namespace {

// Lines are two pixels thick so colours stay recognisable; clipped to `clip`.
struct Rect {
  int x0, y0, x1, y1;  // inclusive
};

void plot_point(Image& img, int x, int y, Rgb8 colour, const Rect& clip) {
  for (int dy = 0; dy < 2; ++dy) {
    for (int dx = 0; dx < 2; ++dx) {
      const int px = x + dx;
      const int py = y - dy;
      if (px >= clip.x0 && px <= clip.x1 && py >= clip.y0 && py <= clip.y1) {
        img.at(px, py) = colour;
      }
    }
  }
}

void plot_line(Image& img, int x0, int y0, int x1, int y1, Rgb8 colour, const Rect& clip) {
  // Bresenham: every step moves one pixel along the major axis.
  const int dx = std::abs(x1 - x0);
  const int dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1;
  const int sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    plot_point(img, x0, y0, colour, clip);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

// A step of 1, 2 or 5 times a power of ten, at least `raw` and at least 1 (columns are integers).
long nice_step(double raw) {
  long step = 1;
  for (;;) {
    for (const long m : {1L, 2L, 5L}) {
      if (static_cast<double>(step * m) >= raw) return step * m;
    }
    step *= 10;
  }
}

}  // namespace

Image plot_curves(const std::vector<Curve>& curves, std::string_view title, int width, int height) {
  constexpr int kPad = 8;
  constexpr int kTick = 4;
  constexpr int kSwatch = 12;
  constexpr Rgb8 kGridLine{225, 225, 225};

  std::size_t n = 0;
  int legend_text = 0;
  for (const Curve& c : curves) {
    n = std::max(n, c.values.size());
    legend_text = std::max(legend_text, text_width(c.label));
  }
  const int title_scale = text_width(title, 2) + 2 * kPad <= width ? 2 : 1;
  const int th = text_height();
  const std::string x_caption = "pixel x";
  const std::string y_caption = "I(x, y)";

  // Plot area (inclusive bounds): tick labels left and below, legend right, title above.
  const int y_label_w = text_width("0.8");
  const int legend_w = curves.empty() ? 0 : kSwatch + 4 + legend_text + kPad;
  Rect area{};
  area.x0 = kPad + y_label_w + kTick + 2;
  area.x1 = width - 1 - kPad - legend_w;
  area.y0 = kPad + (title.empty() ? 0 : text_height(title_scale) + kPad) + th + 4;
  area.y1 = height - 1 - kPad - th - 4 - th - kTick - 2;
  if (width > Image::kMaxSize || height > Image::kMaxSize || area.x1 - area.x0 < 20 ||
      area.y1 - area.y0 < 20) {
    throw Error(fmt::format("plot size {}x{} leaves no room for the plot", width, height));
  }
  const int pw = area.x1 - area.x0;
  const int ph = area.y1 - area.y0;
  const double x_max = n > 1 ? static_cast<double>(n - 1) : 1.0;
  const auto to_px = [&](double x) {
    return area.x0 + static_cast<int>(std::lround(x / x_max * pw));
  };
  const auto to_py = [&](double v) {
    return area.y1 - static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * ph));
  };

  Image img(width, height, kWhite);
  if (!title.empty()) {
    draw_text(img, (width - text_width(title, title_scale)) / 2, kPad, title, kBlack, title_scale);
  }
  draw_text(img, std::max(0, area.x0 - text_width(y_caption) / 2), area.y0 - th - 4, y_caption,
            kBlack);

  // y: gridlines and labels every 0.2.
  for (int i = 0; i <= 5; ++i) {
    const double v = i / 5.0;
    const int py = to_py(v);
    fill_rect(img, area.x0, py, pw + 1, 1, kGridLine);
    fill_rect(img, area.x0 - kTick, py, kTick, 1, kBlack);
    const std::string label = fmt::format("{:g}", v);
    draw_text(img, area.x0 - kTick - 2 - text_width(label), py - th / 2 + 1, label, kBlack);
  }
  // x: a 1-2-5 step wide enough that neighbouring labels do not touch.
  const int widest = text_width(fmt::format("{}", static_cast<long>(x_max)));
  long step = nice_step(x_max / 10.0);
  while (static_cast<double>(step) / x_max * pw < widest + 8) step = nice_step(step + 1.0);
  for (long x = 0; static_cast<double>(x) <= x_max; x += step) {
    const int px = to_px(static_cast<double>(x));
    fill_rect(img, px, area.y0, 1, ph + 1, kGridLine);
    fill_rect(img, px, area.y1 + 1, 1, kTick, kBlack);
    const std::string label = fmt::format("{}", x);
    draw_text(img, px - text_width(label) / 2, area.y1 + kTick + 2, label, kBlack);
  }
  draw_text(img, area.x0 + (pw - text_width(x_caption)) / 2, area.y1 + kTick + 2 + th + 4,
            x_caption, kBlack);
  // Axes last among the furniture so gridlines do not cut them.
  fill_rect(img, area.x0, area.y0, 1, ph + 1, kBlack);
  fill_rect(img, area.x0, area.y1, pw + 1, 1, kBlack);

  for (std::size_t i = 0; i < curves.size(); ++i) {
    const Rgb8 colour = curve_colour(i);
    const auto& v = curves[i].values;
    bool have_prev = false;
    int prev_x = 0;
    int prev_y = 0;
    for (std::size_t x = 0; x < v.size(); ++x) {
      if (std::isnan(v[x])) {
        have_prev = false;
        continue;
      }
      const int px = to_px(static_cast<double>(x));
      const int py = to_py(v[x]);
      if (have_prev) {
        plot_line(img, prev_x, prev_y, px, py, colour, area);
      } else {
        plot_point(img, px, py, colour, area);
      }
      have_prev = true;
      prev_x = px;
      prev_y = py;
    }
    // Legend: swatch and label, one entry per line to the right of the plot.
    const int ly = area.y0 + static_cast<int>(i) * (th + 4);
    const int lx = area.x1 + kPad;
    fill_rect(img, lx, ly, kSwatch, th - 1, colour);
    draw_text(img, lx + kSwatch + 4, ly, curves[i].label, kBlack);
  }
  return img;
}

}  // namespace phongsim
