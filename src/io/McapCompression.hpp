// The compression of an MCAP Chunk's records field (spec "Chunk" and "Supported Compression
// Formats"): "" (none), "lz4" (one or more LZ4 frames, lz4frame.h; not the raw block format)
// and "zstd" (one or more Zstandard frames). McapWriter compresses, McapReader decompresses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uavslam::io {

enum class McapCompression { kNone, kLz4, kZstd };

// The names people type (--compression, YAML): "none", "lz4", "zstd".
const std::vector<std::string>& mcap_compression_names();
// "none" -> kNone, ...; nullopt for any other text.
std::optional<McapCompression> parse_mcap_compression(const std::string& name);
// The name as people type it: kNone -> "none".
std::string mcap_compression_name(McapCompression compression);
// The Chunk record's compression field: kNone -> "" (spec), kLz4 -> "lz4", kZstd -> "zstd".
std::string mcap_chunk_compression_field(McapCompression compression);

// `size` bytes compressed as one frame. std::runtime_error if the library fails (out of memory).
std::vector<std::uint8_t> compress_chunk_records(McapCompression compression,
                                                 const std::uint8_t* data, std::size_t size);

// The largest uncompressed_size a reader accepts for a compressed chunk: 256 MiB, far above any
// writer's chunks (ours are 1 MiB, the mcap CLI's 4 MiB) and below what a fuzzer's memory limit
// allows.
inline constexpr std::uint64_t kMaxUncompressedChunkSize = 256ull << 20;

// Decompresses the `size` bytes of a Chunk's records field compressed with `compression` (the
// field's text: "lz4" or "zstd") into `out`, which must come out exactly `uncompressed_size`
// bytes long. Never allocates from the claim alone: `out` grows with what the data really
// decompresses to, up to uncompressed_size. Returns "" or why the chunk cannot be used (a claim
// over kMaxUncompressedChunkSize or over what the format can reach from `size` bytes, damaged or
// cut-short data, a length other than uncompressed_size).
std::string decompress_chunk_records(const std::string& compression, const std::uint8_t* data,
                                     std::uint64_t size, std::uint64_t uncompressed_size,
                                     std::vector<std::uint8_t>& out);

// True for the compression fields decompress_chunk_records() knows: "lz4" and "zstd".
bool can_decompress_chunk(const std::string& compression);

}  // namespace uavslam::io
