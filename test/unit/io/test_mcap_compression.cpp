// Compressed MCAP chunks (src/io/McapCompression, McapWriter, McapReader): "lz4" (LZ4 frames)
// and "zstd" (Zstandard frames) written and read back through both readers, the Chunk record's
// bytes decoded with the stock lz4/zstd libraries, and damaged or lying chunks reported at their
// offset with every message before them kept.
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/Mcap.hpp"
#include "io/McapCompression.hpp"
#include "io/McapReader.hpp"
#include "io/McapWriter.hpp"
#include "io/RollingMcapWriter.hpp"
#include "unit/io/McapReadAll.hpp"

namespace uavslam::io {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::indexed_from;
using test::is_subsequence;
using test::same;
using test::stream_all;
using ::testing::AnyOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Chunk record (spec "Chunk"): prefix 9, message_start_time 8, message_end_time 8,
// uncompressed_size 8, uncompressed_crc 4, compression 4 + N, records length 8, records.
constexpr std::uint64_t kUncompressedSizeAt = 9 + 8 + 8;
constexpr std::uint64_t kCrcAt = kUncompressedSizeAt + 8;
constexpr std::uint64_t kCompressionAt = kCrcAt + 4;

Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

std::uint64_t read_le(const Bytes& bytes, std::uint64_t at, int size) {
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) value |= std::uint64_t{bytes.at(at + i)} << (8 * i);
  return value;
}

void write_le(Bytes& bytes, std::uint64_t at, std::uint64_t value, int size) {
  for (int i = 0; i < size; ++i) bytes.at(at + i) = static_cast<std::uint8_t>(value >> (8 * i));
}

// The fields of the Chunk record at `at` in a file's bytes.
struct ChunkBytes {
  std::string compression;
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::uint64_t records_at = 0;  // file offset of the records field's bytes
  Bytes records;
};

ChunkBytes chunk_at(const Bytes& file, std::uint64_t at) {
  ChunkBytes chunk;
  chunk.uncompressed_size = read_le(file, at + kUncompressedSizeAt, 8);
  chunk.uncompressed_crc = static_cast<std::uint32_t>(read_le(file, at + kCrcAt, 4));
  const std::uint64_t name_size = read_le(file, at + kCompressionAt, 4);
  const auto name = file.begin() + static_cast<std::ptrdiff_t>(at + kCompressionAt + 4);
  chunk.compression.assign(name, name + static_cast<std::ptrdiff_t>(name_size));
  const std::uint64_t size_at = at + kCompressionAt + 4 + name_size;
  chunk.records_at = size_at + 8;
  const auto begin = file.begin() + static_cast<std::ptrdiff_t>(chunk.records_at);
  chunk.records.assign(begin, begin + static_cast<std::ptrdiff_t>(read_le(file, size_at, 8)));
  return chunk;
}

bool equal(const std::vector<mcap::Message>& a, const std::vector<mcap::Message>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same);
}

// `count` messages on two channels, payloads like a laser scan's (slowly varying ranges, so
// they compress), log times 1e9 + 1000 i ns; a chunk every `per_chunk` messages.
std::vector<mcap::Message> write_sample(const std::string& path, McapCompression compression,
                                        int count, int per_chunk) {
  McapWriterOptions options;
  options.compression = compression;
  McapWriter writer(path, options);
  const std::uint16_t schema = writer.add_schema("uavslam::msg::LaserScan", "omgidl",
                                                 "struct LaserScan { sequence<float> r; };");
  const std::uint16_t channels[] = {writer.add_channel(schema, "/scan", "cdr"),
                                    writer.add_channel(schema, "/scan2", "cdr", {{"k", "v"}})};
  std::mt19937 random(7);
  std::vector<mcap::Message> written;
  for (int i = 0; i < count; ++i) {
    mcap::Message m;
    m.channel_id = channels[i % 2];
    m.sequence = static_cast<std::uint32_t>(i);
    m.log_time = 1'000'000'000ull + 1000ull * static_cast<std::uint64_t>(i);
    m.publish_time = m.log_time - 5;
    m.data.resize(200 + random() % 200);
    for (std::size_t k = 0; k < m.data.size(); ++k) {
      m.data[k] = static_cast<std::uint8_t>(k / 16 + (k % 8 == 0 ? random() % 4 : 0));
    }
    writer.write(m.channel_id, m.sequence, m.log_time, m.publish_time, m.data.data(),
                 m.data.size());
    written.push_back(m);
    if ((i + 1) % per_chunk == 0) writer.flush();
  }
  writer.close();
  return written;
}

