// visnav-eval: scores a visnav-replay CSV against a sequence's truth (README.md in this folder).
// Exit codes (README.md "Exit codes", visnav::cli): 0 all requested requirements hold, 1 a requirement
// failed, 2 usage, 3 an input that does not load or has nothing to score, or an output that cannot be
// written.
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/eval/evaluation.hpp"
#include "visnav/eval/plot.hpp"
#include "visnav/eval/replay_csv.hpp"
#include "visnav/eval/report.hpp"
#include "visnav/replay/sequence.hpp"

namespace {

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;
using visnav::cli::parseNumber;

const char* const kUsage =
    "usage: visnav-eval --sequence DIR --replay replay.csv [--far-range FILE] [--plot errors.png]\n"
    "                   [--csv per_frame_errors.csv]\n"
    "                   [--json summary.json] [--envelope-px 1.0,0.25] [--envelope-stride N]\n"
    "                   [--require-tracked-all] [--min-inside-fraction F [--inside-envelope-px D]]\n"
    "                   [--symmetry x180|y180|z180 ...]  (model rotations that look the same)\n"
    "                   [--timeline modes.png] [--max-far-direction-median-deg X]\n"
    "                   [--max-far-distance-median-pct X] [--require-final-mode MODE]\n"
    "       visnav-eval --help | --version\n"
    "Scores a visnav-replay CSV against a sequence's truth (tools/eval/README.md).\n"
    "  exit code: 0 all requested requirements hold, 1 a requirement failed, 2 usage, 3 an input that does\n"
    "  not load or has nothing to score (empty replay), or an output that cannot be written\n";

struct Args {
  std::string sequence, replay, far_range, plot, timeline, csv, json;
  visnav::eval::EvaluationOptions eval;
  visnav::eval::Requirements req;
  bool inside_px_given = false;
};

// Returns an error message, empty on success.
std::string parseArgs(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string opt = argv[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= argc) return false;
      out = argv[++i];
      return true;
    };
    std::string v;
    double x = 0.0;
    if (opt == "--require-tracked-all") {
      a.req.require_tracked_all = true;
    } else if (opt == "--help" || opt == "-h") {
      return "help";
    } else if (opt == "--version") {
      return "version";
    } else if (!value(v)) {
      return "unknown option or missing value: " + opt;
    } else if (opt == "--sequence") {
      a.sequence = v;
    } else if (opt == "--replay") {
      a.replay = v;
    } else if (opt == "--far-range") {
      a.far_range = v;
    } else if (opt == "--plot") {
      a.plot = v;
    } else if (opt == "--timeline") {
      a.timeline = v;
    } else if (opt == "--max-far-direction-median-deg") {
      if (!parseNumber(v, x) || !(x >= 0.0))
        return "--max-far-direction-median-deg: expected >= 0, got '" + v + "'";
      a.req.check_far_direction = true;
      a.req.max_far_direction_median_deg = x;
    } else if (opt == "--max-far-distance-median-pct") {
      if (!parseNumber(v, x) || !(x >= 0.0))
        return "--max-far-distance-median-pct: expected >= 0, got '" + v + "'";
      a.req.check_far_distance = true;
      a.req.max_far_distance_median_pct = x;
    } else if (opt == "--require-final-mode") {
      if (!visnav::eval::parseReplayMode(v, a.req.final_mode))
        return "--require-final-mode: expected standby, far_range, acquisition or near_range, got '" + v +
               "'";
      a.req.check_final_mode = true;
    } else if (opt == "--csv") {
      a.csv = v;
    } else if (opt == "--json") {
      a.json = v;
    } else if (opt == "--envelope-px") {
      a.eval.envelope_px.clear();
      std::size_t start = 0;
      while (start <= v.size()) {
        const std::size_t comma = std::min(v.find(',', start), v.size());
        // Blanks after a comma are fine ("1.0, 0.25").
        const std::size_t first = std::min(v.find_first_not_of(" \t", start), comma);
        if (!parseNumber(v.substr(first, comma - first), x) || !(x >= 0.0) || x > 100.0)
          return "--envelope-px: expected comma-separated sizes in [0, 100] px, got '" + v + "'";
        a.eval.envelope_px.push_back(x);
        start = comma + 1;
      }
    } else if (opt == "--symmetry") {
      const int axis = v == "x180" ? 0 : (v == "y180" ? 1 : (v == "z180" ? 2 : -1));
      if (axis < 0) return "--symmetry: expected x180, y180 or z180, got '" + v + "'";
      a.eval.model_symmetries.push_back(
          Eigen::AngleAxisd(visnav::kPi, visnav::Vec3::Unit(axis)).toRotationMatrix());
    } else if (opt == "--envelope-stride") {
      long long n = 0;
      if (!visnav::cli::parseInteger(v, 1, INT_MAX, n))
        return "--envelope-stride: expected a positive integer, got '" + v + "'";
      a.eval.envelope_stride = static_cast<int>(n);
    } else if (opt == "--min-inside-fraction") {
      if (!parseNumber(v, x) || x < 0.0 || x > 1.0)
        return "--min-inside-fraction: expected [0, 1], got '" + v + "'";
      a.req.check_inside = true;
      a.req.min_inside_fraction = x;
    } else if (opt == "--inside-envelope-px") {
      if (!parseNumber(v, x) || x < 0.0)
        return "--inside-envelope-px: expected a size in px, got '" + v + "'";
      a.req.inside_envelope_px = x;
      a.inside_px_given = true;
    } else {
      return "unknown option: " + opt;
    }
  }
  if (a.sequence.empty() || a.replay.empty()) return "--sequence and --replay are required";
  std::vector<double>& env = a.eval.envelope_px;
  if (!a.inside_px_given && !env.empty())
    a.req.inside_envelope_px = *std::min_element(env.begin(), env.end());
  if (a.req.check_inside && std::find(env.begin(), env.end(), a.req.inside_envelope_px) == env.end())
    env.push_back(a.req.inside_envelope_px);  // the requirement needs that envelope computed
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace visnav;
  Args args;
  const std::string arg_error = parseArgs(argc, argv, args);
  if (arg_error == "help" || arg_error == "version")
    return cli::standardOption(arg_error == "help" ? "--help" : "--version", "visnav-eval", kUsage);
  if (!arg_error.empty()) {
    std::cerr << "visnav-eval: " << arg_error << '\n' << kUsage;
    return kExitUsage;
  }

  replay::Sequence seq;
  LoadError err = replay::loadSequence(args.sequence, seq);
  if (!err.ok) {
    std::cerr << "visnav-eval: " << err.message << '\n';
    return kExitInvalidInput;
  }
  if (seq.truth.empty()) {
    std::cerr << "visnav-eval: " << args.sequence
              << ": sequence has no truth (truth.csv), nothing to score\n";
    return kExitInvalidInput;
  }
  std::vector<eval::ReplayRow> rows;
  err = eval::loadReplayCsv(args.replay, rows);
  if (!err.ok) {
    std::cerr << "visnav-eval: " << err.message << '\n';
    return kExitInvalidInput;
  }
  if (!args.far_range.empty()) {
    int unmatched = 0;
    err = eval::joinFarRangeCsv(args.far_range, rows, unmatched);
    if (!err.ok) {
      std::cerr << "visnav-eval: " << err.message << '\n';
      return kExitInvalidInput;
    }
    if (unmatched > 0) std::cout << "far-range rows without a replay row (ignored): " << unmatched << '\n';
  }
  std::vector<eval::TruthPose> truth;
  truth.reserve(seq.truth.size());
  for (const replay::TruthRow& t : seq.truth) truth.push_back({t.frame, t.timestamp_ns, t.pose});

  const auto t0 = std::chrono::steady_clock::now();
  const eval::Evaluation ev = eval::evaluate(PinholeCamera(seq.camera), seq.model, truth, rows, args.eval);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (const char* problem = eval::nothingToScore(ev.summary)) {
    std::cerr << "visnav-eval: " << args.replay << ": " << problem << '\n';
    return kExitInvalidInput;
  }
  const std::vector<eval::RequirementResult> req = eval::checkRequirements(ev, args.req);

  std::cout << "sequence " << (seq.name.empty() ? args.sequence : seq.name) << ", replay " << args.replay
            << '\n'
            << eval::summaryText(ev);
  std::printf("evaluation time: %.2f s (envelopes on every %d. frame)\n", seconds, args.eval.envelope_stride);

  if (!args.plot.empty()) err = eval::writeErrorPlot(args.plot, ev);
  if (err.ok && !args.timeline.empty()) err = eval::writeModeTimeline(args.timeline, ev);
  if (err.ok && !args.csv.empty()) err = eval::writeFrameCsv(args.csv, ev);
  if (err.ok && !args.json.empty())
    err = eval::writeSummaryJson(args.json, ev, req, args.sequence, args.replay);
  if (!err.ok) {
    std::cerr << "visnav-eval: " << err.message << '\n';
    return kExitInvalidInput;
  }

  bool passed = true;
  for (const eval::RequirementResult& r : req) {
    std::cout << (r.passed ? "PASSED" : "FAILED") << " requirement " << r.name << ": " << r.detail << '\n';
    passed = passed && r.passed;
  }
  return passed ? kExitOk : kExitFailed;
}
