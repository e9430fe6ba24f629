// visnav-campaign: seeded Monte Carlo campaign over the whole flight pipeline (tools/campaign/README.md).
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

#include "visnav/app/visnav_config.hpp"
#include "visnav/campaign/options.hpp"
#include "visnav/campaign/report.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/io/model_io.hpp"

using namespace visnav;
using namespace visnav::campaign;

namespace {

/// A file under config/: the working directory's config/ first, then the source tree's, then the installed.
std::string findConfigFile(const std::string& relative) {
  const std::string candidates[] = {"config/" + relative,
                                    std::string(VISNAV_SOURCE_CONFIG_DIR) + "/" + relative,
                                    std::string(VISNAV_INSTALL_CONFIG_DIR) + "/" + relative};
  for (const std::string& c : candidates) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(c, ec)) return c;
  }
  return "";
}

bool needsFamily(const CampaignOptions& o, Family f) {
  if (!o.cases.empty()) return f == Family::kSmallsat;  // approach_smallsat; the other cases build theirs
  for (Family g : o.families)
    if (g == f) return true;
  return false;
}

/// A model, config or output that does not load or cannot be written, or a scene that cannot be set up:
/// exit 3 of the one exit-code table (README.md "Exit codes"); usage errors are 2.
int fail(const std::string& message) {
  std::fprintf(stderr, "visnav-campaign: %s\n", message.c_str());
  return cli::kExitInvalidInput;
}

}  // namespace

