// Outputs of visnav-eval: per-frame CSV, JSON summary, human-readable summary and requirement checks.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "visnav/core/status.hpp"
#include "visnav/eval/evaluation.hpp"

namespace visnav::eval {

struct Requirements {
  bool require_tracked_all = false;  ///< no lost and no missing frame
  bool check_inside = false;         ///< inside fraction at `inside_envelope_px` >= `min_inside_fraction`
  double min_inside_fraction = 0.0;
  double inside_envelope_px = 0.25;
  bool check_far_direction = false;  ///< far-range direction error median <= the bound (and some far frames)
  double max_far_direction_median_deg = 0.0;
  bool check_far_distance = false;  ///< far-range |distance error| median <= the bound (and some far frames)
  double max_far_distance_median_pct = 0.0;
  bool check_final_mode = false;  ///< the replay's last row is in `final_mode`
  ReplayMode final_mode = ReplayMode::kNearRange;
};

std::vector<RequirementResult> checkRequirements(const Evaluation& evaluation, const Requirements& req);

/// A JSON string literal of `s` (quotes, backslashes and control characters escaped): the one escaper of
/// the ground tools' JSON outputs.
std::string jsonString(const std::string& s);

/// Column-name tag of an envelope size: 1 -> "1px", 0.25 -> "0p25px".
std::string envelopeTag(double delta_px);

void writeFrameCsv(std::ostream& out, const Evaluation& evaluation);
LoadError writeFrameCsv(const std::string& path, const Evaluation& evaluation);

void writeSummaryJson(std::ostream& out, const Evaluation& evaluation,
                      const std::vector<RequirementResult>& req, const std::string& sequence,
                      const std::string& replay);
LoadError writeSummaryJson(const std::string& path, const Evaluation& evaluation,
                           const std::vector<RequirementResult>& req, const std::string& sequence,
                           const std::string& replay);

/// Multi-line summary: frame counts, per-axis median/p95/max, envelope maxima and inside fractions, far-range
/// errors, frames per mode and the mode transitions.
std::string summaryText(const Evaluation& evaluation);

}  // namespace visnav::eval
