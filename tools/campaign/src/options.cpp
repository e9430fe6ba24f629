#include "visnav/campaign/options.hpp"

#include <limits>

#include "visnav/cli/numbers.hpp"

namespace visnav::campaign {

std::string usageText() {
  return "usage: visnav-campaign --runs N [--seed S] [--families plate,octagon,box,smallsat,cao]\n"
         "                       [--kind near|approach] [--model FILE.cao|.toml] [--config FILE]\n"
         "                       [--jobs J] [--out DIR] [--dump-frames DIR]\n"
         "                       [--max-frames N] [--no-timing] [--quiet] [--frames] [--trace] [--oracle]\n"
         "                       [--require-tracked-fraction F] [--require-no-confident-wrong]\n"
         "                       [--require-recovery-frames K] [--require-max-mode-changes M]\n"
         "       visnav-campaign --case NAME|all [same options]   (tumbling_box, eclipse_box, slew_box,\n"
         "                       low_contrast_octagon, approach_smallsat)\n"
         "Seeded Monte Carlo campaign: N random scenes per family (scene seeds S, S+1, ..., S+N-1), each "
         "run\n"
         "through the whole flight pipeline in memory and scored against its truth. Writes "
         "DIR/campaign.json,\n"
         "DIR/scenes.csv and DIR/campaign.png (default DIR out/campaign; --frames adds DIR/frames.csv).\n"
         "Exit 0: every gate holds; 1: a gate failed (the worst scene and the command to rerun it are\n"
         "printed); 2: bad arguments or files.\n"
         "Details: tools/campaign/README.md\n";
}

LoadError parseArguments(const std::vector<std::string>& args, CampaignOptions& out) {
  CampaignOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& v) {
      if (i + 1 >= args.size()) return false;
      v = args[++i];
      return true;
    };
    std::string v;
    long long n = 0;
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--no-timing") {
      o.timing = false;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (a == "--frames") {
      o.frames_csv = true;
    } else if (a == "--trace") {
      o.trace = true;
    } else if (a == "--oracle") {
      o.oracle = true;
    } else if (a == "--require-no-confident-wrong") {
      o.gates.no_confident_wrong = true;
    } else if (a == "--runs" || a == "--jobs" || a == "--max-frames" || a == "--require-recovery-frames" ||
               a == "--require-max-mode-changes") {
      if (!value(v)) return LoadError::failure(a + ": needs a value");
      const long long lo = a == "--runs" || a == "--jobs" ? 1 : 0;
      const long long hi = a == "--jobs" ? 64 : 1000000;
      if (!cli::parseInteger(v, lo, hi, n)) {
        std::string message = a;
        message += ": expected an integer in [" + std::to_string(lo);
        message += ", " + std::to_string(hi);
        message += "], got '" + v + "'";
        return LoadError::failure(message);
      }
      const int k = static_cast<int>(n);
      if (a == "--runs") o.runs = k;
      if (a == "--jobs") o.jobs = k;
      if (a == "--max-frames") o.max_frames = k;
      if (a == "--require-recovery-frames") {
        o.gates.recovery = true;
        o.gates.max_recovery_frames = k;
      }
      if (a == "--require-max-mode-changes") {
        o.gates.mode_changes = true;
        o.gates.max_mode_changes = k;
      }
    } else if (a == "--seed") {
      unsigned long long seed = 0;
      if (!value(v) || !cli::parseUnsigned(v, std::numeric_limits<std::uint64_t>::max(), seed))
        return LoadError::failure("--seed: expected an unsigned 64-bit integer" +
                                  (v.empty() ? "" : ", got '" + v + "'"));
      o.seed = static_cast<std::uint64_t>(seed);
    } else if (a == "--require-tracked-fraction") {
      double f = 0.0;
      if (!value(v) || !cli::parseNumber(v, f) || f < 0.0 || f > 1.0)
        return LoadError::failure("--require-tracked-fraction: expected a fraction in [0, 1]" +
                                  (v.empty() ? "" : ", got '" + v + "'"));
      o.gates.tracked_fraction = true;
      o.gates.min_tracked_fraction = f;
    } else if (a == "--families") {
      if (!value(v)) return LoadError::failure("--families: needs a comma-separated list");
      o.families.clear();
      std::size_t start = 0;
      while (start <= v.size()) {
        const std::size_t comma = v.find(',', start);
        const std::string name =
            v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        Family f = Family::kPlate;
        if (!parseFamily(name, f))
          return LoadError::failure("--families: unknown family '" + name +
                                    "' (plate, octagon, box, smallsat, cao)");
        bool dup = false;
        for (Family g : o.families) dup = dup || g == f;
        if (dup) return LoadError::failure("--families: '" + name + "' given twice");
        o.families.push_back(f);
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      o.families_given = true;
    } else if (a == "--kind") {
      if (!value(v) || (v != "near" && v != "approach"))
        return LoadError::failure("--kind: expected near or approach" +
                                  (v.empty() ? "" : ", got '" + v + "'"));
      o.kind = v == "near" ? SceneKind::kNear : SceneKind::kApproach;
    } else if (a == "--model" || a == "--config" || a == "--out" || a == "--case" || a == "--dump-frames") {
      if (!value(v) || v.empty()) return LoadError::failure(a + ": needs a value");
      if (a == "--model") o.model_path = v;
      if (a == "--config") o.config_path = v;
      if (a == "--out") o.out_dir = v;
      if (a == "--dump-frames") o.dump_frames_dir = v;
      if (a == "--case") {
        if (v == "all") {
          o.cases = caseNames();
        } else {
          bool known = false;
          for (const std::string& c : caseNames()) known = known || c == v;
          if (!known) {
            std::string list;
            for (const std::string& c : caseNames()) list += c + ", ";
            std::string message = "--case: unknown case '" + v;
            message += "' (" + list + "all)";
            return LoadError::failure(message);
          }
          bool dup = false;
          for (const std::string& c : o.cases) dup = dup || c == v;
          if (!dup) o.cases.push_back(v);
        }
      }
    } else {
      return LoadError::failure("unknown option '" + a + "' (--help lists them)");
    }
  }
  if (o.help) {
    out = o;
    return LoadError::success();
  }
  if (o.cases.empty() && o.runs <= 0) return LoadError::failure("--runs N (or --case NAME) is required");
  if (!o.cases.empty() && (o.runs > 0 || o.families_given || o.kind != SceneKind::kAny))
    return LoadError::failure(
        "--case runs the named scenes only: do not combine it with --runs, --families or --kind");
  if (o.families.empty())
    for (int f = 0; f < kFamilyCount; ++f) o.families.push_back(static_cast<Family>(f));
  out = o;
  return LoadError::success();
}

std::string rerunCommand(const Scene& scene, const CampaignOptions& o) {
  std::string cmd = "visnav-campaign";
  if (scene.is_case) {
    cmd += " --case " + scene.name;
  } else {
    cmd += " --runs 1 --seed " + std::to_string(scene.seed) + " --families " + toString(scene.family);
    if (scene.family == Family::kCao && !o.model_path.empty()) cmd += " --model " + o.model_path;
  }
  if (!o.config_path.empty()) cmd += " --config " + o.config_path;
  if (o.max_frames > 0) cmd += " --max-frames " + std::to_string(o.max_frames);
  if (o.trace) cmd += " --trace";
  if (o.oracle) cmd += " --oracle";
  return cmd;
}

}  // namespace visnav::campaign
