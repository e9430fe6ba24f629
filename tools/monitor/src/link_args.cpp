#include "visnav/monitor/link_args.hpp"

#include <cstdlib>
#include <cstring>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/io/config_io.hpp"

namespace visnav::monitor {

bool parseLinkArgument(int argc, char** argv, int& i, telemetry::TelemetryParams& link, LoadError& error,
                       int& exit_code) {
  const char* arg = argv[i];
  exit_code = cli::kExitUsage;
  const bool has_value = i + 1 < argc;
  if (std::strcmp(arg, "--config") == 0 && has_value) {
    const std::string path = argv[++i];
    io::ConfigFile config;
    error = config.open(path);
    if (error.ok) error = telemetry::applyTelemetryConfig(config, link);
    exit_code = cli::kExitInvalidInput;  // a file that does not load or is invalid, not a usage error
    return true;
  }
  if (std::strcmp(arg, "--domain") == 0 && has_value) {
    long long domain = 0;
    if (!cli::parseInteger(argv[++i], 0, 232, domain))
      error = LoadError::failure(std::string("--domain wants 0..232, got '") + argv[i] + "'");
    else
      link.domain_id = static_cast<int>(domain);
    return true;
  }
  if (std::strcmp(arg, "--partition") == 0 && has_value) {
    const char* name = argv[++i];
    if (!telemetry::setPartition(link, name))
      error =
          LoadError::failure(std::string("--partition '") + name + "' " + telemetry::partitionProblem(name));
    return true;
  }
  return false;
}

}  // namespace visnav::monitor
