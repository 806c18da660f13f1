// The IDL texts recordings carry as schemas: one self-contained text per wire type, found by the
// name its fastddsgen PubSubType reports.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <msg/ImuPubSubTypes.h>
#include <msg/LaserScanPubSubTypes.h>
#include <msg/MapPointsPubSubTypes.h>
#include <msg/MatcherStatusPubSubTypes.h>
#include <msg/OccupancyMapPubSubTypes.h>
#include <msg/PosePubSubTypes.h>

#include "dds/IdlSchemas.hpp"

namespace uavslam::dds {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

template <typename PubSubType>
std::string schema_of() {
  PubSubType type;
  const std::optional<std::string> text = idl_schema(type.getName());
  EXPECT_TRUE(text.has_value()) << type.getName();
  return text.value_or("");
}

TEST(IdlSchemas, EveryWireTypeHasASelfContainedText) {
  for (const std::string& text :
       {schema_of<msg::LaserScanPubSubType>(), schema_of<msg::ImuPubSubType>(),
        schema_of<msg::PoseWithCovarianceStampedPubSubType>(),
        schema_of<msg::MapPointsPubSubType>(), schema_of<msg::OccupancyMapPubSubType>(),
        schema_of<msg::MatcherStatusPubSubType>()}) {
    EXPECT_THAT(text, HasSubstr("struct Header {")) << "Common.idl inlined";
    EXPECT_THAT(text, Not(HasSubstr("#include"))) << text;
    EXPECT_THAT(text, Not(HasSubstr("#define"))) << text;
  }
}

TEST(IdlSchemas, ATypeGetsItsOwnFile) {
  const std::string scan = schema_of<msg::LaserScanPubSubType>();
  EXPECT_THAT(scan, HasSubstr("struct LaserScan {"));
  EXPECT_THAT(scan, HasSubstr("sequence<float> ranges;"));
  EXPECT_THAT(scan, Not(HasSubstr("struct Imu {")));
  EXPECT_THAT(*idl_schema("uavslam::msg::Header"), Not(HasSubstr("struct LaserScan")))
      << "a Common type: Common.idl alone";
}

TEST(IdlSchemas, AnUnknownTypeHasNone) {
  EXPECT_FALSE(idl_schema("uavslam::msg::NoSuchType").has_value());
  EXPECT_FALSE(idl_schema("other::LaserScan").has_value());
}

}  // namespace
}  // namespace uavslam::dds