// The records field of a Chunk, decoded with the stock library, one frame after another.
Bytes lz4_frame_decode(const Bytes& compressed) {
  LZ4F_dctx* context = nullptr;
  EXPECT_FALSE(LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION)));
  Bytes out;
  std::size_t at = 0;
  std::uint8_t buffer[4096];
  std::size_t hint = 1;
  while (at < compressed.size() && hint != 0) {
    std::size_t written = sizeof(buffer);
    std::size_t read = compressed.size() - at;
    hint = LZ4F_decompress(context, buffer, &written, compressed.data() + at, &read, nullptr);
    EXPECT_FALSE(LZ4F_isError(hint)) << LZ4F_getErrorName(hint);
    if (LZ4F_isError(hint)) break;
    at += read;
    out.insert(out.end(), buffer, buffer + written);
  }
  LZ4F_freeDecompressionContext(context);
  EXPECT_EQ(hint, 0u) << "the lz4 frame is not complete";
  return out;
}

Bytes zstd_decode(const Bytes& compressed, std::uint64_t size) {
  Bytes out(size);
  const std::size_t n =
      ZSTD_decompress(out.data(), out.size(), compressed.data(), compressed.size());
  EXPECT_FALSE(ZSTD_isError(n)) << ZSTD_getErrorName(n);
  out.resize(ZSTD_isError(n) ? 0 : n);
  return out;
}

const McapCompression kCompressions[] = {McapCompression::kNone, McapCompression::kLz4,
                                         McapCompression::kZstd};
const McapCompression kCompressed[] = {McapCompression::kLz4, McapCompression::kZstd};

class McapCompressionTest : public test::TempDirTest {};

// --- Names -------------------------------------------------------------------------------------

TEST(McapCompressionNames, AreTheOnesPeopleTypeAndTheSpecsFields) {
  EXPECT_EQ(mcap_compression_names(), (std::vector<std::string>{"none", "lz4", "zstd"}));
  for (const std::string& name : mcap_compression_names()) {
    const auto compression = parse_mcap_compression(name);
    ASSERT_TRUE(compression.has_value()) << name;
    EXPECT_EQ(mcap_compression_name(*compression), name);
  }
  EXPECT_FALSE(parse_mcap_compression("LZ4").has_value());
  EXPECT_FALSE(parse_mcap_compression("").has_value());
  EXPECT_EQ(mcap_chunk_compression_field(McapCompression::kNone), "");
  EXPECT_EQ(mcap_chunk_compression_field(McapCompression::kLz4), "lz4");
  EXPECT_EQ(mcap_chunk_compression_field(McapCompression::kZstd), "zstd");
}

// --- Round trips -------------------------------------------------------------------------------

TEST_F(McapCompressionTest, BothReadersReturnEveryMessage) {
  for (const McapCompression compression : kCompressions) {
    SCOPED_TRACE(mcap_compression_name(compression));
    const std::string file = path("round.mcap");
    const auto written = write_sample(file, compression, 300, 40);
    McapReadReport report;
    EXPECT_TRUE(equal(stream_all(file, &report), written));
    EXPECT_TRUE(report.complete) << report.problem;
    EXPECT_TRUE(report.skipped.empty());
    EXPECT_TRUE(equal(indexed_from(file, 0, &report), written));
    EXPECT_TRUE(report.complete) << report.problem;
    EXPECT_TRUE(report.skipped.empty());
  }
}

TEST_F(McapCompressionTest, ChunkAndChunkIndexSayTheCompressionAndSizes) {
  for (const McapCompression compression : kCompressions) {
    SCOPED_TRACE(mcap_compression_name(compression));
    const std::string file = path("sizes.mcap");
    write_sample(file, compression, 100, 30);
    const Bytes bytes = read_file(file);
    McapIndexedReader reader(file);
    ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
    ASSERT_EQ(reader.chunk_indexes().size(), 4u);
    for (const mcap::ChunkIndex& index : reader.chunk_indexes()) {
      const ChunkBytes chunk = chunk_at(bytes, index.chunk_start_offset);
      EXPECT_EQ(chunk.compression, mcap_chunk_compression_field(compression));
      EXPECT_EQ(index.compression, chunk.compression);
      EXPECT_EQ(index.compressed_size, chunk.records.size());
      EXPECT_EQ(index.uncompressed_size, chunk.uncompressed_size);
      EXPECT_EQ(index.chunk_length,
                chunk.records_at + chunk.records.size() - index.chunk_start_offset);
      if (compression != McapCompression::kNone) {
        EXPECT_LT(index.compressed_size, index.uncompressed_size / 2)
            << "scan-like data compresses";
      }
    }
  }
}

