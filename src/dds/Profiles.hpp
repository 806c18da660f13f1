// The QoS profile file (qos/uavslam_profiles.xml by default): loading it into Fast DDS, and where
// it is.
#pragma once

#include <string>
#include <vector>

namespace uavslam::dds {

// Loads the Fast DDS XML profiles in xml_path (process-wide: every participant, writer and reader
// created afterwards can use the profiles it defines). Loading a path already loaded does nothing.
// Throws DdsError "cannot load QoS profiles from '<path>': <reason>" for a missing or unreadable
// file or one Fast DDS rejects (the reason quotes Fast DDS's XML parser errors). Thread-safe.
void load_profiles(const std::string& xml_path);

// $UAVSLAM_QOS_FILE if set and non-empty; else, in an installed tree (bin/ beside qos/), its
// qos/uavslam_profiles.xml; else the source tree's qos/uavslam_profiles.xml.
std::string default_profiles_path();

// The profile_name attributes of the <element> profiles ("participant", "data_writer",
// "data_reader") declared in xml_path, in file order; empty when the file cannot be read. A plain
// text scan for error messages, not a parser.
std::vector<std::string> profile_names(const std::string& xml_path, const std::string& element);

}  // namespace uavslam::dds
