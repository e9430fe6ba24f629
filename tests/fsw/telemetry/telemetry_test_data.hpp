// Deterministic flight records for the telemetry tests: sample i of a run has values derived from i, so a
// receiver (in-process or another process) can check every field against an independent recomputation.
#pragma once

#include <cstdint>
#include <string>

#include "visnav/navigation/nav_solution.hpp"
#include "visnav/telemetry/telemetry_params.hpp"

namespace visnav::telemetry::test {

/// NavSolution number i (1-based): near range with a valid pose, except every 7th (lost) and every 11th
/// (far range, no pose); a pose rotating and approaching with i; covariance with distinct entries.
nav::NavSolution makeNavSolution(std::uint64_t i);
/// HealthRecord number i with distinct values in every field.
nav::HealthRecord makeHealthRecord(std::uint64_t i);

/// Telemetry params on a partition no other test or process uses ("<name>-<pid>").
TelemetryParams uniqueLinkParams(const std::string& name);
/// A DDS domain of this test process's own (100-199, from the pid): participants of other DDS users on the
/// host (a running visnavd, another test) are not discovered, so their traffic cannot reach the allocation
/// counts. Peer processes must be given it (`--domain`).
int isolatedDomainId();
/// uniqueLinkParams() on isolatedDomainId().
TelemetryParams isolatedLinkParams(const std::string& name);

}  // namespace visnav::telemetry::test