TEST_F(McapCompressionTest, IndexedReadFromALogTimeReadsTheLaterMessages) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    const std::string file = path("seek.mcap");
    const auto written = write_sample(file, compression, 200, 25);
    for (const std::uint64_t start :
         {0ull, 1'000'050'000ull, 1'000'100'500ull, 1'000'199'000ull, 1'000'199'001ull}) {
      std::vector<mcap::Message> expected;
      std::copy_if(written.begin(), written.end(), std::back_inserter(expected),
                   [&](const mcap::Message& m) { return m.log_time >= start; });
      McapReadReport report;
      EXPECT_TRUE(equal(indexed_from(file, start, &report), expected)) << "from " << start;
      EXPECT_TRUE(report.complete) << report.problem;
    }
  }
}

TEST_F(McapCompressionTest, RollingWriterCompressesEveryFile) {
  std::vector<std::uint8_t> payload(300);
  for (std::size_t k = 0; k < payload.size(); ++k) payload[k] = static_cast<std::uint8_t>(k / 8);
  for (const McapCompression compression : kCompressions) {
    SCOPED_TRACE(mcap_compression_name(compression));
    RollingMcapOptions options;
    options.compression = compression;
    options.sync_on_flush = false;
    options.max_file_bytes = 4000;
    const std::string base = path(mcap_compression_name(compression) + ".mcap");
    std::vector<std::string> files;
    {
      RollingMcapWriter recording(base, options);
      const std::size_t topic = recording.add_topic("scan", "m::Scan", "struct Scan {};");
      for (std::uint64_t i = 0; i < 300; ++i) {
        recording.write(topic, 1000 + i, 1000 + i, payload.data(), payload.size());
        if (i % 10 == 9) recording.flush();
      }
      recording.close();
      files = recording.files();
    }
    ASSERT_GE(files.size(), 2u);
    std::size_t messages = 0;
    for (const std::string& file : files) {
      McapIndexedReader reader(file);
      ASSERT_TRUE(reader.has_summary()) << file << ": " << reader.summary_problem();
      for (const mcap::ChunkIndex& index : reader.chunk_indexes()) {
        EXPECT_EQ(index.compression, mcap_chunk_compression_field(compression)) << file;
      }
      McapReadReport report;
      messages += stream_all(file, &report).size();
      EXPECT_TRUE(report.complete) << file << ": " << report.problem;
    }
    EXPECT_EQ(messages, 300u);
  }
}

// --- The Chunk's bytes, decoded with the stock libraries ----------------------------------------

TEST_F(McapCompressionTest, ChunkRecordsDecodeWithTheStockLibrariesToTheUncompressedRecords) {
  write_sample(path("none.mcap"), McapCompression::kNone, 3, 3);
  write_sample(path("lz4.mcap"), McapCompression::kLz4, 3, 3);
  write_sample(path("zstd.mcap"), McapCompression::kZstd, 3, 3);
  const auto first_chunk = [&](const std::string& file) {
    McapIndexedReader reader(path(file));
    EXPECT_EQ(reader.chunk_indexes().size(), 1u);
    return chunk_at(read_file(path(file)), reader.chunk_indexes().at(0).chunk_start_offset);
  };
  const ChunkBytes none = first_chunk("none.mcap");
  const ChunkBytes lz4 = first_chunk("lz4.mcap");
  const ChunkBytes zstd = first_chunk("zstd.mcap");
  ASSERT_EQ(none.compression, "");
  ASSERT_EQ(lz4.compression, "lz4");
  ASSERT_EQ(zstd.compression, "zstd");
  // The LZ4 frame magic 0x184D2204 and the zstd frame magic 0xFD2FB528, little-endian.
  EXPECT_EQ(read_le(lz4.records, 0, 4), 0x184D2204u);
  EXPECT_EQ(read_le(zstd.records, 0, 4), 0xFD2FB528u);
  EXPECT_EQ(lz4_frame_decode(lz4.records), none.records);
  EXPECT_EQ(zstd_decode(zstd.records, none.records.size()), none.records);
  for (const ChunkBytes* chunk : {&lz4, &zstd}) {
    EXPECT_EQ(chunk->uncompressed_size, none.records.size());
    EXPECT_EQ(chunk->uncompressed_crc, none.uncompressed_crc);
    EXPECT_EQ(chunk->uncompressed_crc,
              mcap::crc32_update(0, none.records.data(), none.records.size()));
  }
}

// --- Damage --------------------------------------------------------------------------------------

