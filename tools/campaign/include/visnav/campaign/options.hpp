// visnav-campaign's command line (tools/campaign/README.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "visnav/campaign/scene.hpp"
#include "visnav/core/status.hpp"

namespace visnav::campaign {

struct Gates {
  bool tracked_fraction = false;
  double min_tracked_fraction = 0.0;
  bool no_confident_wrong = false;
  bool recovery = false;
  int max_recovery_frames = 0;
  bool mode_changes = false;
  int max_mode_changes = 0;
};

/// Which of the drawn scenes run (--kind): a scene's kind is drawn from its seed with the rest of it.
enum class SceneKind { kAny, kNear, kApproach };

struct CampaignOptions {
  int runs = 0;  ///< scenes per family (0 with --case)
  std::uint64_t seed = 1;
  std::vector<Family> families;  ///< default: all five
  bool families_given = false;
  SceneKind kind = SceneKind::kAny;  ///< --kind: run only the near or only the approach scenes of the seeds
  std::string model_path;            ///< the "cao" family's model (empty: config/models/plate_2300x1800.cao)
  std::string config_path;           ///< visnavd whole config (empty: built-in defaults)
  int jobs = 1;
  std::string out_dir = "out/campaign";
  std::vector<std::string> cases;  ///< --case NAME|all (instead of random scenes)
  int max_frames = 0;              ///< 0: no cap
  bool timing = true;              ///< --no-timing: no clock, timing fields 0
  bool quiet = false;              ///< --quiet: no per-scene progress lines on stderr
  bool frames_csv = false;         ///< --frames: also DIR/frames.csv (one row per frame)
  bool trace = false;              ///< --trace: one diagnostic line per frame on stderr (runner.hpp)
  bool oracle = false;             ///< --oracle: image support of every untracked visible frame (runner.hpp)
  std::string dump_frames_dir;     ///< --dump-frames DIR: every rendered frame as a PGM (runner.hpp)
  Gates gates;
  bool help = false;
};

std::string usageText();

/// Parses argv[1..]. Errors name the option; `out` is complete only on success.
LoadError parseArguments(const std::vector<std::string>& args, CampaignOptions& out);

/// The command that reruns one scene alone (same model, config and frame cap).
std::string rerunCommand(const Scene& scene, const CampaignOptions& options);

}  // namespace visnav::campaign
