#include "engine/scene/image_io.h"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>

#include <png.h>
#include <stb_image.h>
#include <webp/decode.h>
#include <zlib.h>

#include "engine/scene/file_bytes.h"

namespace eng {
namespace {

constexpr size_t kMaxImageFileBytes = size_t{512} << 20;

Result<void> checkRgbaSize(int w, int h, size_t bytes, const std::string& what) {
  if (w <= 0 || h <= 0 || static_cast<uint64_t>(w) * static_cast<uint64_t>(h) * 4 != bytes)
    return makeError(ErrorKind::InvalidArgument, what + ": image of " + std::to_string(w) + "x" + std::to_string(h) + " needs " +
                     std::to_string(static_cast<uint64_t>(std::max(w, 0)) * std::max(h, 0) * 4) +
                     " RGBA8 bytes, got " + std::to_string(bytes));
  if (static_cast<uint64_t>(w) * 4 > INT_MAX || static_cast<uint64_t>(w) * h * 4 > INT_MAX)
    return makeError(ErrorKind::TooLarge, what + ": image of " + std::to_string(w) + "x" + std::to_string(h) + " is too large for PNG");
  return {};
}

// libpng reports an error by calling its error function, which must not
// return: ours keeps the message and long-jumps back to encodeRows' setjmp.
// So nothing with a destructor lives in the frames between them.
struct PngSink {
  std::vector<uint8_t>* out = nullptr;
  char message[160] = {};
};

[[noreturn]] void pngFailed(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof(sink->message), "%s", message);
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}  // (none for what we write)

void pngAppend(png_structp png, png_bytep data, size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool grown = true;
  try {
    sink->out->insert(sink->out->end(), data, data + size);
  } catch (const std::bad_alloc&) {
    grown = false;  // (png_error outside the handler: a jump out of it would leak the exception)
  }
  if (!grown) png_error(png, "out of memory for the encoded image");
}

void pngFlush(png_structp) {}

// zlib level 2 with the Sub filter on every row: a 512x512 rendered frame in
// 6.3 ms and 162 KB, where stb_image_write (level 8, the best of five filters
// per row) took 27.8 ms for 180 KB and zlib level 6 24 ms for 114 KB. Frames
// written in a sequence are encoded while the next ones render, on the same
// cores, so the encoder's time is the sequence's.
bool encodeRows(png_structp png, png_infop info, int w, int h, const uint8_t* rgba8) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, static_cast<png_uint_32>(w), static_cast<png_uint_32>(h), 8, PNG_COLOR_TYPE_RGBA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 2);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_write_info(png, info);
  const size_t stride = static_cast<size_t>(w) * 4;
  for (int y = 0; y < h; ++y)  // (libpng copies each row before filtering it: the pixels stay as given)
    png_write_row(png, const_cast<png_bytep>(rgba8 + stride * static_cast<size_t>(y)));
  png_write_end(png, nullptr);
  return true;
}

// stb's own header check refuses what it could not decode (60000 x 60000 PNG, JPEG) and
// stbi_info then reports the last format it tried, "unknown image type": the dimensions are
// read here from the PNG IHDR or the JPEG frame header so the refusal can say what it is.
uint32_t bigEndian(const uint8_t* p, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v = v << 8 | p[i];
  return v;
}

bool headerDimensions(std::span<const uint8_t> encoded, uint32_t& w, uint32_t& h) {
  static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (encoded.size() >= 24 && std::memcmp(encoded.data(), kPng, 8) == 0 && std::memcmp(encoded.data() + 12, "IHDR", 4) == 0) {
    w = bigEndian(encoded.data() + 16, 4);
    h = bigEndian(encoded.data() + 20, 4);
    return true;
  }
  if (encoded.size() < 4 || encoded[0] != 0xFF || encoded[1] != 0xD8) return false;
  // JPEG: walk the marker segments to the first start-of-frame (SOF0..SOF15 but DHT, JPG, DAC).
  for (size_t at = 2; at + 4 <= encoded.size();) {
    if (encoded[at] != 0xFF) return false;
    const uint8_t marker = encoded[at + 1];
    if (marker == 0xFF) { ++at; continue; }  // fill byte
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD9)) { at += 2; continue; }  // no length
    const size_t length = bigEndian(encoded.data() + at + 2, 2);
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      if (at + 9 > encoded.size()) return false;
      h = bigEndian(encoded.data() + at + 5, 2);
      w = bigEndian(encoded.data() + at + 7, 2);
      return true;
    }
    at += 2 + length;
  }
  return false;
}

