#include "visnav/campaign/classify.hpp"

#include <algorithm>

namespace visnav::campaign {

bool targetInView(const PinholeCamera& camera, const Pose& truth, bool eclipsed) {
  if (eclipsed || !(truth.t_c_m.z() > 1e-6)) return false;
  Vec2 px;
  if (!camera.project(truth.t_c_m, px)) return false;
  return px.x() >= 0.0 && px.y() >= 0.0 && px.x() < camera.width() && px.y() < camera.height();
}

bool targetVisible(const PinholeCamera& camera, const PolygonModel& model, const Pose& truth, bool eclipsed,
                   const Thresholds& th) {
  if (!targetInView(camera, truth, eclipsed)) return false;
  const double z = truth.t_c_m.z();
  if (2.0 * camera.intrinsics().fx_px * model.boundingRadius() / z < th.min_visible_px) return false;
  for (const ModelSurface& s : model.surfaces()) {
    const Vec3 n_c = truth.R_c_m * s.normal_m;
    const Vec3 c_c = truth.transform(s.centroid_m);
    if (c_c.z() > 0.0 && -n_c.dot(c_c.normalized()) > th.min_facing_cos) return true;
  }
  return false;
}

bool poseErrorIsWrong(double position_error_m, double range_m, double attitude_error_deg,
                      const Thresholds& th) {
  const double rel = range_m > 0.0 ? position_error_m / range_m : 1e300;
  return rel > th.wrong_position_rel || attitude_error_deg > th.wrong_attitude_deg;
}

void classifyFrame(FrameOutcome& f, const Thresholds& th) {
  f.wrong = false;
  f.tracked = false;
  f.accurate = false;
  if (!f.pose_valid) return;
  const double rel = f.range_m > 0.0 ? f.position_error_m / f.range_m : 1e300;
  f.wrong = poseErrorIsWrong(f.position_error_m, f.range_m, f.attitude_error_deg, th);
  const bool six_dof_mode = f.mode == nav::NavMode::kNearRange || f.mode == nav::NavMode::kAcquisition;
  f.tracked = six_dof_mode && !f.wrong;
  f.accurate =
      f.tracked && rel <= th.accurate_position_rel && f.attitude_error_deg <= th.accurate_attitude_deg;
}

const char* toString(EventKind kind) {
  switch (kind) {
    case EventKind::kSlew: return "slew";
    case EventKind::kEclipseEnd: return "eclipse_end";
    case EventKind::kReappear: return "reappear";
    case EventKind::kLoss: return "loss";
  }
  return "?";
}

std::vector<RecoveryEvent> recoveryEvents(const std::vector<FrameOutcome>& frames, bool tracked_at_start) {
  std::vector<RecoveryEvent> events;
  const int n = static_cast<int>(frames.size());
  // Next tracked frame at or after i (n: none), from the back.
  std::vector<int> next_tracked(static_cast<std::size_t>(n) + 1U, n);
  for (int i = n - 1; i >= 0; --i)
    next_tracked[static_cast<std::size_t>(i)] =
        frames[static_cast<std::size_t>(i)].tracked ? i : next_tracked[static_cast<std::size_t>(i) + 1U];
  bool ever_tracked = tracked_at_start;
  bool eclipse_pending = false;  // an eclipse ended, the target not visible yet
  for (int i = 0; i < n; ++i) {
    const FrameOutcome& f = frames[static_cast<std::size_t>(i)];
    const FrameOutcome* prev = i > 0 ? &frames[static_cast<std::size_t>(i) - 1U] : nullptr;
    if (prev != nullptr && prev->eclipsed && !f.eclipsed) eclipse_pending = true;
    bool have = false;
    EventKind kind = EventKind::kLoss;
    if (f.slew) {
      have = true;
      kind = EventKind::kSlew;
    } else if (eclipse_pending && f.visible) {
      have = true;
      kind = EventKind::kEclipseEnd;
    } else if (prev != nullptr && f.visible && !prev->visible && ever_tracked) {
      have = true;
      kind = EventKind::kReappear;
    } else if (f.visible && !f.tracked && (prev != nullptr ? prev->tracked : tracked_at_start)) {
      have = true;
      kind = EventKind::kLoss;
    }
    if (f.visible) eclipse_pending = false;
    if (have) {
      const int next = next_tracked[static_cast<std::size_t>(i)];
      events.push_back({kind, i, next < n ? next - i : -1});
    }
    ever_tracked = ever_tracked || f.tracked;
  }
  return events;
}

}  // namespace visnav::campaign
