#include "core/ScanOutcome.hpp"

namespace uavslam {

std::string to_string(ScanOutcome outcome) {
  switch (outcome) {
    case ScanOutcome::Accepted:
      return "accepted";
    case ScanOutcome::MapInitialised:
      return "map_initialised";
    case ScanOutcome::Malformed:
      return "malformed";
    case ScanOutcome::NoImu:
      return "no_imu";
    case ScanOutcome::TooFewPoints:
      return "too_few_points";
    case ScanOutcome::NoCorrespondences:
      return "no_correspondences";
    case ScanOutcome::TranslationTooLarge:
      return "translation_too_large";
    case ScanOutcome::RotationTooLarge:
      return "rotation_too_large";
    case ScanOutcome::ErrorTooLarge:
      return "error_too_large";
    case ScanOutcome::ErrorIncreased:
      return "error_increased";
    case ScanOutcome::DisagreesWithPrior:
      return "disagrees_with_prior";
  }
  return "unknown";
}

}  // namespace uavslam