// A file of three compressed chunks of 30 messages each, to damage.
class McapCompressionDamageTest : public McapCompressionTest {
 protected:
  void write_good(McapCompression compression) {
    name_ = mcap_chunk_compression_field(compression);
    written_ = write_sample(path("good.mcap"), compression, 90, 30);
    bytes_ = read_file(path("good.mcap"));
    McapIndexedReader reader(path("good.mcap"));
    ASSERT_EQ(reader.chunk_indexes().size(), 3u);
    second_at_ = reader.chunk_indexes()[1].chunk_start_offset;
    second_ = chunk_at(bytes_, second_at_);
    first_messages_.assign(written_.begin(), written_.begin() + 30);
  }

  // Both readers on `damaged`: they keep the first chunk's 30 messages and stop at the second
  // chunk, naming its offset and `problem`.
  void expect_stop_at_second_chunk(const Bytes& damaged, const std::string& problem) {
    write_file(path("bad.mcap"), damaged);
    McapReadReport report;
    EXPECT_TRUE(equal(stream_all(path("bad.mcap"), &report), first_messages_));
    EXPECT_FALSE(report.complete);
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_THAT(report.problem, HasSubstr("at byte " + std::to_string(second_at_)));
    EXPECT_THAT(report.problem, HasSubstr(problem));
    EXPECT_TRUE(equal(indexed_from(path("bad.mcap"), 0, &report), first_messages_));
    EXPECT_FALSE(report.complete);
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_THAT(report.problem, HasSubstr("at byte " + std::to_string(second_at_)));
    EXPECT_THAT(report.problem, HasSubstr(problem));
  }

  std::string name_;  // the Chunk's compression field
  std::vector<mcap::Message> written_;
  std::vector<mcap::Message> first_messages_;
  Bytes bytes_;
  std::uint64_t second_at_ = 0;
  ChunkBytes second_;
};

TEST_F(McapCompressionDamageTest, AFlippedByteInTheCompressedRecordsStopsAtTheChunk) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    // In the compressed data itself, past the frame header: lz4 may decode it to other bytes
    // (the CRC says so), zstd may refuse it; either way the chunk is reported, not trusted.
    Bytes damaged = bytes_;
    damaged[second_.records_at + second_.records.size() / 2] ^= 0x5A;
    write_file(path("bad.mcap"), damaged);
    const std::string chunk_problem = "Chunk at byte " + std::to_string(second_at_) + " (";
    const std::string crc_problem = "chunk CRC mismatch at byte " + std::to_string(second_at_);
    McapReadReport report;
    EXPECT_TRUE(equal(stream_all(path("bad.mcap"), &report), first_messages_));
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_THAT(report.problem, AnyOf(StartsWith(chunk_problem), StartsWith(crc_problem)));
    EXPECT_TRUE(equal(indexed_from(path("bad.mcap"), 0, &report), first_messages_));
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_THAT(report.problem, AnyOf(StartsWith(chunk_problem), StartsWith(crc_problem)));
  }
}

TEST_F(McapCompressionDamageTest, AWrongUncompressedCrcIsAMismatch) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    Bytes damaged = bytes_;
    damaged[second_at_ + kCrcAt] ^= 0x01;
    expect_stop_at_second_chunk(damaged, "chunk CRC mismatch at byte");
  }
}

TEST_F(McapCompressionDamageTest, AWrongUncompressedSizeIsReported) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    const std::uint64_t size = second_.uncompressed_size;
    Bytes damaged = bytes_;
    write_le(damaged, second_at_ + kUncompressedSizeAt, size + 1, 8);
    expect_stop_at_second_chunk(damaged, "data decompresses to " + std::to_string(size) +
                                             " bytes, the chunk's uncompressed_size says " +
                                             std::to_string(size + 1));
    write_le(damaged, second_at_ + kUncompressedSizeAt, size - 1, 8);
    expect_stop_at_second_chunk(damaged,
                                "data decompresses to more than the chunk's "
                                "uncompressed_size of " +
                                    std::to_string(size - 1) + " bytes");
  }
}

// A claim over the cap, or of more than the format can make of the bytes, allocates nothing.
TEST_F(McapCompressionDamageTest, AnImpossibleUncompressedSizeIsRefusedBeforeDecoding) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    Bytes damaged = bytes_;
    write_le(damaged, second_at_ + kUncompressedSizeAt, 1ull << 60, 8);
    expect_stop_at_second_chunk(
        damaged, "is over the limit of " + std::to_string(kMaxUncompressedChunkSize));
    const std::uint64_t compressed = second_.records.size();
    ASSERT_LT(compressed * 33'000, kMaxUncompressedChunkSize);
    write_le(damaged, second_at_ + kUncompressedSizeAt, compressed * 33'000, 8);
    expect_stop_at_second_chunk(damaged, " bytes is more than " + name_ + " can make of " +
                                             std::to_string(compressed) + " bytes");
  }
}

