// visnav-closedloop: a chaser flies itself from far range to a hold point in front of a tumbling target on
// visnav's solution alone (libvisnav's C ABI), next to the same guidance fed the truth. See README.md.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "visnav/cli/standard_options.hpp"
#include "visnav/closedloop/report.hpp"
#include "visnav/closedloop/scenario.hpp"
#include "visnav/closedloop/simulation.hpp"

namespace {

void usage(std::FILE* stream) {
  std::fputs(
      "usage: visnav-closedloop --scenario ci|200|750 [--out DIR] [--config-dir DIR] [--require-arrival]\n"
      "       visnav-closedloop --help | --version\n"
      "Flies a chaser (double integrator, thrust and rate limits, carrying the camera) from far range to a "
      "hold\n"
      "point 5 m in front of the tumbling plate on visnav's solution only, then the same guidance fed the "
      "truth;\n"
      "prints arrival time, final errors, delta-v of both and the mode timeline; DIR gets closedloop.csv "
      "and\n"
      "closedloop.png (tools/closedloop/README.md). Exit code: 0 done, 1 --require-arrival and the visnav "
      "run\n"
      "did not arrive within the gates, 2 usage, 3 a config, camera or model that does not load, or an "
      "output\n"
      "that cannot be written. --config-dir: the folder with closedloop.toml,\n"
      "cameras/ and models/ (default: the source tree's config/, else the installed share/visnav/config).\n",
      stream);
}

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;

}  // namespace

int main(int argc, char** argv) {
  std::string scenario, out_dir;
  std::string config_dir = std::filesystem::exists(VISNAV_SOURCE_DIR "/config/closedloop.toml")
                               ? VISNAV_SOURCE_DIR "/config"
                               : VISNAV_INSTALLED_CONFIG_DIR;
  bool require = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-closedloop", usage); code >= 0)
      return code;
    if (arg == "--scenario" && i + 1 < argc) {
      scenario = argv[++i];
    } else if (arg == "--out" && i + 1 < argc) {
      out_dir = argv[++i];
    } else if (arg == "--config-dir" && i + 1 < argc) {
      config_dir = argv[++i];
    } else if (arg == "--require-arrival") {
      require = true;
    } else {
      std::fprintf(stderr, "visnav-closedloop: unknown or incomplete argument '%s'\n", arg.c_str());
      usage(stderr);
      return kExitUsage;
    }
  }
  visnav::closedloop::ScenarioParams params;
  if (!visnav::closedloop::presetScenario(scenario, config_dir, params)) {
    std::fprintf(stderr, "visnav-closedloop: --scenario must be ci, 200 or 750 (got '%s')\n",
                 scenario.c_str());
    return kExitUsage;
  }
  visnav::closedloop::RunResult with_visnav, with_truth;
  if (visnav::LoadError e = visnav::closedloop::runClosedLoop(params, true, with_visnav); !e.ok) {
    std::fprintf(stderr, "visnav-closedloop: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  if (visnav::LoadError e = visnav::closedloop::runClosedLoop(params, false, with_truth); !e.ok) {
    std::fprintf(stderr, "visnav-closedloop: %s\n", e.message.c_str());
    return kExitInvalidInput;
  }
  visnav::closedloop::printSummary(stdout, params, with_visnav, with_truth);
  if (!out_dir.empty()) {
    for (const auto& [name, e] :
         {std::make_pair("closedloop.csv",
                         visnav::closedloop::writeCsv(out_dir + "/closedloop.csv", with_visnav, with_truth)),
          std::make_pair("closedloop.png", visnav::closedloop::writePlot(out_dir + "/closedloop.png", params,
                                                                         with_visnav, with_truth))}) {
      if (!e.ok) {
        std::fprintf(stderr, "visnav-closedloop: %s: %s\n", name, e.message.c_str());
        return kExitInvalidInput;
      }
    }
    std::printf("  wrote %s/closedloop.csv and %s/closedloop.png\n", out_dir.c_str(), out_dir.c_str());
  }
  const bool ok = with_visnav.arrived && with_visnav.final_position_error_m < params.gate_position_m &&
                  with_visnav.final_attitude_error_deg < params.gate_attitude_deg;
  if (require && !ok) {
    std::fputs("visnav-closedloop: the visnav run did not arrive within the gates\n", stderr);
    return kExitFailed;
  }
  return kExitOk;
}
