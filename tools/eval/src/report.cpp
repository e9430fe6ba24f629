#include "visnav/eval/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace visnav::eval {
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

std::string jnum(double v) { return std::isfinite(v) ? num(v) : "null"; }

std::string axisColumn(int a) { return std::string(axisName(a)) + "_" + axisUnit(a); }

// "median 0.0312 deg over 120 far_valid frames, required <= 0.1"; fails when nothing was scored.
RequirementResult farMedianRequirement(const char* name, const ErrorStats& stats, const char* unit,
                                       double bound) {
  RequirementResult r{name, stats.count > 0 && stats.median <= bound, ""};
  r.detail = stats.count > 0
                 ? "median " + num(stats.median) + " " + unit + " over " + std::to_string(stats.count) +
                       " far_valid frames, required <= " + num(bound)
                 : "no far_valid frame to score";
  return r;
}

std::string transitionText(const ModeChange& t) {
  return "frame " + std::to_string(t.frame) + " " + toString(t.from) + " -> " + toString(t.to);
}

}  // namespace

std::string jsonString(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20U) {
      char buf[8];
      std::snprintf(buf, sizeof(buf), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(ch)));
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::vector<RequirementResult> checkRequirements(const Evaluation& ev, const Requirements& req) {
  std::vector<RequirementResult> out;
  const EvaluationSummary& s = ev.summary;
  if (req.require_tracked_all) {
    RequirementResult r{"tracked_all", s.track_loss_count == 0, ""};
    r.detail = std::to_string(s.frames_lost) + " lost, " + std::to_string(s.frames_missing) + " missing of " +
               std::to_string(s.frames_evaluated) + " frames";
    out.push_back(r);
  }
  if (req.check_inside) {
    RequirementResult r{"inside_fraction", false, ""};
    const int d = envelopeIndex(ev, req.inside_envelope_px);
    if (d < 0) {
      r.detail = "envelope " + num(req.inside_envelope_px) + " px was not computed";
    } else {
      const EnvelopeSummary& es = s.envelopes[d];
      r.passed = es.frames_with_envelope > 0 && es.inside_fraction >= req.min_inside_fraction;
      r.detail = insideLine(es) + ", required >= " + num(100.0 * req.min_inside_fraction) + "%";
    }
    out.push_back(r);
  }
  if (req.check_far_direction)
    out.push_back(farMedianRequirement("far_direction_median", s.far_direction_deg, "deg",
                                       req.max_far_direction_median_deg));
  if (req.check_far_distance)
    out.push_back(farMedianRequirement("far_distance_median", s.far_distance_pct, "%",
                                       req.max_far_distance_median_pct));
  if (req.check_final_mode) {
    RequirementResult r{"final_mode", s.has_modes && s.final_mode == req.final_mode, ""};
    r.detail = s.has_modes ? std::string("last row in ") + toString(s.final_mode) + ", required " +
                                 toString(req.final_mode)
                           : "the replay has no mode column";
    out.push_back(r);
  }
  return out;
}

std::string envelopeTag(double delta_px) {
  std::string t = num(delta_px);
  for (char& ch : t)
    if (ch == '.') ch = 'p';
  return t + "px";
}

void writeFrameCsv(std::ostream& out, const Evaluation& ev) {
  out << "frame,timestamp_ns,distance_m,status,scored";
  for (int a = 0; a < kAxisCount; ++a) out << ",err_" << axisColumn(a);
  out << ",err_att_deg,env_vertices,env_combinations";
  for (double d : ev.envelope_px) {
    const std::string tag = envelopeTag(d);
    for (int a = 0; a < kAxisCount; ++a) out << ",env_" << tag << "_" << axisColumn(a);
    out << ",env_" << tag << "_att_deg,inside_" << tag;
  }
  out << ",mode,far_scored,err_far_dir_deg,err_far_dist_pct\n";
  for (const FrameRecord& f : ev.frames) {
    out << f.frame << ',' << f.timestamp_ns << ',' << num(f.distance_m) << ',' << toString(f.status) << ','
        << (f.scored ? 1 : 0);
    for (int a = 0; a < kAxisCount; ++a) out << ',' << (f.scored ? num(f.error[a]) : "");
    out << ',' << (f.scored ? num(f.attitude_error_deg) : "");
    // Vertices and combinations of the largest-delta envelope (delta = 0 needs one solve only).
    int vertices = 0, combinations = 0;
    for (const FrameEnvelope& e : f.envelopes) {
      if (!e.valid) continue;
      vertices = e.vertex_count;
      combinations = std::max(combinations, e.combinations);
    }
    out << ',' << vertices << ',' << combinations;
    for (std::size_t d = 0; d < f.envelopes.size(); ++d) {
      const FrameEnvelope& e = f.envelopes[d];
      for (int a = 0; a < kAxisCount; ++a) out << ',' << (e.valid ? num(e.max_abs[a]) : "");
      out << ',' << (e.valid ? num(e.max_angle_deg) : "") << ','
          << (e.valid ? (f.inside[d] ? "1" : "0") : "");
    }
    out << ',' << (f.mode == ReplayMode::kUnknown ? "" : toString(f.mode)) << ',' << (f.far_scored ? 1 : 0)
        << ',' << (f.far_scored ? num(f.far_error.direction_deg) : "") << ','
        << (f.far_scored ? num(f.far_error.distance_pct) : "") << '\n';
  }
}