TEST_F(McapCompressionDamageTest, CompressedDataCutShortIsReported) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    // The Chunk's records field loses its last 8 bytes, the record's lengths made to agree:
    // the frame itself ends early.
    const std::uint64_t end = second_.records_at + second_.records.size();
    Bytes damaged(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(end - 8));
    damaged.insert(damaged.end(), bytes_.begin() + static_cast<std::ptrdiff_t>(end), bytes_.end());
    write_le(damaged, second_at_ + 1, read_le(bytes_, second_at_ + 1, 8) - 8, 8);
    write_le(damaged, second_.records_at - 8, second_.records.size() - 8, 8);
    write_file(path("bad.mcap"), damaged);
    McapReadReport report;
    EXPECT_TRUE(equal(stream_all(path("bad.mcap"), &report), first_messages_));
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_EQ(report.problem, "Chunk at byte " + std::to_string(second_at_) + " (" + name_ +
                                  "): " + name_ + " data ends inside a frame (cut short) after " +
                                  std::to_string(second_.records.size() - 8) + " bytes");
  }
}

TEST_F(McapCompressionDamageTest, AFileCutInsideACompressedChunkKeepsTheChunksBefore) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    const Bytes cut(bytes_.begin(),
                    bytes_.begin() + static_cast<std::ptrdiff_t>(second_.records_at + 10));
    write_file(path("cut.mcap"), cut);
    McapReadReport report;
    EXPECT_TRUE(equal(stream_all(path("cut.mcap"), &report), first_messages_));
    EXPECT_EQ(report.stopped_at, second_at_);
    EXPECT_THAT(report.problem, StartsWith("truncated inside a Chunk record at byte " +
                                           std::to_string(second_at_)));
    McapIndexedReader indexed(path("cut.mcap"));
    EXPECT_FALSE(indexed.has_summary());
    EXPECT_TRUE(equal(indexed_from(path("cut.mcap"), 0, &report), first_messages_));
    EXPECT_EQ(report.stopped_at, second_at_);
  }
}

TEST_F(McapCompressionDamageTest, AnUnknownCompressionIsSkippedAndReported) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    write_good(compression);
    Bytes damaged = bytes_;
    damaged[second_.records_at - 9] = 'X';  // the compression's last letter: "lzX", "zstX"
    write_file(path("bad.mcap"), damaged);
    std::vector<mcap::Message> expected = first_messages_;
    expected.insert(expected.end(), written_.begin() + 60, written_.end());
    const std::string skipped = "Chunk at byte " + std::to_string(second_at_) + ": compression \"" +
                                name_.substr(0, name_.size() - 1) +
                                "X\" is not supported, its messages were skipped";
    McapReadReport report;
    EXPECT_TRUE(equal(indexed_from(path("bad.mcap"), 0, &report), expected));
    EXPECT_TRUE(report.complete) << report.problem;
    EXPECT_THAT(report.skipped, ::testing::ElementsAre(skipped));
    // The stream reader skips it too, then finds the data section's CRC changed.
    EXPECT_TRUE(equal(stream_all(path("bad.mcap"), &report), expected));
    EXPECT_THAT(report.skipped, ::testing::ElementsAre(skipped));
    EXPECT_THAT(report.problem, HasSubstr("data section CRC mismatch"));
  }
}

// Whatever byte is flipped, neither reader crashes or makes up a message.
TEST_F(McapCompressionTest, EveryFlippedByteIsSafe) {
  for (const McapCompression compression : kCompressed) {
    SCOPED_TRACE(mcap_compression_name(compression));
    const auto written = write_sample(path("small.mcap"), compression, 6, 2);
    const Bytes bytes = read_file(path("small.mcap"));
    for (std::uint64_t at = 0; at < bytes.size(); ++at) {
      Bytes copy = bytes;
      copy[at] ^= 0xFF;
      write_file(path("flip.mcap"), copy);
      McapReadReport report;
      const auto streamed = stream_all(path("flip.mcap"), &report);
      ASSERT_FALSE(report.complete) << "byte " << at << " flipped";
      ASSERT_TRUE(is_subsequence(streamed, written)) << "byte " << at << " flipped";
      ASSERT_TRUE(is_subsequence(indexed_from(path("flip.mcap"), 0), written))
          << "byte " << at << " flipped";
    }
  }
}

}  // namespace
}  // namespace uavslam::io
