// The SCIP 2.0 codec against the specification's own examples (C-42-03320B section 6, the
// encoding examples; section 7 and 8, the status and PP lines) and round trips.
#include <gtest/gtest.h>

#include <cmath>

#include "drivers/scip2/Encoding.hpp"
#include "drivers/scip2/ReplyText.hpp"
#include "drivers/scip2/ScanReply.hpp"
#include "drivers/scip2/SensorDescription.hpp"

namespace uavslam::drivers::scip2 {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Scip2Encoding, DecodesTheSpecificationExamples) {
  EXPECT_EQ(decode("CB"), 1234u);        // 2-character encoding
  EXPECT_EQ(decode("1Dh"), 5432u);       // 3-character encoding
  EXPECT_EQ(decode("m2@0"), 16000000u);  // 4-character encoding
}

TEST(Scip2Encoding, EncodesWhatItDecodes) {
  for (const std::uint32_t value : {0u, 1u, 63u, 64u, 4095u, 262143u, 16777215u}) {
    EXPECT_EQ(decode(encode(value, 4)), value);
  }
  EXPECT_EQ(encode(1234, 2), "CB");
  EXPECT_EQ(encode(5432, 3), "1Dh");
}

TEST(Scip2Encoding, RejectsCharactersOutsideTheEncoding) {
  EXPECT_FALSE(decode("0/"));  // below 0x30
  EXPECT_FALSE(decode("p0"));  // above 0x6F
  EXPECT_FALSE(decode(""));
  EXPECT_FALSE(decode("00000"));  // more than 24 bits
}

TEST(Scip2Encoding, ChecksumsMatchTheSpecificationLines) {
  EXPECT_EQ(checksum("00"), 'P');
  EXPECT_EQ(checksum("99"), 'b');
  EXPECT_EQ(info_line("DMIN", "20"), "DMIN:20;4");
  EXPECT_EQ(info_line("SCAN", "600"), "SCAN:600;e");
  EXPECT_TRUE(has_valid_checksum("00P"));
  EXPECT_FALSE(has_valid_checksum("00Q"));
}

TEST(Scip2ScanReply, CommandTextFollowsTheFormat) {
  ScanRequest r;
  r.first_step = 0;
  r.last_step = 1080;
  EXPECT_EQ(command_text(r), "MD0000108001000");
  r.with_intensity = true;
  EXPECT_EQ(command_text(r), "ME0000108001000");
  r.continuous = false;
  EXPECT_EQ(command_text(r), "GE0000108001");
  const auto parsed = parse_scan_echo("MD0044072501000");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->first_step, 44);
  EXPECT_EQ(parsed->last_step, 725);
  EXPECT_EQ(parsed->values(), 682);
  EXPECT_FALSE(parse_scan_echo("VV"));
  EXPECT_FALSE(parse_scan_echo("MD00x0108001000"));
}

Response response_from(const std::vector<std::string>& lines_with_sums) {
  Response r;
  r.echo = "ME0000009901000";
  r.status = "99";
  for (const std::string& l : lines_with_sums) r.data.push_back(l.substr(0, l.size() - 1));
  return r;
}

TEST(Scip2ScanReply, DecodesValuesThatStraddleLines) {
  ScanData scan;
  scan.timestamp_ms = 16000000;
  for (std::uint32_t i = 0; i < 100; ++i) {
    scan.distances_mm.push_back(100 + i * 37);
    scan.intensities.push_back(5000 + i);
  }
  const auto lines = encode_scan_lines(scan);
  ASSERT_EQ(lines.size(), 1 + (600 + 63) / 64);  // 600 data characters in 64-character blocks
  for (const std::string& l : lines) EXPECT_TRUE(has_valid_checksum(l)) << l;
  ScanRequest request;
  request.with_intensity = true;
  request.last_step = 99;
  std::string problem;
  const auto decoded = decode_scan(response_from(lines), request, problem);
  ASSERT_TRUE(decoded) << problem;
  EXPECT_EQ(decoded->timestamp_ms, 16000000u);
  EXPECT_EQ(decoded->distances_mm, scan.distances_mm);
  EXPECT_EQ(decoded->intensities, scan.intensities);
}

TEST(Scip2ScanReply, RejectsAScanOfTheWrongLength) {
  ScanData scan;
  scan.distances_mm.assign(10, 1000);
  ScanRequest request;
  request.last_step = 10;  // 11 steps expected
  std::string problem;
  EXPECT_FALSE(decode_scan(response_from(encode_scan_lines(scan)), request, problem));
  EXPECT_NE(problem.find("expected 33"), std::string::npos) << problem;
}

TEST(Scip2SensorDescription, GivesTheUtm30lxGeometry) {
  const InfoFields pp = parse_info_lines({"MODL:UTM-30LX", "DMIN:23", "DMAX:60000", "ARES:1440",
                                          "AMIN:0", "AMAX:1080", "AFRT:540", "SCAN:2400"});
  std::string problem;
  const auto d = describe_sensor(pp, parse_info_lines({"SERI:H0912345"}), problem);
  ASSERT_TRUE(d) << problem;
  EXPECT_EQ(d->model, "UTM-30LX");
  EXPECT_EQ(d->serial, "H0912345");
  EXPECT_EQ(d->beams(), 1081);
  EXPECT_NEAR(d->angle_of_step(0), -135.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(d->angle_of_step(1080), 135.0 * kPi / 180.0, 1e-12);
  EXPECT_NEAR(d->angle_increment(), 0.25 * kPi / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(d->scan_period(), 0.025);
}

TEST(Scip2SensorDescription, NamesTheMissingOrBadField) {
  std::string problem;
  EXPECT_FALSE(describe_sensor(parse_info_lines({"DMIN:23"}), {}, problem));
  EXPECT_EQ(problem, "PP reply has no DMAX");
  const InfoFields bad = parse_info_lines(
      {"DMIN:23", "DMAX:60000", "ARES:1440", "AMIN:0", "AMAX:1080", "AFRT:540", "SCAN:0"});
  EXPECT_FALSE(describe_sensor(bad, {}, problem));
  EXPECT_NE(problem.find("inconsistent"), std::string::npos);
}

}  // namespace
}  // namespace uavslam::drivers::scip2