int main(int argc, char** argv) {
  CampaignOptions options;
  const std::vector<std::string> args(argv + 1, argv + argc);
  // --version alone; --help goes through the option parser (its usage text).
  if (args.size() == 1 && args[0] == "--version") {
    cli::printVersion("visnav-campaign");
    return cli::kExitOk;
  }
  if (LoadError e = parseArguments(args, options); !e.ok) {
    std::fprintf(stderr, "visnav-campaign: %s\n%s", e.message.c_str(), usageText().c_str());
    return cli::kExitUsage;
  }
  if (options.help) {
    std::fputs(usageText().c_str(), stdout);
    return cli::kExitOk;
  }

  ModelLibrary models;
  if (needsFamily(options, Family::kSmallsat)) {
    models.smallsat_path = findConfigFile("models/smallsat_panels.toml");
    if (models.smallsat_path.empty()) return fail("config/models/smallsat_panels.toml not found");
    if (LoadError e = io::loadModel(models.smallsat_path, models.smallsat); !e.ok) return fail(e.message);
  }
  if (needsFamily(options, Family::kCao)) {
    models.cao_path =
        options.model_path.empty() ? findConfigFile("models/plate_2300x1800.cao") : options.model_path;
    if (models.cao_path.empty())
      return fail("config/models/plate_2300x1800.cao not found (give --model FILE)");
    if (LoadError e = io::loadModel(models.cao_path, models.cao); !e.ok) return fail("--model: " + e.message);
  }
  nav::PipelineParams params;
  if (!options.config_path.empty()) {
    app::VisnavConfig config;
    if (LoadError e = app::loadVisnavConfig(options.config_path, config); !e.ok)
      return fail("--config: " + e.message);
    params = config.pipeline;
  }

  std::error_code ec;  // before the scenes run: a bad --out fails at once
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) return fail(options.out_dir + ": cannot create: " + ec.message());
  if (!options.dump_frames_dir.empty()) {
    std::filesystem::create_directories(options.dump_frames_dir, ec);
    if (ec) return fail(options.dump_frames_dir + ": cannot create: " + ec.message());
  }

  std::vector<SceneRun> runs;
  if (!options.cases.empty()) {
    for (const std::string& name : options.cases) {
      SceneRun run;
      if (LoadError e = makeCase(name, models, options.max_frames, run.scene); !e.ok) return fail(e.message);
      runs.push_back(std::move(run));
    }
  } else {
    for (Family f : options.families) {
      for (int i = 0; i < options.runs; ++i) {
        SceneRun run;
        if (LoadError e = drawScene(f, sceneSeed(options.seed, i), models, options.max_frames, run.scene);
            !e.ok)
          return fail(e.message);
        const SceneKind kind = run.scene.approach ? SceneKind::kApproach : SceneKind::kNear;
        if (options.kind != SceneKind::kAny && options.kind != kind) continue;
        runs.push_back(std::move(run));
      }
    }
  }
  std::printf("visnav-campaign: %zu scenes", runs.size());
  if (options.cases.empty())
    std::printf(" (%zu families x %d, scene seeds %llu..%llu)", options.families.size(), options.runs,
                static_cast<unsigned long long>(options.seed),
                static_cast<unsigned long long>(sceneSeed(options.seed, options.runs - 1)));
  std::printf(
      ", config %s%s\n", options.config_path.empty() ? "built-in defaults" : options.config_path.c_str(),
      options.max_frames > 0 ? (", at most " + std::to_string(options.max_frames) + " frames").c_str() : "");
  std::fflush(stdout);

  // Scenes are independent: workers take the next one; results land in scene order (deterministic output).
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> done{0};
  std::mutex print;
  auto worker = [&]() {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      runs[i].result = runScene(runs[i].scene, params, options.timing, Thresholds{}, options.trace,
                                options.oracle, options.dump_frames_dir);
      const std::size_t k = ++done;
      if (!options.quiet) {
        const std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "[%zu/%zu] %s\n", k, runs.size(), sceneLine(runs[i]).c_str());
      }
      if (options.trace) {
        const std::lock_guard<std::mutex> lock(print);
        std::fprintf(stderr, "trace %s:\n%s", runs[i].scene.name.c_str(), runs[i].result.trace.c_str());
      }
    }
  };
  const int jobs = std::max(1, std::min(options.jobs, static_cast<int>(runs.size())));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();

  const std::vector<GroupSummary> groups = summariseAll(runs);
  const std::vector<GateResult> gates = checkGates(runs, options.gates);
  if (runs.size() <= 12)
    for (const SceneRun& r : runs) std::printf("%s\n", sceneLine(r).c_str());
  std::fputs(summaryTable(groups, runs, options.timing).c_str(), stdout);
  std::fputs(lossTable(groups).c_str(), stdout);
  if (options.oracle) std::fputs(oracleTable(runs).c_str(), stdout);

  {
    std::ofstream json(options.out_dir + "/campaign.json");
    writeJson(json, options, runs, groups, gates);
    std::ofstream csv(options.out_dir + "/scenes.csv");
    writeCsv(csv, runs);
    if (options.frames_csv) {
      std::ofstream frames(options.out_dir + "/frames.csv");
      writeFramesCsv(frames, runs);
      if (!frames) return fail(options.out_dir + "/frames.csv: write failed");
    }
    if (!json || !csv) return fail(options.out_dir + ": write failed");
  }
  if (LoadError e =
          renderCampaignPlot(runs, groups, options.gates).writePng(options.out_dir + "/campaign.png");
      !e.ok)
    return fail(e.message);
  std::printf("wrote %s/campaign.json, scenes.csv, campaign.png\n", options.out_dir.c_str());

  bool not_run = false;
  for (const SceneRun& r : runs) not_run = not_run || !r.result.error.ok;
  if (not_run) return fail("some scenes did not run (see above)");
  bool passed = true;
  for (const GateResult& g : gates) {
    passed = passed && g.passed;
    std::printf("%s %s: %s", g.passed ? "gate passed" : "GATE FAILED", g.name.c_str(), g.detail.c_str());
    if (!g.passed && g.worst != nullptr)
      std::printf("; worst scene %s, rerun: %s", g.worst->scene.name.c_str(),
                  rerunCommand(g.worst->scene, options).c_str());
    std::printf("\n");
  }
  return passed ? cli::kExitOk : cli::kExitFailed;
}
