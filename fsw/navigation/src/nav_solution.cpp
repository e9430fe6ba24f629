#include "visnav/navigation/nav_solution.hpp"

namespace visnav::nav {

const char* toString(NavMode mode) {
  switch (mode) {
    case NavMode::kStandby: return "standby";
    case NavMode::kFarRange: return "far_range";
    case NavMode::kAcquisition: return "acquisition";
    case NavMode::kNearRange: return "near_range";
  }
  return "unknown";
}

const char* toString(ModeCommandKind kind) {
  switch (kind) {
    case ModeCommandKind::kForceFarRange: return "force_far_range";
    case ModeCommandKind::kReacquire: return "reacquire";
    case ModeCommandKind::kStandby: return "standby";
    case ModeCommandKind::kResume: return "resume";
  }
  return "unknown";
}

}  // namespace visnav::nav
