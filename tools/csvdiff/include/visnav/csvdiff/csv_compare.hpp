// Numeric CSV comparison (tools/csvdiff): same header, same number of rows, cell by cell within a tolerance.
#pragma once

#include <string>
#include <vector>

namespace visnav::csvdiff {

/// A tolerance for the columns matching `pattern`: a column name, or a name prefix followed by '*'.
struct ColumnTolerance {
  std::string pattern;
  double abs_tol = 0.0;
  double rel_tol = 0.0;
};

struct CompareOptions {
  double abs_tol = 0.0;  ///< numeric cells: |a - b| <= abs_tol + rel_tol * max(|a|, |b|)
  double rel_tol = 0.0;
  std::vector<ColumnTolerance> column_tols;   ///< per-column tolerances; the first match wins over the above
  std::vector<std::string> ignored_columns;   ///< exact column names not compared
  std::vector<std::string> ignored_prefixes;  ///< columns whose name starts with one of these
};

struct ColumnStats {
  std::string name;
  bool ignored = false;
  double max_abs_diff = 0.0;  ///< over the numeric cells
  int mismatches = 0;
};

struct CompareReport {
  int rows = 0;
  int compared_cells = 0;
  int mismatched_cells = 0;
  std::vector<ColumnStats> columns;
  std::string first_mismatch;  ///< "row R column C: a vs b", empty when none
  /// Set when the comparison failed because the headers or the row counts differ: two readable CSV files that
  /// differ (visnav-csvdiff exit 1), not an input that does not load (exit 3).
  bool shape_differs = false;
};

/// Splits `text` at `separator` and appends the pieces to `out`.
void splitInto(const std::string& text, char separator, std::vector<std::string>& out);

/// Parses "PATTERN=ABS" or "PATTERN=ABS:REL" (e.g. "cov_*=1e-5:0.05"). False on a malformed text.
bool parseColumnTolerance(const std::string& text, ColumnTolerance& out);

/// The tolerance that applies to `column` (a copy of `options` with abs_tol/rel_tol of the first match).
CompareOptions toleranceFor(const std::string& column, const CompareOptions& options);

/// True when the cells match: numerically within the tolerance, or as equal text when not both numbers.
bool cellsMatch(const std::string& a, const std::string& b, const CompareOptions& options, double& abs_diff);

/// Compares two CSV texts (first line the header). False with `error` when they cannot be compared
/// (different headers or row counts: `report.shape_differs`; an empty text or ragged rows).
bool compareCsv(const std::string& a, const std::string& b, const CompareOptions& options,
                CompareReport& report, std::string& error);

/// compareCsv on two files; `error` names the file that cannot be read.
bool compareCsvFiles(const std::string& path_a, const std::string& path_b, const CompareOptions& options,
                     CompareReport& report, std::string& error);

/// Human-readable summary: tolerance, rows, per-column largest difference (non-zero ones), verdict.
std::string formatReport(const CompareReport& report, const CompareOptions& options);

}  // namespace visnav::csvdiff
