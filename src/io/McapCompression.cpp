#include "io/McapCompression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

namespace uavslam::io {

namespace {

using Bytes = std::vector<std::uint8_t>;

// The most one compressed byte can decode to, per format: an LZ4 sequence adds at most 255
// match bytes per extra length byte; a 4-byte zstd RLE block decodes to at most 128 KiB. A claim
// beyond these cannot be true.
constexpr std::uint64_t kLz4MaxRatio = 255;
constexpr std::uint64_t kZstdMaxRatio = 32 * 1024;
// The first output buffer; it doubles as the data really decompresses to.
constexpr std::uint64_t kFirstOutputSize = 64 * 1024;
// zstd level 1: on the demo flight's recording level 3 (zstd's default) made the file no smaller
// (32.6 MB against 32.5 MB) and took 0.20 s instead of 0.14 s to write.
constexpr int kZstdLevel = 1;
// zstd's own window buffer follows the frame's window size, which a damaged header can set to
// anything up to this (16 MiB .. 128 MiB, zstd's default ceiling) whatever the chunk claims.
constexpr unsigned kZstdMinWindowLog = 24;
constexpr unsigned kZstdMaxWindowLog = 27;

// One step of a streaming decompressor: reads from in[*in_pos..in_size), writes to
// out[*out_pos..out_size). Returns "" or the library's error; `frame_done` when a frame has been
// decoded and flushed completely.
struct StepResult {
  std::string error;
  bool frame_done = false;
};

class Lz4FrameDecoder {
 public:
  Lz4FrameDecoder() {
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context_, LZ4F_VERSION))) context_ = nullptr;
  }
  ~Lz4FrameDecoder() { LZ4F_freeDecompressionContext(context_); }
  Lz4FrameDecoder(const Lz4FrameDecoder&) = delete;
  Lz4FrameDecoder& operator=(const Lz4FrameDecoder&) = delete;

  StepResult step(const std::uint8_t* in, std::size_t& in_pos, std::size_t in_size,
                  std::uint8_t* out, std::size_t& out_pos, std::size_t out_size) {
    if (context_ == nullptr) return {"cannot create an lz4 decompression context", false};
    std::size_t written = out_size - out_pos;
    std::size_t read = in_size - in_pos;
    const std::size_t hint =
        LZ4F_decompress(context_, out + out_pos, &written, in + in_pos, &read, nullptr);
    if (LZ4F_isError(hint)) return {LZ4F_getErrorName(hint), false};
    in_pos += read;
    out_pos += written;
    return {"", hint == 0};
  }

 private:
  LZ4F_dctx* context_ = nullptr;
};

class ZstdFrameDecoder {
 public:
  explicit ZstdFrameDecoder(std::uint64_t uncompressed_size) : context_(ZSTD_createDCtx()) {
    unsigned window_log = kZstdMinWindowLog;
    while (window_log < kZstdMaxWindowLog && (std::uint64_t{1} << window_log) < uncompressed_size) {
      ++window_log;
    }
    if (context_ != nullptr) {
      ZSTD_DCtx_setParameter(context_, ZSTD_d_windowLogMax, static_cast<int>(window_log));
    }
  }
  ~ZstdFrameDecoder() { ZSTD_freeDCtx(context_); }
  ZstdFrameDecoder(const ZstdFrameDecoder&) = delete;
  ZstdFrameDecoder& operator=(const ZstdFrameDecoder&) = delete;

  StepResult step(const std::uint8_t* in, std::size_t& in_pos, std::size_t in_size,
                  std::uint8_t* out, std::size_t& out_pos, std::size_t out_size) {
    if (context_ == nullptr) return {"cannot create a zstd decompression context", false};
    ZSTD_inBuffer input{in, in_size, in_pos};
    ZSTD_outBuffer output{out, out_size, out_pos};
    const std::size_t hint = ZSTD_decompressStream(context_, &output, &input);
    if (ZSTD_isError(hint)) return {ZSTD_getErrorName(hint), false};
    in_pos = input.pos;
    out_pos = output.pos;
    return {"", hint == 0};
  }

 private:
  ZSTD_DCtx* context_;
};