LoadError writeFrameCsv(const std::string& path, const Evaluation& ev) {
  std::ofstream out(path);
  if (!out) return LoadError::failure(path + ": cannot open for writing");
  writeFrameCsv(out, ev);
  return out ? LoadError::success() : LoadError::failure(path + ": write failed");
}

void writeSummaryJson(std::ostream& out, const Evaluation& ev, const std::vector<RequirementResult>& req,
                      const std::string& sequence, const std::string& replay) {
  const EvaluationSummary& s = ev.summary;
  bool passed = true;
  for (const RequirementResult& r : req) passed = passed && r.passed;
  out << "{\n  \"sequence\": " << jsonString(sequence) << ",\n  \"replay\": " << jsonString(replay) << ",\n";
  out << "  \"frames\": {\"evaluated\": " << s.frames_evaluated << ", \"tracking\": " << s.frames_tracking
      << ", \"degraded\": " << s.frames_degraded << ", \"lost\": " << s.frames_lost
      << ", \"missing\": " << s.frames_missing << ", \"init\": " << s.frames_init
      << ", \"track_loss\": " << s.track_loss_count
      << ", \"unmatched_replay_rows\": " << s.unmatched_replay_rows << "},\n  \"errors\": {\n";
  auto stats = [&out](const std::string& name, const ErrorStats& e, bool last) {
    out << "    " << jsonString(name) << ": {\"count\": " << e.count << ", \"median\": " << jnum(e.median)
        << ", \"p95\": " << jnum(e.p95) << ", \"max\": " << jnum(e.max) << "}" << (last ? "\n" : ",\n");
  };
  for (int a = 0; a < kAxisCount; ++a) stats(axisColumn(a), s.axes[a], false);
  stats("att_deg", s.attitude, true);
  out << "  },\n  \"envelopes\": [";
  for (std::size_t d = 0; d < s.envelopes.size(); ++d) {
    const EnvelopeSummary& e = s.envelopes[d];
    out << (d ? ",\n" : "\n") << "    {\"delta_px\": " << jnum(e.delta_px)
        << ", \"frames_with_envelope\": " << e.frames_with_envelope
        << ", \"inside_count\": " << e.inside_count << ", \"inside_fraction\": " << jnum(e.inside_fraction)
        << ", \"failed_solves\": " << e.failed_solves << ", \"max_envelope\": {";
    for (int a = 0; a < kAxisCount; ++a)
      out << (a ? ", " : "") << jsonString(axisColumn(a)) << ": " << jnum(e.max_envelope[a]);
    out << "}}";
  }
  out << (s.envelopes.empty() ? "],\n" : "\n  ],\n") << "  \"far_range\": {\n";
  stats("direction_deg", s.far_direction_deg, false);
  stats("distance_pct", s.far_distance_pct, true);
  out << "  },\n";
  if (s.nis.count > 0) {
    out << "  \"filter_nis\": {\"count\": " << s.nis.count << ", \"mean\": " << jnum(s.nis_mean)
        << ", \"median\": " << jnum(s.nis.median) << ", \"p95\": " << jnum(s.nis.p95)
        << ", \"max\": " << jnum(s.nis.max) << ", \"above_gate\": " << s.nis_above_gate << "},\n";
  }
  out << "  \"modes\": {\"frames\": {";
  for (int m = 0; m < kReplayModeCount; ++m)
    out << (m ? ", " : "") << jsonString(toString(static_cast<ReplayMode>(m))) << ": " << s.mode_frames[m];
  out << "}, \"final\": " << (s.has_modes ? jsonString(toString(s.final_mode)) : "null")
      << ", \"transitions\": [";
  for (std::size_t i = 0; i < s.transitions.size(); ++i) {
    const ModeChange& t = s.transitions[i];
    out << (i ? ", " : "") << "{\"frame\": " << t.frame << ", \"from\": " << jsonString(toString(t.from))
        << ", \"to\": " << jsonString(toString(t.to)) << "}";
  }
  out << "]},\n  \"requirements\": [";
  for (std::size_t i = 0; i < req.size(); ++i) {
    out << (i ? ",\n" : "\n") << "    {\"name\": " << jsonString(req[i].name)
        << ", \"passed\": " << (req[i].passed ? "true" : "false")
        << ", \"detail\": " << jsonString(req[i].detail) << "}";
  }
  out << (req.empty() ? "],\n" : "\n  ],\n") << "  \"passed\": " << (passed ? "true" : "false") << "\n}\n";
}

