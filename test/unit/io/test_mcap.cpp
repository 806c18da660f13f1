// MCAP writer and readers (src/io/McapWriter, src/io/McapReader) against the format
// specification (https://mcap.dev/spec): record bytes computed by hand from the spec's tables,
// CRCs recomputed independently, round trips, the summary against the data, indexed seeks, and
// files cut short or damaged at every byte.
#include <signal.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "TempDirTest.hpp"
#include "io/Mcap.hpp"
#include "io/McapReader.hpp"
#include "io/McapWriter.hpp"
#include "unit/io/McapReadAll.hpp"

namespace uavslam::io {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::indexed_from;
using test::is_subsequence;
using test::same;
using test::stream_all;
using ::testing::HasSubstr;

// --- Bytes, built by hand as the spec's "Serialization" section says -------------------------

void le(Bytes& out, std::uint64_t value, int size) {
  ASSERT_LE(size, 8);
  std::uint8_t bytes[8] = {};
  for (int i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(value >> (8 * i));
  out.insert(out.end(), bytes, bytes + size);
}

Bytes str(const std::string& text) {
  Bytes out;
  le(out, text.size(), 4);
  for (const char c : text) out.push_back(static_cast<std::uint8_t>(c));
  return out;
}

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

Bytes record(std::uint8_t opcode, const Bytes& content) {
  Bytes out{opcode};
  le(out, content.size(), 8);
  return cat({out, content});
}

Bytes u(std::uint64_t value, int size) {
  Bytes out;
  le(out, value, size);
  return out;
}

std::uint64_t read_le(const Bytes& bytes, std::uint64_t at, int size) {
  std::uint64_t value = 0;
  for (int i = 0; i < size; ++i) value |= std::uint64_t{bytes.at(at + i)} << (8 * i);
  return value;
}

Bytes slice(const Bytes& bytes, std::uint64_t begin, std::uint64_t size) {
  return Bytes(bytes.begin() + static_cast<std::ptrdiff_t>(begin),
               bytes.begin() + static_cast<std::ptrdiff_t>(begin + size));
}

std::uint32_t crc_of(const Bytes& bytes, std::uint64_t begin, std::uint64_t end) {
  return mcap::crc32_update(0, bytes.data() + begin, end - begin);
}

const Bytes kMagic{0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};

Bytes magic_and_header() {
  return cat({kMagic, record(0x01, cat({str(""), str("test")}))});
}

// Data End with no CRC, a Footer without summary, the closing magic.
Bytes closing_without_summary() {
  return cat({record(0x0F, u(0, 4)), record(0x02, cat({u(0, 8), u(0, 8), u(0, 4)})), kMagic});
}

Bytes uncompressed_chunk(const Bytes& records, std::uint32_t crc) {
  return record(0x06, cat({u(1, 8), u(1, 8), u(records.size(), 8), u(crc, 4), str(""),
                           u(records.size(), 8), records}));
}

Bytes schema_record() {
  return record(0x03, cat({u(1, 2), str("m::S"), str("omgidl"), str("x")}));
}

Bytes channel_record() {
  return record(0x04, cat({u(1, 2), u(1, 2), str("/t"), str("cdr"), u(0, 4)}));
}

Bytes message_record(std::uint64_t log_time) {
  return record(0x05, cat({u(1, 2), u(0, 4), u(log_time, 8), u(log_time, 8), Bytes{1, 2, 3}}));
}

// --- Files -----------------------------------------------------------------------------------

Bytes read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

// True when `got` are the first got.size() messages of `all`.
bool is_prefix(const std::vector<mcap::Message>& got, const std::vector<mcap::Message>& all) {
  return got.size() <= all.size() && std::equal(got.begin(), got.end(), all.begin(), same);
}

// Writes `count` messages on three channels of two schemas (sizes 0..~300 bytes, log times
// increasing by 1000 ns from 1e9), flushing after every `flush_every`; returns them in order.
std::vector<mcap::Message> write_sample(const std::string& path, McapWriterOptions options,
                                        int count, int flush_every = 0) {
  McapWriter writer(path, options);
  const std::uint16_t scan = writer.add_schema("uavslam::msg::LaserScan", "omgidl",
                                               "module uavslam { module msg { struct LaserScan "
                                               "{ sequence<float> ranges; }; }; };");
  const std::uint16_t pose = writer.add_schema("uavslam::msg::Pose", "omgidl", "struct Pose {};");
  const std::uint16_t channels[] = {
      writer.add_channel(scan, "/scan", "cdr", {{"qos", "sensor"}}),
      writer.add_channel(pose, "/pose", "cdr"),
      writer.add_channel(scan, "/scan2", "cdr", {{"a", "1"}, {"b", "2"}}),
  };
  std::vector<mcap::Message> written;
  std::mt19937 random(42);
  for (int i = 0; i < count; ++i) {
    mcap::Message m;
    m.channel_id = channels[random() % 3];
    m.sequence = static_cast<std::uint32_t>(i);
    m.log_time = 1'000'000'000ull + 1000ull * static_cast<std::uint64_t>(i);
    m.publish_time = m.log_time - 17;
    m.data.resize(random() % 300);
    for (std::uint8_t& byte : m.data) byte = static_cast<std::uint8_t>(random());
    writer.write(m.channel_id, m.sequence, m.log_time, m.publish_time, m.data.data(),
                 m.data.size());
    written.push_back(m);
    if (flush_every > 0 && (i + 1) % flush_every == 0) writer.flush();
  }
  writer.close();
  return written;
}

// Chunk records start after the Chunk's prefix and fields (spec "Chunk").
constexpr std::uint64_t kChunkRecordsOffset = 9 + 8 + 8 + 8 + 4 + 4 + 8;

// Number of messages the Message Index records of one chunk list (spec "Message Index").
std::uint64_t indexed_message_count(const Bytes& file, const mcap::ChunkIndex& index) {
  std::uint64_t count = 0;
  for (const auto& [channel, offset] : index.message_index_offsets) {
    count += read_le(file, offset + 9 + 2, 4) / 16;
  }
  return count;
}

McapWriterOptions chunks_of(std::size_t size) {
  McapWriterOptions options;
  options.chunk_size = size;
  return options;
}

class McapTest : public test::TempDirTest {};

// --- Format ----------------------------------------------------------------------------------

TEST(McapCrc, MatchesTheStandardCheckValue) {
  const std::string text = "123456789";
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(text.data());
  EXPECT_EQ(mcap::crc32_update(0, bytes, text.size()), 0xCBF43926u);
  EXPECT_EQ(mcap::crc32_update(mcap::crc32_update(0, bytes, 4), bytes + 4, 5), 0xCBF43926u);
}

TEST(McapFormat, OpcodesAndMagicAreTheSpecs) {
  EXPECT_EQ(Bytes(std::begin(mcap::kMagic), std::end(mcap::kMagic)), kMagic);
  EXPECT_EQ(static_cast<int>(mcap::Opcode::kHeader), 0x01);
  EXPECT_EQ(static_cast<int>(mcap::Opcode::kChunk), 0x06);
  EXPECT_EQ(static_cast<int>(mcap::Opcode::kDataEnd), 0x0F);
  EXPECT_EQ(mcap::opcode_name(0x07), "Message Index");
  EXPECT_EQ(mcap::opcode_name(0x9A), "unknown (opcode 0x9A)");
}

// Every byte of a one-message file, from the spec's record tables.
TEST_F(McapTest, RecordsHaveTheSpecsBytes) {
  const std::string file = path("one.mcap");
  McapWriter writer(file);
  const std::uint16_t schema = writer.add_schema("m::S", "omgidl", "x");
  const std::uint16_t channel = writer.add_channel(schema, "/t", "cdr", {{"k", "v"}});
  const std::uint8_t data[] = {0xAA, 0xBB};
  writer.write(channel, 7, 0x0102030405060708ull, 0x1112131415161718ull, data, sizeof(data));
  writer.flush();
  const Bytes flushed = read_file(file);

  const Bytes header{0x01, 15, 0, 0, 0,   0,   0,   0,   0,  // opcode, u64 content length
                     0,    0,  0, 0,                         // profile ""
                     7,    0,  0, 0, 'u', 'a', 'v', 's', 'l', 'a', 'm'};
  const Bytes schema_bytes{0x03, 25, 0, 0, 0,   0,   0,   0,   0,   1,   0,    // id 1
                           4,    0,  0, 0, 'm', ':', ':', 'S',                 // name
                           6,    0,  0, 0, 'o', 'm', 'g', 'i', 'd', 'l',       // encoding
                           1,    0,  0, 0, 'x'};                               // data
  const Bytes channel_bytes{0x04, 31, 0, 0, 0,   0,   0,   0, 0, 1,  0, 1, 0,  // id 1, schema 1
                            2,    0,  0, 0, '/', 't',                          // topic
                            3,    0,  0, 0, 'c', 'd', 'r',                     // message_encoding
                            10,   0,  0, 0,                                    // map: 10 bytes
                            1,    0,  0, 0, 'k', 1,   0,   0, 0, 'v'};
  const Bytes message_bytes{0x05, 24,   0,    0,    0,    0,    0,    0,    0,  // 22 + 2 bytes
                            1,    0,    7,    0,    0,    0,                    // channel, seq
                            8,    7,    6,    5,    4,    3,    2,    1,        // log_time
                            0x18, 0x17, 0x16, 0x15, 0x14, 0x13, 0x12, 0x11,     // publish_time
                            0xAA, 0xBB};
  const Bytes records = cat({schema_bytes, channel_bytes, message_bytes});
  ASSERT_EQ(records.size(), 107u);
  const Bytes chunk =
      cat({Bytes{0x06, 147, 0, 0, 0, 0, 0, 0, 0},                        // 40 bytes of fields + 107
           Bytes{8, 7, 6, 5, 4, 3, 2, 1},                                // message_start_time
           Bytes{8, 7, 6, 5, 4, 3, 2, 1},                                // message_end_time
           Bytes{107, 0, 0, 0, 0, 0, 0, 0},                              // uncompressed_size
           u(crc_of(records, 0, records.size()), 4), Bytes{0, 0, 0, 0},  // compression ""
           Bytes{107, 0, 0, 0, 0, 0, 0, 0}, records});
  const Bytes message_index{0x07, 22, 0, 0, 0, 0, 0, 0, 0, 1, 0,  // channel 1
                            16,   0,  0, 0,                       // array: 16 bytes
                            8,    7,  6, 5, 4, 3, 2, 1,           // log_time
                            74,   0,  0, 0, 0, 0, 0, 0};          // offset 34 + 40 in the chunk
  EXPECT_EQ(flushed, cat({kMagic, header, chunk, message_index}));

  writer.close();
  const Bytes closed = read_file(file);
  ASSERT_EQ(slice(closed, 0, flushed.size()), flushed);
  const Bytes data_end = cat({Bytes{0x0F, 4, 0, 0, 0, 0, 0, 0, 0}, u(crc_of(flushed, 0, 219), 4)});
  EXPECT_EQ(slice(closed, 219, 13), data_end);
  EXPECT_EQ(slice(closed, closed.size() - 8, 8), kMagic);
  const std::uint64_t footer_at = closed.size() - 8 - 29;
  EXPECT_EQ(slice(closed, footer_at, 9), (Bytes{0x02, 20, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(read_le(closed, footer_at + 9, 8), 232u);  // summary_start: just after the Data End
}

TEST_F(McapTest, WrittenCrcsMatchARecomputation) {
  const std::string file = path("crc.mcap");
  write_sample(file, chunks_of(2000), 100);
  const Bytes bytes = read_file(file);
  const std::uint64_t footer_at = bytes.size() - 8 - 29;
  const std::uint64_t summary_start = read_le(bytes, footer_at + 9, 8);
  const std::uint64_t data_end_at = summary_start - 13;
  ASSERT_EQ(bytes[data_end_at], 0x0F);
  EXPECT_EQ(read_le(bytes, data_end_at + 9, 4), crc_of(bytes, 0, data_end_at));
  EXPECT_EQ(read_le(bytes, footer_at + 9 + 16, 4), crc_of(bytes, summary_start, footer_at + 25));
  McapIndexedReader reader(file);
  ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
  ASSERT_GT(reader.chunk_indexes().size(), 3u);
  for (const mcap::ChunkIndex& index : reader.chunk_indexes()) {
    const std::uint64_t at = index.chunk_start_offset;
    const std::uint64_t records = at + kChunkRecordsOffset;
    EXPECT_EQ(read_le(bytes, at + 9 + 24, 4), crc_of(bytes, records, at + index.chunk_length));
  }
}

// --- Round trip, summary, seek ---------------------------------------------------------------

TEST_F(McapTest, ManyMessagesRoundTripAcrossChunksAndChannels) {
  const std::string file = path("many.mcap");
  const auto written = write_sample(file, chunks_of(4096), 2000, 333);
  McapStreamReader reader(file);
  std::vector<mcap::Message> read;
  mcap::Message message;
  while (reader.next(message)) read.push_back(message);
  EXPECT_TRUE(reader.report().complete) << reader.report().problem;
  EXPECT_TRUE(reader.report().skipped.empty());
  EXPECT_EQ(reader.report().stopped_at, read_file(file).size());
  ASSERT_EQ(read.size(), written.size());
  EXPECT_TRUE(std::equal(read.begin(), read.end(), written.begin(), same));
  EXPECT_EQ(reader.header().library, "uavslam");
  EXPECT_EQ(reader.header().profile, "");
  ASSERT_EQ(reader.channels().size(), 3u);
  EXPECT_EQ(reader.channels().at(3).topic, "/scan2");
  EXPECT_EQ(reader.channels().at(3).schema_id, 1);
  EXPECT_EQ(reader.channels().at(3).metadata.at("b"), "2");
  EXPECT_EQ(reader.schemas().at(2).name, "uavslam::msg::Pose");
  EXPECT_EQ(reader.schemas().at(2).data, "struct Pose {};");
}

TEST_F(McapTest, SummaryAgreesWithTheData) {
  const std::string file = path("summary.mcap");
  const auto written = write_sample(file, chunks_of(3000), 500);
  const Bytes bytes = read_file(file);
  McapIndexedReader reader(file);
  ASSERT_TRUE(reader.has_summary()) << reader.summary_problem();
  EXPECT_EQ(reader.header().library, "uavslam");
  ASSERT_TRUE(reader.statistics().has_value());
  const mcap::Statistics& stats = *reader.statistics();
  std::map<std::uint16_t, std::uint64_t> counts;
  for (const mcap::Message& m : written) ++counts[m.channel_id];
  EXPECT_EQ(stats.message_count, written.size());
  EXPECT_EQ(stats.channel_message_counts, counts);
  EXPECT_EQ(stats.schema_count, 2);
  EXPECT_EQ(stats.channel_count, 3u);
  EXPECT_EQ(stats.message_start_time, written.front().log_time);
  EXPECT_EQ(stats.message_end_time, written.back().log_time);
  EXPECT_EQ(stats.chunk_count, reader.chunk_indexes().size());
  EXPECT_EQ(reader.channels().size(), 3u);
  EXPECT_EQ(reader.schemas().size(), 2u);

  // Every Message Index entry points at a Message record with its log time, within its chunk's
  // times; together they list every message once.
  std::uint64_t indexed = 0;
  std::uint64_t expected_next_chunk = 0;
  for (const mcap::ChunkIndex& index : reader.chunk_indexes()) {
    if (expected_next_chunk != 0) {
      EXPECT_EQ(index.chunk_start_offset, expected_next_chunk);
    }
    EXPECT_EQ(bytes.at(index.chunk_start_offset), 0x06);
    EXPECT_EQ(index.compression, "");
    EXPECT_EQ(index.compressed_size, index.uncompressed_size);
    EXPECT_EQ(index.chunk_length, kChunkRecordsOffset + index.uncompressed_size);
    std::uint64_t index_bytes = 0;
    std::uint64_t expected_index_at = index.chunk_start_offset + index.chunk_length;
    for (const auto& [channel, offset] : index.message_index_offsets) {
      EXPECT_EQ(offset, expected_index_at);
      ASSERT_EQ(bytes.at(offset), 0x07);
      ASSERT_EQ(read_le(bytes, offset + 9, 2), channel);
      const std::uint64_t entries = read_le(bytes, offset + 11, 4) / 16;
      for (std::uint64_t e = 0; e < entries; ++e) {
        const std::uint64_t log_time = read_le(bytes, offset + 15 + 16 * e, 8);
        const std::uint64_t at = index.chunk_start_offset + kChunkRecordsOffset +
                                 read_le(bytes, offset + 15 + 16 * e + 8, 8);
        EXPECT_EQ(bytes.at(at), 0x05);
        EXPECT_EQ(read_le(bytes, at + 9, 2), channel);
        EXPECT_EQ(read_le(bytes, at + 9 + 6, 8), log_time);
        EXPECT_GE(log_time, index.message_start_time);
        EXPECT_LE(log_time, index.message_end_time);
      }
      indexed += entries;
      const std::uint64_t record_size = 9 + read_le(bytes, offset + 1, 8);
      index_bytes += record_size;
      expected_index_at += record_size;
    }
    EXPECT_EQ(index.message_index_length, index_bytes);
    expected_next_chunk = expected_index_at;
  }
  EXPECT_EQ(indexed, written.size());
}

TEST_F(McapTest, SummaryOffsetsPointAtTheirGroups) {
  const std::string file = path("offsets.mcap");
  write_sample(file, chunks_of(2000), 100);
  const Bytes bytes = read_file(file);
  const std::uint64_t footer_at = bytes.size() - 8 - 29;
  const std::uint64_t summary_offset_start = read_le(bytes, footer_at + 9 + 8, 8);
  std::vector<int> groups;
  for (std::uint64_t at = summary_offset_start; at < footer_at; at += 9 + 17) {
    ASSERT_EQ(bytes.at(at), 0x0E);
    const int opcode = bytes.at(at + 9);
    const std::uint64_t start = read_le(bytes, at + 10, 8);
    const std::uint64_t end = start + read_le(bytes, at + 18, 8);
    groups.push_back(opcode);
    for (std::uint64_t r = start; r < end; r += 9 + read_le(bytes, r + 1, 8)) {
      EXPECT_EQ(bytes.at(r), opcode) << "record at byte " << r;
    }
  }
  EXPECT_EQ(groups, (std::vector<int>{0x03, 0x04, 0x0B, 0x08}));
}

TEST_F(McapTest, IndexedSeekReturnsExactlyTheMessagesFromThatTime) {
  const std::string file = path("seek.mcap");
  const auto written = write_sample(file, chunks_of(1500), 400);
  const std::uint64_t first = written.front().log_time;
  const std::uint64_t last = written.back().log_time;
  for (const std::uint64_t t : {std::uint64_t{0}, first, first + 1, first + 123'456, last - 1000,
                                last - 999, last, last + 1}) {
    std::vector<mcap::Message> expected;
    std::copy_if(written.begin(), written.end(), std::back_inserter(expected),
                 [t](const mcap::Message& m) { return m.log_time >= t; });
    McapReadReport report;
    const auto got = indexed_from(file, t, &report);
    EXPECT_TRUE(report.complete) << report.problem;
    ASSERT_EQ(got.size(), expected.size()) << "from " << t;
    EXPECT_TRUE(std::equal(got.begin(), got.end(), expected.begin(), same)) << "from " << t;
  }
}

TEST_F(McapTest, IndexedReadStopsWhenTheVisitorSaysSo) {
  const std::string file = path("stop.mcap");
  write_sample(file, chunks_of(1500), 100);
  McapIndexedReader reader(file);
  int seen = 0;
  const McapReadReport report =
      reader.read_messages(0, [&](const mcap::Message&) { return ++seen < 5; });
  EXPECT_EQ(seen, 5);
  EXPECT_TRUE(report.complete);
}

TEST_F(McapTest, WriterReturnsTheSameIdsForTheSameDefinitions) {
  McapWriter writer(path("ids.mcap"));
  const std::uint16_t a = writer.add_schema("A", "omgidl", "struct A {};");
  EXPECT_EQ(a, 1);
  EXPECT_EQ(writer.add_schema("A", "omgidl", "struct A {};"), a);
  EXPECT_EQ(writer.add_schema("B", "omgidl", "struct B {};"), 2);
  const std::uint16_t c = writer.add_channel(a, "/a", "cdr");
  EXPECT_EQ(writer.add_channel(a, "/a", "cdr"), c);
  EXPECT_NE(writer.add_channel(a, "/a", "cdr", {{"k", "v"}}), c);
  EXPECT_NE(writer.add_channel(0, "/no_schema", "json"), c);
  EXPECT_THROW(writer.add_channel(9, "/x", "cdr"), std::invalid_argument);
  const std::uint8_t byte = 0;
  EXPECT_THROW(writer.write(42, 0, 0, 0, &byte, 1), std::invalid_argument);
}

// --- Cut short, damaged, foreign -------------------------------------------------------------

TEST_F(McapTest, FlushedMessagesAreWholeOnDiskBeforeClose) {
  const std::string file = path("open.mcap");
  const std::string copy = path("copy.mcap");
  McapWriter writer(file);
  const std::uint16_t channel = writer.add_channel(0, "/raw", "x-bytes");
  const std::uint8_t data[] = {1, 2, 3};
  for (std::uint64_t i = 0; i < 10; ++i) writer.write(channel, 0, i, i, data, sizeof(data));
  writer.flush();
  const std::uint64_t flushed_size = read_file(file).size();
  EXPECT_EQ(writer.bytes_written(), flushed_size);
  writer.write(channel, 0, 10, 10, data, sizeof(data));  // stays in the open chunk
  EXPECT_GT(writer.bytes_written(), flushed_size);
  write_file(copy, read_file(file));  // what a crash now would leave

  McapReadReport report;
  EXPECT_EQ(stream_all(copy, &report).size(), 10u);
  EXPECT_FALSE(report.complete);
  EXPECT_EQ(report.stopped_at, flushed_size);
  EXPECT_THAT(report.problem, HasSubstr("without a Data End record"));
  McapIndexedReader indexed(copy);
  EXPECT_FALSE(indexed.has_summary());
  EXPECT_THAT(indexed.summary_problem(), HasSubstr("no closing magic"));
  EXPECT_EQ(indexed_from(copy, 5).size(), 5u);  // falls back to the streaming read
  writer.close();
  EXPECT_EQ(stream_all(file).size(), 11u);
}

TEST_F(McapTest, SyncOnFlushKeepsTheSameFile) {
  McapWriterOptions options;
  options.sync_on_flush = true;
  const std::string file = path("synced.mcap");
  McapWriter writer(file, options);
  const std::uint16_t channel = writer.add_channel(0, "/raw", "x-bytes");
  const std::uint8_t data[] = {1, 2, 3};
  writer.write(channel, 0, 1, 1, data, sizeof(data));
  writer.flush();
  EXPECT_EQ(stream_all(file).size(), 1u);
  writer.close();
  McapReadReport report;
  EXPECT_EQ(stream_all(file, &report).size(), 1u);
  EXPECT_TRUE(report.complete) << report.problem;
}

TEST_F(McapTest, FileCutAtEveryByteGivesTheWholeChunksBeforeTheCut) {
  const std::string file = path("full.mcap");
  const auto written = write_sample(file, chunks_of(400), 24, 5);
  const Bytes bytes = read_file(file);
  McapIndexedReader full(file);
  ASSERT_TRUE(full.has_summary());
  ASSERT_GE(full.chunk_indexes().size(), 5u);
  const std::string cut_file = path("cut.mcap");
  for (std::uint64_t cut = 0; cut < bytes.size(); ++cut) {
    std::size_t whole = 0;  // messages in the chunks that end before the cut
    for (const mcap::ChunkIndex& index : full.chunk_indexes()) {
      if (index.chunk_start_offset + index.chunk_length <= cut) {
        whole += indexed_message_count(bytes, index);
      }
    }
    write_file(cut_file, slice(bytes, 0, cut));
    McapReadReport report;
    const auto messages = stream_all(cut_file, &report);
    ASSERT_EQ(messages.size(), whole) << "cut at " << cut;
    ASSERT_TRUE(is_prefix(messages, written)) << "cut at " << cut;
    ASSERT_FALSE(report.complete) << "cut at " << cut;
    ASSERT_FALSE(report.problem.empty()) << "cut at " << cut;
    ASSERT_LE(report.stopped_at, cut);
    McapReadReport indexed_report;
    const auto indexed = indexed_from(cut_file, 0, &indexed_report);
    ASSERT_EQ(indexed.size(), whole) << "cut at " << cut;
    ASSERT_FALSE(indexed_report.complete) << "cut at " << cut;
  }
}

TEST_F(McapTest, ReportSaysWhereAndWhyAFileWasCut) {
  const std::string file = path("full.mcap");
  write_sample(file, chunks_of(400), 24);
  const Bytes bytes = read_file(file);
  McapIndexedReader full(file);
  const mcap::ChunkIndex& second = full.chunk_indexes().at(1);
  write_file(path("cut.mcap"), slice(bytes, 0, second.chunk_start_offset + 100));
  McapReadReport report;
  stream_all(path("cut.mcap"), &report);
  EXPECT_EQ(report.problem, "truncated inside a Chunk record at byte " +
                                std::to_string(second.chunk_start_offset) + " (its length says " +
                                std::to_string(second.chunk_length - 9) + " bytes, 91 remain)");
  EXPECT_EQ(report.stopped_at, second.chunk_start_offset);
}

TEST_F(McapTest, EveryFlippedByteIsReported) {
  const std::string file = path("flip.mcap");
  const auto written = write_sample(file, chunks_of(300), 12, 4);
  const Bytes bytes = read_file(file);
  const std::string damaged = path("damaged.mcap");
  for (std::uint64_t at = 0; at < bytes.size(); ++at) {
    Bytes copy = bytes;
    copy[at] ^= 0xFF;
    write_file(damaged, copy);
    McapReadReport report;
    const auto messages = stream_all(damaged, &report);
    ASSERT_FALSE(report.complete) << "byte " << at << " flipped";
    ASSERT_FALSE(report.problem.empty()) << "byte " << at << " flipped";
    // A chunk whose damaged header makes it look compressed is skipped, and the data section's
    // CRC catches that only at the Data End: later chunks may come first.
    ASSERT_TRUE(is_subsequence(messages, written)) << "byte " << at << " flipped";
    indexed_from(damaged, 0);  // must not crash; what it finds is checked by CRC where it can
  }
}

TEST_F(McapTest, CrcMismatchesAreNamed) {
  const std::string file = path("crc.mcap");
  write_sample(file, chunks_of(400), 24);
  const Bytes bytes = read_file(file);
  McapIndexedReader full(file);
  const mcap::ChunkIndex& second = full.chunk_indexes().at(1);

  Bytes chunk_damaged = bytes;
  chunk_damaged[second.chunk_start_offset + kChunkRecordsOffset + 20] ^= 0x01;
  write_file(path("chunk.mcap"), chunk_damaged);
  McapReadReport report;
  const auto messages = stream_all(path("chunk.mcap"), &report);
  EXPECT_EQ(messages.size(), indexed_message_count(bytes, full.chunk_indexes().at(0)));
  EXPECT_THAT(report.problem,
              HasSubstr("chunk CRC mismatch at byte " + std::to_string(second.chunk_start_offset)));
  indexed_from(path("chunk.mcap"), 0, &report);
  EXPECT_THAT(report.problem, HasSubstr("chunk CRC mismatch"));

  Bytes index_damaged = bytes;  // a Message Index: only the data section's CRC covers it
  index_damaged[second.message_index_offsets.begin()->second + 12] ^= 0x01;
  write_file(path("index.mcap"), index_damaged);
  EXPECT_EQ(stream_all(path("index.mcap"), &report).size(), full.statistics()->message_count);
  EXPECT_THAT(report.problem, HasSubstr("data section CRC mismatch"));

  Bytes summary_damaged = bytes;  // a letter of the summary's first Schema name
  const std::uint64_t summary_start = read_le(bytes, bytes.size() - 8 - 29 + 9, 8);
  ASSERT_EQ(bytes.at(summary_start), 0x03);
  summary_damaged[summary_start + 9 + 2 + 4] ^= 0x01;
  write_file(path("summary.mcap"), summary_damaged);
  EXPECT_EQ(stream_all(path("summary.mcap"), &report).size(), full.statistics()->message_count);
  EXPECT_THAT(report.problem, HasSubstr("summary CRC mismatch"));
  McapIndexedReader indexed(path("summary.mcap"));
  EXPECT_THAT(indexed.summary_problem(), HasSubstr("summary CRC mismatch"));
  EXPECT_EQ(indexed_from(path("summary.mcap"), 0).size(), full.statistics()->message_count);
}

TEST_F(McapTest, RandomDamageNeverCrashes) {
  const std::string file = path("fuzz.mcap");
  write_sample(file, chunks_of(500), 30, 7);
  const Bytes bytes = read_file(file);
  const std::string damaged = path("damaged.mcap");
  std::mt19937 random(7);
  for (int round = 0; round < 1500; ++round) {
    Bytes copy = bytes;
    const int changes = 1 + static_cast<int>(random() % 4);
    for (int i = 0; i < changes; ++i) {
      const std::size_t at = random() % copy.size();
      if (random() % 2 == 0 || at + 8 > copy.size()) {
        copy[at] = static_cast<std::uint8_t>(random());
      } else {  // a length-sized field full of ones: the worst length there can be
        std::fill_n(copy.begin() + static_cast<std::ptrdiff_t>(at), 4 + random() % 5, 0xFF);
      }
    }
    if (random() % 4 == 0) copy.resize(random() % copy.size());
    write_file(damaged, copy);
    McapReadReport report;
    stream_all(damaged, &report);
    ASSERT_TRUE(report.complete || !report.problem.empty()) << "round " << round;
    indexed_from(damaged, 0, &report);
    ASSERT_TRUE(report.complete || !report.problem.empty()) << "round " << round;
  }
}

TEST_F(McapTest, ForeignAndEmptyFilesAreReportedAsNotMcap) {
  const struct {
    std::string name;
    Bytes content;
    std::string problem;
  } cases[] = {
      {"empty", {}, "not an MCAP file: the file is empty"},
      {"text", Bytes{'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd', '\n'},
       "not an MCAP file: bad magic"},
      {"png", Bytes{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}, "not an MCAP file: bad magic"},
      {"short", Bytes{0x89, 'M', 'C'}, "truncated inside the opening magic"},
      {"magic_only", kMagic, "the file ends at byte 8 without a Data End record"},
  };
  for (const auto& c : cases) {
    write_file(path(c.name), c.content);
    McapReadReport report;
    EXPECT_TRUE(stream_all(path(c.name), &report).empty()) << c.name;
    EXPECT_FALSE(report.complete) << c.name;
    EXPECT_THAT(report.problem, HasSubstr(c.problem)) << c.name;
    McapIndexedReader indexed(path(c.name));
    EXPECT_FALSE(indexed.has_summary()) << c.name;
    EXPECT_TRUE(indexed_from(path(c.name), 0).empty()) << c.name;
  }
  EXPECT_THROW(McapStreamReader(path("missing.mcap")), FileError);
  EXPECT_THROW(McapIndexedReader(path("missing.mcap")), FileError);
}

TEST_F(McapTest, HugeLengthsAreReportedNotAllocated) {
  const Bytes huge = u(~std::uint64_t{0}, 8);
  const Bytes records_overrun = cat({channel_record(), Bytes{0x05}, u(1ull << 40, 8)});
  const Bytes huge_string =
      cat({schema_record(), Bytes{0x04}, u(16, 8), u(1, 2), u(1, 2), u(0xFFFFFFFF, 4), u(0, 8)});
  const struct {
    std::string name;
    Bytes content;
    std::string problem;
  } cases[] = {
      {"record", cat({kMagic, Bytes{0x01}, huge}),
       "truncated inside a Header record at byte 8 (its length says 18446744073709551615 bytes, "
       "0 remain)"},
      {"chunk", cat({magic_and_header(), Bytes{0x06}, huge, Bytes(16, 0)}),
       "truncated inside a Chunk record at byte 29"},
      {"inner_record", cat({magic_and_header(), uncompressed_chunk(records_overrun, 0)}),
       "Message record at byte"},
      {"inner_string", cat({magic_and_header(), uncompressed_chunk(huge_string, 0)}),
       "Channel record at byte"},
      {"records_field",
       cat({magic_and_header(),
            record(0x06, cat({u(0, 8), u(0, 8), u(0, 8), u(0, 4), str(""), huge}))}),
       "Chunk record at byte 29 is too short for its fields"},
  };
  for (const auto& c : cases) {
    write_file(path(c.name), c.content);
    McapReadReport report;
    EXPECT_TRUE(stream_all(path(c.name), &report).empty()) << c.name;
    EXPECT_THAT(report.problem, HasSubstr(c.problem)) << c.name;
    EXPECT_TRUE(indexed_from(path(c.name), 0).empty()) << c.name;
  }
}

TEST_F(McapTest, SummaryPointingOutsideTheFileIsNotUsed) {
  const std::string file = path("bad_footer.mcap");
  const Bytes body = cat({magic_and_header(), schema_record(), channel_record(), message_record(5),
                          record(0x0F, u(0, 4))});
  write_file(file, cat({body, record(0x02, cat({u(1ull << 50, 8), u(0, 8), u(0, 4)})), kMagic}));
  McapIndexedReader reader(file);
  EXPECT_FALSE(reader.has_summary());
  EXPECT_THAT(reader.summary_problem(), HasSubstr("points outside"));
  EXPECT_EQ(indexed_from(file, 0).size(), 1u);

  const Bytes bad_index = record(0x08, cat({u(0, 8), u(0, 8), u(1ull << 62, 8), u(1ull << 62, 8),
                                            u(0, 4), u(0, 8), str(""), u(0, 8), u(0, 8)}));
  write_file(file, cat({body, bad_index, record(0x02, cat({u(body.size(), 8), u(0, 8), u(0, 4)})),
                        kMagic}));
  McapIndexedReader bad(file);
  EXPECT_THAT(bad.summary_problem(), HasSubstr("Chunk Index record at byte"));
  EXPECT_EQ(indexed_from(file, 0).size(), 1u);
}

// Spec "Records": unknown opcodes are skipped; messages outside chunks are allowed.
TEST_F(McapTest, UnknownRecordsAreSkippedAndUnchunkedMessagesRead) {
  const Bytes records = cat({record(0x81, Bytes{1, 2}), schema_record(), channel_record(),
                             message_record(2), record(0x7F, Bytes{})});
  const std::string file = path("unknown.mcap");
  write_file(file, cat({magic_and_header(), record(0x80, Bytes{1, 2, 3, 4, 5}), schema_record(),
                        channel_record(), message_record(1),
                        uncompressed_chunk(records, crc_of(records, 0, records.size())),
                        closing_without_summary()}));
  McapReadReport report;
  const auto messages = stream_all(file, &report);
  EXPECT_TRUE(report.complete) << report.problem;
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0].log_time, 1u);
  EXPECT_EQ(messages[1].log_time, 2u);
  EXPECT_EQ(messages[1].data, (Bytes{1, 2, 3}));
  McapIndexedReader indexed(file);
  EXPECT_THAT(indexed.summary_problem(), HasSubstr("no summary section"));
  EXPECT_EQ(indexed.header().library, "test");
  EXPECT_EQ(indexed_from(file, 2).size(), 1u);
}

// "lz4" and "zstd" chunks are read (test_mcap_compression.cpp); any other compression is not.
TEST_F(McapTest, ChunksOfAnUnknownCompressionAreSkippedAndReported) {
  const Bytes plain = cat({schema_record(), channel_record(), message_record(9)});
  const Bytes bz2 = record(0x06, cat({u(1, 8), u(1, 8), u(5000, 8), u(0x1234, 4), str("bz2"),
                                      u(4, 8), Bytes{'B', 'Z', 'h', '9'}}));
  const std::string file = path("compressed.mcap");
  write_file(file, cat({magic_and_header(), bz2, uncompressed_chunk(plain, 0),
                        closing_without_summary()}));
  McapReadReport report;
  const auto messages = stream_all(file, &report);
  EXPECT_TRUE(report.complete) << report.problem;
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0].log_time, 9u);
  ASSERT_EQ(report.skipped.size(), 1u);
  EXPECT_EQ(report.skipped[0],
            "Chunk at byte 29: compression \"bz2\" is not supported, its messages were skipped");
}

TEST_F(McapTest, MessageOnAnUndeclaredChannelStopsTheRead) {
  const std::string file = path("undeclared.mcap");
  write_file(file, cat({magic_and_header(), schema_record(), message_record(1),
                        closing_without_summary()}));
  McapReadReport report;
  EXPECT_TRUE(stream_all(file, &report).empty());
  EXPECT_THAT(report.problem, HasSubstr("Message at byte 63 is on channel 1, which no Channel"));
}

TEST_F(McapTest, FirstRecordMustBeAHeader) {
  const std::string file = path("no_header.mcap");
  write_file(file, cat({kMagic, schema_record(), closing_without_summary()}));
  McapReadReport report;
  stream_all(file, &report);
  EXPECT_EQ(report.problem, "expected a Header record at byte 8, found Schema");
}

TEST_F(McapTest, BytesAfterTheClosingMagicAreReported) {
  const std::string file = path("tail.mcap");
  write_file(file, cat({magic_and_header(), closing_without_summary(), Bytes{0}}));
  McapReadReport report;
  stream_all(file, &report);
  EXPECT_FALSE(report.complete);
  EXPECT_THAT(report.problem, HasSubstr("1 bytes after the closing magic"));
}

// --- Write errors ----------------------------------------------------------------------------

TEST_F(McapTest, WriteErrorsNameTheFileAndTheReason) {
  try {
    McapWriter writer("/dev/full");
    FAIL() << "writing to /dev/full succeeded";
  } catch (const FileError& error) {
    EXPECT_THAT(error.what(), HasSubstr("/dev/full"));
    EXPECT_THAT(error.what(), HasSubstr("No space left on device"));
  }
  try {
    McapWriter writer(path("no/such/dir.mcap"));
    FAIL() << "created a file in a missing directory";
  } catch (const FileError& error) {
    EXPECT_THAT(error.what(), HasSubstr("no/such/dir.mcap: cannot create: No such file"));
  }
}

// A file size limit (RLIMIT_FSIZE, in a child process) makes the disk "full" after 4 KiB: the
// error must come out of write() (chunk full) or flush(), and later calls must fail too.
void write_past_the_size_limit(const std::string& path, bool flush) {
  ::signal(SIGXFSZ, SIG_IGN);  // so write(2) fails with EFBIG instead of killing the process
  const rlimit limit{4096, 4096};
  ::setrlimit(RLIMIT_FSIZE, &limit);
  McapWriter writer(path, chunks_of(flush ? 1u << 20 : 1000));
  const std::uint16_t channel = writer.add_channel(0, "/raw", "x-bytes");
  const Bytes data(500, 0x55);
  try {
    for (int i = 0; i < 20; ++i) writer.write(channel, 0, 0, 0, data.data(), data.size());
    if (flush) writer.flush();
  } catch (const FileError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    try {
      writer.flush();
    } catch (const FileError& again) {
      std::fprintf(stderr, "%s\n", again.what());
      writer.close();
      std::exit(0);
    }
  }
  std::exit(1);
}

TEST_F(McapTest, DiskFullSurfacesFromWriteAndFlush) {
  const std::string file = path("limited.mcap");
  EXPECT_EXIT(write_past_the_size_limit(file, false), ::testing::ExitedWithCode(0),
              "limited.mcap: cannot write: File too large\n.*an earlier write failed");
  EXPECT_EXIT(write_past_the_size_limit(file, true), ::testing::ExitedWithCode(0),
              "limited.mcap: cannot write: File too large");
  McapReadReport report;
  stream_all(file, &report);  // what the failed writer left is read as far as it is whole
  EXPECT_FALSE(report.complete);
  EXPECT_THAT(report.problem, HasSubstr("truncated inside a Chunk record"));
}

}  // namespace
}  // namespace uavslam::io
