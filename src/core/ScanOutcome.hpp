// How the processing of one scan ended: accepted, or the counted reason it was dropped.
#pragma once

#include <cstddef>
#include <string>

namespace uavslam {

enum class ScanOutcome {
  Accepted,
  MapInitialised,       // the first scan seeds the map
  Malformed,            // no geometry, range count differs from the geometry, or a bad stamp
  NoImu,                // no orientation sample near the scan's time
  TooFewPoints,         // fewer valid points than the matcher needs
  NoCorrespondences,    // no scan point had a map point near enough
  TranslationTooLarge,  // accumulated correction beyond icp.max_translation (seed step 3)
  RotationTooLarge,     // accumulated yaw correction beyond icp.max_rotation
  ErrorTooLarge,        // error after above icp.max_error_after (seed step 4)
  ErrorIncreased,       // error after above icp.max_error_ratio * error before (seed step 4)
  DisagreesWithPrior,   // beyond the seed: too many sigmas from the motion prior (icp.prior_gate)
};
constexpr std::size_t kScanOutcomeCount = 11;

std::string to_string(ScanOutcome outcome);

}  // namespace uavslam
