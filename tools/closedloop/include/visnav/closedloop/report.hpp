// visnav-closedloop's outputs: the printed summary, the per-frame CSV and the plot (range, errors against
// the gates, delta-v of both runs, visnav's mode timeline).
#pragma once

#include <cstdio>
#include <string>

#include "visnav/closedloop/scenario.hpp"
#include "visnav/closedloop/simulation.hpp"
#include "visnav/core/status.hpp"

namespace visnav::closedloop {

void printSummary(std::FILE* out, const ScenarioParams& params, const RunResult& visnav,
                  const RunResult& truth);
LoadError writeCsv(const std::string& path, const RunResult& visnav, const RunResult& truth);
LoadError writePlot(const std::string& path, const ScenarioParams& params, const RunResult& visnav,
                    const RunResult& truth);

}  // namespace visnav::closedloop