// Runs `decoder` over the whole input, growing `out` with what it produces, to at most
// uncompressed_size + 1 bytes (the extra byte shows a chunk that decodes to more than it says).
template <typename Decoder>
std::string decode_all(Decoder& decoder, const std::string& name, const std::uint8_t* data,
                       std::size_t size, std::uint64_t uncompressed_size, Bytes& out) {
  const std::uint64_t room = uncompressed_size + 1;
  const auto too_long = [&] {
    return name + " data decompresses to more than the chunk's uncompressed_size of " +
           std::to_string(uncompressed_size) + " bytes";
  };
  out.resize(static_cast<std::size_t>(std::min(room, kFirstOutputSize)));
  std::size_t in_pos = 0;
  std::size_t out_pos = 0;
  bool frame_done = false;
  while (in_pos < size || !frame_done) {
    if (out_pos == out.size()) {
      if (out.size() == room) return too_long();
      out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(room, 2 * out.size())));
    }
    const std::size_t in_before = in_pos;
    const std::size_t out_before = out_pos;
    const StepResult result = decoder.step(data, in_pos, size, out.data(), out_pos, out.size());
    if (!result.error.empty()) return name + " data is damaged (" + result.error + ")";
    frame_done = result.frame_done;
    if (in_pos == in_before && out_pos == out_before) {  // the decoder wants what is not there
      if (in_pos < size) {
        return name + " data is damaged (decoding stops at byte " + std::to_string(in_pos) +
               " of " + std::to_string(size) + ")";
      }
      return name + " data ends inside a frame (cut short) after " + std::to_string(size) +
             " bytes";
    }
  }
  out.resize(out_pos);
  if (out_pos > uncompressed_size) return too_long();
  if (out_pos != uncompressed_size) {
    return name + " data decompresses to " + std::to_string(out_pos) +
           " bytes, the chunk's uncompressed_size says " + std::to_string(uncompressed_size);
  }
  return "";
}

Bytes compress_lz4(const std::uint8_t* data, std::size_t size) {
  LZ4F_preferences_t preferences{};
  preferences.frameInfo.contentSize = size;  // lets a reader check the length before decoding
  Bytes out(LZ4F_compressFrameBound(size, &preferences));
  const std::size_t written = LZ4F_compressFrame(out.data(), out.size(), data, size, &preferences);
  if (LZ4F_isError(written)) {
    throw std::runtime_error(std::string("lz4 compression failed: ") + LZ4F_getErrorName(written));
  }
  out.resize(written);
  return out;
}

Bytes compress_zstd(const std::uint8_t* data, std::size_t size) {
  Bytes out(ZSTD_compressBound(size));
  const std::size_t written = ZSTD_compress(out.data(), out.size(), data, size, kZstdLevel);
  if (ZSTD_isError(written)) {
    throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(written));
  }
  out.resize(written);
  return out;
}

}  // namespace

const std::vector<std::string>& mcap_compression_names() {
  static const std::vector<std::string> kNames{"none", "lz4", "zstd"};
  return kNames;
}

std::optional<McapCompression> parse_mcap_compression(const std::string& name) {
  if (name == "none") return McapCompression::kNone;
  if (name == "lz4") return McapCompression::kLz4;
  if (name == "zstd") return McapCompression::kZstd;
  return std::nullopt;
}

std::string mcap_compression_name(McapCompression compression) {
  const std::string field = mcap_chunk_compression_field(compression);
  return field.empty() ? "none" : field;
}

std::string mcap_chunk_compression_field(McapCompression compression) {
  switch (compression) {
    case McapCompression::kLz4:
      return "lz4";
    case McapCompression::kZstd:
      return "zstd";
    case McapCompression::kNone:
      break;
  }
  return "";
}

Bytes compress_chunk_records(McapCompression compression, const std::uint8_t* data,
                             std::size_t size) {
  switch (compression) {
    case McapCompression::kLz4:
      return compress_lz4(data, size);
    case McapCompression::kZstd:
      return compress_zstd(data, size);
    case McapCompression::kNone:
      break;
  }
  return Bytes(data, data + size);
}

bool can_decompress_chunk(const std::string& compression) {
  return compression == "lz4" || compression == "zstd";
}

std::string decompress_chunk_records(const std::string& compression, const std::uint8_t* data,
                                     std::uint64_t size, std::uint64_t uncompressed_size,
                                     Bytes& out) {
  out.clear();
  const bool lz4 = compression == "lz4";
  if (!lz4 && compression != "zstd") return "compression \"" + compression + "\" is not supported";
  const std::uint64_t max_ratio = lz4 ? kLz4MaxRatio : kZstdMaxRatio;
  if (uncompressed_size > kMaxUncompressedChunkSize) {
    return "its uncompressed_size of " + std::to_string(uncompressed_size) +
           " bytes is over the limit of " + std::to_string(kMaxUncompressedChunkSize);
  }
  if (uncompressed_size / max_ratio > size) {
    return "its uncompressed_size of " + std::to_string(uncompressed_size) +
           " bytes is more than " + compression + " can make of " + std::to_string(size) + " bytes";
  }
  // Both bounds above keep these sizes far below what a size_t holds.
  const auto in_size = static_cast<std::size_t>(size);
  if (lz4) {
    Lz4FrameDecoder decoder;
    return decode_all(decoder, compression, data, in_size, uncompressed_size, out);
  }
  ZstdFrameDecoder decoder(uncompressed_size);
  return decode_all(decoder, compression, data, in_size, uncompressed_size, out);
}

}  // namespace uavslam::io