Result<void> checkImageSize(uint64_t w, uint64_t h, const std::string& name, size_t maxPixels) {
  if (w > 0 && h > 0 && w <= kMaxImageSide && h <= kMaxImageSide && w * h <= maxPixels) return {};
  return makeError(ErrorKind::TooLarge, name + ": image too large: " + std::to_string(w) + "x" + std::to_string(h) + ", the limit is " +
                   std::to_string(kMaxImageSide) + " per side and " + std::to_string(maxPixels) + " pixels");
}

// Bytes of filtered scanlines a PNG of this header inflates to (Adam7: the seven passes').
uint64_t pngRawBytes(uint64_t w, uint64_t h, uint8_t depth, uint8_t colourType, bool interlaced) {
  const uint64_t channels = colourType == 2 ? 3 : colourType == 4 ? 2 : colourType == 6 ? 4 : 1;
  const uint64_t bitsPerPixel = channels * std::max<uint8_t>(depth, 1);
  const auto passBytes = [&](uint64_t pw, uint64_t ph) { return pw && ph ? ph * ((pw * bitsPerPixel + 7) / 8 + 1) : 0; };
  if (!interlaced) return passBytes(w, h);
  static constexpr uint64_t x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
  static constexpr uint64_t dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
  uint64_t bytes = 0;
  for (int p = 0; p < 7; ++p)
    bytes += passBytes(w > x0[p] ? (w - x0[p] + dx[p] - 1) / dx[p] : 0, h > y0[p] ? (h - y0[p] + dy[p] - 1) / dy[p] : 0);
  return bytes;
}

// stb (Debian's 2022 snapshot) trusts a PNG's chunk lengths and its zlib stream: an IDAT
// chunk that declares a gigabyte the file does not hold makes it allocate 2 GiB before it
// reads a byte, and a small deflate stream may inflate into gigabytes before it checks the
// size against the header. Both are refused here, before stb sees the file: every chunk
// must fit in the data, and the image data must not inflate past what the header needs.
Result<void> checkPngStream(std::span<const uint8_t> encoded, const std::string& name) {
  static constexpr uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (encoded.size() < 8 || std::memcmp(encoded.data(), kPng, 8) != 0) return {};
  uint64_t rawBytes = 0;
  z_stream inflater{};
  if (inflateInit(&inflater) != Z_OK) return makeError(ErrorKind::Io, name + ": zlib could not start");
  const std::unique_ptr<z_stream, int (*)(z_stream*)> closeInflater(&inflater, inflateEnd);
  bool inflating = true;
  uint64_t inflated = 0;
  uint8_t scratch[16384];
  // Down to a bare chunk header: stb reads one from 8 bytes (length and type)
  // and reallocates for its declared length before it finds nothing follows.
  for (size_t at = 8; at + 8 <= encoded.size();) {
    const uint32_t length = bigEndian(encoded.data() + at, 4);
    const std::string type(reinterpret_cast<const char*>(encoded.data() + at + 4), 4);
    const size_t followingHeader = encoded.size() - at - 8;  // its data and CRC
    if (length > 0x7FFFFFFFu || size_t{length} + 4 > followingHeader)
      return makeError(ErrorKind::Malformed, name + ": PNG chunk '" + type + "' at byte " + std::to_string(at) + " declares " +
                       std::to_string(length) + " bytes, only " + std::to_string(followingHeader) +
                       " follow its header (truncated or corrupt file)");
    const uint8_t* data = encoded.data() + at + 8;
    if (type == "IHDR" && length >= 13)
      rawBytes = pngRawBytes(bigEndian(data, 4), bigEndian(data + 4, 4), data[8], data[9], data[12] != 0);
    if (type == "IDAT" && inflating) {
      // A stream zlib cannot read is left to stb, which names what is corrupt.
      const uint64_t limit = 2 * rawBytes + 4096;
      inflater.next_in = const_cast<Bytef*>(data);
      inflater.avail_in = length;
      while (inflating && inflater.avail_in > 0) {
        inflater.next_out = scratch;
        inflater.avail_out = sizeof(scratch);
        const int status = inflate(&inflater, Z_NO_FLUSH);
        inflated += sizeof(scratch) - inflater.avail_out;
        if (inflated > limit)
          return makeError(ErrorKind::Malformed, name + ": PNG image data inflates past " + std::to_string(limit) + " bytes, " +
                           (rawBytes ? "its header needs " + std::to_string(rawBytes) : std::string("and no header precedes it")) +
                           " (a decompression bomb or corrupt data)");
        if (status != Z_OK) inflating = false;
      }
    }
    if (type == "IEND") break;
    at += size_t{12} + length;
  }
  return {};
}

