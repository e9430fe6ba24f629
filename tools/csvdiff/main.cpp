// visnav-csvdiff: numeric comparison of two CSV files with the same header (e.g. the x86 and the arm64
// visnav-replay output of one sequence). Exit codes (README.md "Exit codes", visnav::cli): 0 every cell
// matches, 1 a difference (cells, header or row count), 2 usage, 3 a file that cannot be read or is not a CSV
// table.
//   visnav-csvdiff A.csv B.csv [--abs-tol X] [--rel-tol R] [--column-tol PATTERN=ABS[:REL]]...
//                  [--ignore COL[,COL...]] [--ignore-prefix P]
// Numeric cells match when |a - b| <= abs_tol + rel_tol * max(|a|, |b|), with the tolerance of the first
// --column-tol whose PATTERN (a column name, or a prefix followed by '*') matches; other cells must be equal.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "visnav/cli/numbers.hpp"
#include "visnav/cli/standard_options.hpp"
#include "visnav/csvdiff/csv_compare.hpp"

namespace {

const char* const kUsage =
    "usage: visnav-csvdiff A.csv B.csv [--abs-tol X] [--rel-tol R] [--column-tol PATTERN=ABS[:REL]]...\n"
    "                      [--ignore COL,...] [--ignore-prefix P]\n"
    "       visnav-csvdiff --help | --version\n"
    "Compares two CSV files with the same header cell by cell, numbers within a tolerance\n"
    "(|a - b| <= abs + rel * max(|a|, |b|); --column-tol PATTERN is a column name or a prefix and '*').\n"
    "  exit code: 0 every cell matches, 1 a difference (cells, header or row count), 2 usage,\n"
    "  3 a file that cannot be read or is not a CSV table (empty, rows with a different cell count)\n";

using visnav::cli::kExitFailed;
using visnav::cli::kExitInvalidInput;
using visnav::cli::kExitOk;
using visnav::cli::kExitUsage;

/// A whole-argument finite number >= 0 ("1e-6"; not "", "x", "1x", "inf" or a negative one).
bool parseTolerance(const char* text, double& out) {
  double v = 0.0;
  if (!visnav::cli::parseNumber(text, v) || v < 0.0) return false;
  out = v;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  visnav::csvdiff::CompareOptions options;
  std::string paths[2];
  int n_paths = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (const int code = visnav::cli::standardOption(argv[i], "visnav-csvdiff", kUsage); code >= 0)
      return code;
    if ((arg == "--abs-tol" || arg == "--rel-tol") && has_value) {
      double& tol = arg == "--abs-tol" ? options.abs_tol : options.rel_tol;
      if (!parseTolerance(argv[++i], tol)) {
        std::fprintf(stderr, "visnav-csvdiff: %s wants a number >= 0, got '%s'\n", arg.c_str(), argv[i]);
        return kExitUsage;
      }
    } else if (arg == "--column-tol" && has_value) {
      visnav::csvdiff::ColumnTolerance rule;
      if (!visnav::csvdiff::parseColumnTolerance(argv[++i], rule)) {
        std::fprintf(stderr, "visnav-csvdiff: --column-tol wants PATTERN=ABS[:REL], got '%s'\n", argv[i]);
        return kExitUsage;
      }
      options.column_tols.push_back(rule);
    } else if (arg == "--ignore" && has_value) {
      visnav::csvdiff::splitInto(argv[++i], ',', options.ignored_columns);
    } else if (arg == "--ignore-prefix" && has_value) {
      options.ignored_prefixes.push_back(argv[++i]);
    } else if (n_paths < 2 && !arg.empty() && arg[0] != '-') {
      paths[n_paths++] = arg;
    } else {
      std::fprintf(stderr, "visnav-csvdiff: unknown or incomplete argument '%s'\n", arg.c_str());
      std::fputs(kUsage, stderr);
      return kExitUsage;
    }
  }
  if (n_paths != 2) {
    std::fprintf(stderr, "visnav-csvdiff: two CSV files needed\n%s", kUsage);
    return kExitUsage;
  }
  visnav::csvdiff::CompareReport report;
  std::string error;
  if (!visnav::csvdiff::compareCsvFiles(paths[0], paths[1], options, report, error)) {
    if (report.shape_differs) {  // two tables that differ in shape: a difference, like a cell's
      std::printf("DIFFERENT: %s\n", error.c_str());
      return kExitFailed;
    }
    std::fprintf(stderr, "visnav-csvdiff: %s\n", error.c_str());
    return kExitInvalidInput;
  }
  std::fputs(visnav::csvdiff::formatReport(report, options).c_str(), stdout);
  return report.mismatched_cells == 0 ? kExitOk : kExitFailed;
}