LoadError writeSummaryJson(const std::string& path, const Evaluation& ev,
                           const std::vector<RequirementResult>& req, const std::string& sequence,
                           const std::string& replay) {
  std::ofstream out(path);
  if (!out) return LoadError::failure(path + ": cannot open for writing");
  writeSummaryJson(out, ev, req, sequence, replay);
  return out ? LoadError::success() : LoadError::failure(path + ": write failed");
}

std::string summaryText(const Evaluation& ev) {
  const EvaluationSummary& s = ev.summary;
  std::ostringstream o;
  char buf[200];
  std::snprintf(
      buf, sizeof(buf),
      "frames evaluated: %d (tracking %d, degraded %d, init %d, lost %d, missing %d); track losses: %d\n",
      s.frames_evaluated, s.frames_tracking, s.frames_degraded, s.frames_init, s.frames_lost,
      s.frames_missing, s.track_loss_count);
  o << buf;
  if (s.unmatched_replay_rows > 0)
    o << "replay rows without a truth frame (ignored): " << s.unmatched_replay_rows << '\n';
  std::snprintf(buf, sizeof(buf), "%-10s %12s %12s %12s", "|error|", "median", "p95", "max");
  o << buf;
  for (const EnvelopeSummary& e : s.envelopes) {
    std::snprintf(buf, sizeof(buf), " %12s", ("env " + num(e.delta_px) + " px").c_str());
    o << buf;
  }
  o << '\n';
  for (int a = 0; a < kAxisCount; ++a) {
    std::snprintf(buf, sizeof(buf), "%-10s %12.6g %12.6g %12.6g", axisColumn(a).c_str(), s.axes[a].median,
                  s.axes[a].p95, s.axes[a].max);
    o << buf;
    for (const EnvelopeSummary& e : s.envelopes) {
      std::snprintf(buf, sizeof(buf), " %12.6g", e.max_envelope[a]);
      o << buf;
    }
    o << '\n';
  }
  std::snprintf(buf, sizeof(buf), "%-10s %12.6g %12.6g %12.6g\n", "att_deg", s.attitude.median,
                s.attitude.p95, s.attitude.max);
  o << buf << "(" << s.axes[0].count
    << " scored frames; envelope columns: largest envelope over the frames)\n";
  for (const EnvelopeSummary& e : s.envelopes) {
    o << insideLine(e);
    if (e.failed_solves > 0) o << "  [" << e.failed_solves << " envelope LM solves did not converge]";
    o << '\n';
  }
  if (s.far_direction_deg.count > 0) {
    o << "far range (" << s.far_direction_deg.count << " far_valid frames):\n";
    for (const auto& [label, e] : {std::make_pair("far_dir_deg", s.far_direction_deg),
                                   std::make_pair("far_dist_pct", s.far_distance_pct)}) {
      std::snprintf(buf, sizeof(buf), "%-12s %10.6g %12.6g %12.6g\n", label, e.median, e.p95, e.max);
      o << buf;
    }
  }
  if (s.nis.count > 0) {
    std::snprintf(
        buf, sizeof(buf),
        "filter NIS (%d 6-DOF updates): mean %.3g (6 if consistent), median %.3g, p95 %.3g, max %.3g; "
        "above %.2f (99.9 %%): %d\n",
        s.nis.count, s.nis_mean, s.nis.median, s.nis.p95, s.nis.max, kNisGate6Dof, s.nis_above_gate);
    o << buf;
  }
  if (s.has_modes) {
    o << "frames per mode:";
    for (int m = 0; m < kReplayModeCount; ++m)
      o << (m ? ", " : " ") << toString(static_cast<ReplayMode>(m)) << ' ' << s.mode_frames[m];
    o << "; final mode " << toString(s.final_mode) << '\n' << "mode transitions: " << s.transitions.size();
    constexpr std::size_t kListed = 20;  // chatter would flood the console: the CSV/JSON have them all
    for (std::size_t i = 0; i < std::min(s.transitions.size(), kListed); ++i)
      o << (i ? ", " : " (") << transitionText(s.transitions[i]);
    if (s.transitions.size() > kListed) o << ", ... " << s.transitions.size() - kListed << " more";
    o << (s.transitions.empty() ? "\n" : ")\n");
  }
  return o.str();
}

}  // namespace visnav::eval
