// visnav-csvdiff: numeric comparison of two CSV files with the same header (e.g. the x86 and the arm64
// visnav-replay output of one sequence). Exit 0 when every cell matches, 1 on a difference, 2 on bad input.
//   visnav-csvdiff A.csv B.csv [--abs-tol X] [--rel-tol R] [--column-tol PATTERN=ABS[:REL]]...
//                  [--ignore COL[,COL...]] [--ignore-prefix P]
// Numeric cells match when |a - b| <= abs_tol + rel_tol * max(|a|, |b|), with the tolerance of the first
// --column-tol whose PATTERN (a column name, or a prefix followed by '*') matches; other cells must be equal.
#include <cstdio>
#include <string>

#include "visnav/cli/standard_options.hpp"
#include "visnav/csvdiff/csv_compare.hpp"

namespace {

const char* const kUsage =
    "usage: visnav-csvdiff A.csv B.csv [--abs-tol X] [--rel-tol R] [--column-tol PATTERN=ABS[:REL]]...\n"
    "                      [--ignore COL,...] [--ignore-prefix P]\n"
    "       visnav-csvdiff --help | --version\n"
    "Compares two CSV files with the same header cell by cell, numbers within a tolerance\n"
    "(|a - b| <= abs + rel * max(|a|, |b|); --column-tol PATTERN is a column name or a prefix and '*').\n"
    "  exit code: 0 every cell matches, 1 a difference, 2 usage or bad input\n";

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
    if (arg == "--abs-tol" && has_value) {
      options.abs_tol = std::stod(argv[++i]);
    } else if (arg == "--rel-tol" && has_value) {
      options.rel_tol = std::stod(argv[++i]);
    } else if (arg == "--column-tol" && has_value) {
      visnav::csvdiff::ColumnTolerance rule;
      if (!visnav::csvdiff::parseColumnTolerance(argv[++i], rule)) {
        std::fprintf(stderr, "visnav-csvdiff: --column-tol wants PATTERN=ABS[:REL], got '%s'\n", argv[i]);
        return 2;
      }
      options.column_tols.push_back(rule);
    } else if (arg == "--ignore" && has_value) {
      visnav::csvdiff::splitInto(argv[++i], ',', options.ignored_columns);
    } else if (arg == "--ignore-prefix" && has_value) {
      options.ignored_prefixes.push_back(argv[++i]);
    } else if (n_paths < 2 && !arg.empty() && arg[0] != '-') {
      paths[n_paths++] = arg;
    } else {
      std::fputs(kUsage, stderr);
      return 2;
    }
  }
  if (n_paths != 2) {
    std::fprintf(stderr, "visnav-csvdiff: two CSV files needed\n");
    return 2;
  }
  visnav::csvdiff::CompareReport report;
  std::string error;
  if (!visnav::csvdiff::compareCsvFiles(paths[0], paths[1], options, report, error)) {
    std::fprintf(stderr, "visnav-csvdiff: %s\n", error.c_str());
    return 2;
  }
  std::fputs(visnav::csvdiff::formatReport(report, options).c_str(), stdout);
  return report.mismatched_cells == 0 ? 0 : 1;
}
