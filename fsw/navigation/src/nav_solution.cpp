#include "visnav/navigation/nav_solution.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace visnav::nav {

void copyBounded(const char* text, char* out, std::size_t capacity) {
  if (capacity == 0) return;
  std::size_t n = 0;
  while (text != nullptr && n + 1 < capacity && text[n] != '\0') {
    out[n] = text[n];
    ++n;
  }
  std::memset(out + n, 0, capacity - n);
}

PoseSigmas poseSigmas(const Pose& pose, const Mat6& covariance) {
  PoseSigmas s;
  s.attitude_deg = std::sqrt(covariance.topLeftCorner<3, 3>().trace()) * kDegPerRad;
  s.position_rel =
      std::sqrt(covariance.bottomRightCorner<3, 3>().trace()) / std::max(pose.t_c_m.norm(), 1e-9);
  return s;
}

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