// WebP (EXT_texture_webp) is not an stb format: libwebp decodes it.
Result<Image> decodeWebp(std::span<const uint8_t> encoded, const std::string& name, int w, int h) {
  Image img;
  img.name = name;
  img.width = w;
  img.height = h;
  img.rgba8.resize(static_cast<size_t>(w) * h * 4);
  if (!WebPDecodeRGBAInto(encoded.data(), encoded.size(), img.rgba8.data(), img.rgba8.size(), w * 4))
    return makeError(ErrorKind::Malformed, name + ": WebP decode failed (corrupt or truncated data)");
  return img;
}

}  // namespace

bool isWebp(std::span<const uint8_t> encoded) {
  return encoded.size() >= 12 && std::memcmp(encoded.data(), "RIFF", 4) == 0 &&
         std::memcmp(encoded.data() + 8, "WEBP", 4) == 0;
}

bool isKtx2(std::span<const uint8_t> encoded) {
  static constexpr uint8_t kMagic[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  return encoded.size() >= sizeof(kMagic) && std::memcmp(encoded.data(), kMagic, sizeof(kMagic)) == 0;
}

Result<std::vector<uint8_t>> encodePng(int w, int h, std::span<const uint8_t> rgba8) {
  if (auto ok = checkRgbaSize(w, h, rgba8.size(), "encodePng"); !ok) return ok.error();
  std::vector<uint8_t> encoded;
  encoded.reserve(rgba8.size() / 2);
  PngSink sink{&encoded};
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, pngFailed, pngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  bool written = false;
  if (info) {
    png_set_write_fn(png, &sink, pngAppend, pngFlush);
    written = encodeRows(png, info, w, h, rgba8.data());
  } else {
    std::snprintf(sink.message, sizeof(sink.message), "libpng could not allocate its state");
  }
  png_destroy_write_struct(&png, &info);  // (either may be null)
  if (!written)
    return makeError(ErrorKind::Io, "encodePng: a " + std::to_string(w) + "x" + std::to_string(h) + " image: " + sink.message);
  return encoded;
}

Result<void> writePng(const std::filesystem::path& path, int w, int h, std::span<const uint8_t> rgba8) {
  if (auto ok = checkRgbaSize(w, h, rgba8.size(), path.string()); !ok) return ok.error();
  auto png = encodePng(w, h, rgba8);
  if (!png) return png.error();
  return writeFileBytes(path, png->data(), png->size());
}

Result<ImageSize> imageSize(std::span<const uint8_t> encoded, const std::string& name, size_t maxPixels) {
  if (encoded.empty()) return makeError(ErrorKind::Malformed, name + ": image data is empty");
  if (encoded.size() > static_cast<size_t>(INT_MAX)) return makeError(ErrorKind::TooLarge, name + ": image data is larger than 2 GiB");
  int w = 0, h = 0, channels = 0;
  if (isWebp(encoded)) {
    if (!WebPGetInfo(encoded.data(), encoded.size(), &w, &h))
      return makeError(ErrorKind::Malformed, name + ": not a decodable WebP image (bad header)");
  } else {
    if (isKtx2(encoded))
      return makeError(ErrorKind::Unsupported, name + ": KTX2 (KHR_texture_basisu) needs a Basis Universal transcoder, which this build lacks");
    if (uint32_t headerW = 0, headerH = 0; headerDimensions(encoded, headerW, headerH))
      if (auto size = checkImageSize(headerW, headerH, name, maxPixels); !size) return size.error();
    if (auto stream = checkPngStream(encoded, name); !stream) return stream.error();
    if (!stbi_info_from_memory(encoded.data(), static_cast<int>(encoded.size()), &w, &h, &channels))
      return makeError(ErrorKind::Malformed, name + ": not a decodable image (" + stbi_failure_reason() + ")");
  }
  if (auto size = checkImageSize(std::max(w, 0), std::max(h, 0), name, maxPixels); !size) return size.error();
  return ImageSize{w, h};
}

Result<Image> decodeImage(std::span<const uint8_t> encoded, const std::string& name, size_t maxPixels) {
  auto size = imageSize(encoded, name, maxPixels);
  if (!size) return size.error();
  if (isWebp(encoded)) return decodeWebp(encoded, name, size->width, size->height);
  int w = 0, h = 0, channels = 0;
  const int len = static_cast<int>(encoded.size());
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(encoded.data(), len, &w, &h, &channels, 4),
                                                    stbi_image_free);
  if (!pixels) return makeError(ErrorKind::Malformed, name + ": image decode failed (" + stbi_failure_reason() + ")");
  Image img;
  img.name = name;
  img.width = w;
  img.height = h;
  img.rgba8.assign(pixels.get(), pixels.get() + static_cast<size_t>(w) * h * 4);
  return img;
}

Result<Image> readImage(const std::filesystem::path& path) {
  auto bytes = readFileBytes(path, kMaxImageFileBytes);
  if (!bytes) return bytes.error();
  return decodeImage(*bytes, path.string());
}

}  // namespace eng
