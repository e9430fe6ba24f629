#include "visnav/csvdiff/csv_compare.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "visnav/cli/numbers.hpp"

namespace visnav::csvdiff {
namespace {

using Row = std::vector<std::string>;

bool readFile(const std::string& path, std::string& text) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  text = buffer.str();
  return true;
}

// Lines without their '\r\n' / '\n'; a trailing empty line is not a row.
std::vector<Row> parseRows(const std::string& text) {
  std::vector<Row> rows;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    Row row;
    splitInto(line, ',', row);
    rows.push_back(std::move(row));
  }
  return rows;
}

// Whole-cell number ("12abc" and "" are not numbers; "nan" and "inf" are).
bool asNumber(const std::string& cell, double& value) {
  if (cell.empty()) return false;
  errno = 0;
  char* end = nullptr;
  value = std::strtod(cell.c_str(), &end);
  return end == cell.c_str() + cell.size();
}

bool isIgnored(const std::string& name, const CompareOptions& options) {
  if (std::find(options.ignored_columns.begin(), options.ignored_columns.end(), name) !=
      options.ignored_columns.end())
    return true;
  for (const std::string& prefix : options.ignored_prefixes)
    if (name.compare(0, prefix.size(), prefix) == 0) return true;
  return false;
}

}  // namespace

void splitInto(const std::string& text, char separator, std::vector<std::string>& out) {
  std::size_t begin = 0;
  for (;;) {
    const std::size_t end = text.find(separator, begin);
    out.push_back(text.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos) return;
    begin = end + 1;
  }
}

bool parseColumnTolerance(const std::string& text, ColumnTolerance& out) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) return false;
  out.pattern = text.substr(0, eq);
  const std::string values = text.substr(eq + 1);
  const std::size_t colon = values.find(':');
  out.rel_tol = 0.0;
  // Command-line numbers (visnav/cli/numbers.hpp, as --abs-tol and --rel-tol), not cells: "inf" is refused.
  if (!cli::parseNumber(values.substr(0, colon), out.abs_tol) || out.abs_tol < 0.0) return false;
  if (colon == std::string::npos) return true;
  return cli::parseNumber(values.substr(colon + 1), out.rel_tol) && out.rel_tol >= 0.0;
}

CompareOptions toleranceFor(const std::string& column, const CompareOptions& options) {
  CompareOptions chosen = options;
  for (const ColumnTolerance& rule : options.column_tols) {
    const bool prefix = !rule.pattern.empty() && rule.pattern.back() == '*';
    const std::string stem = prefix ? rule.pattern.substr(0, rule.pattern.size() - 1) : rule.pattern;
    if (prefix ? column.compare(0, stem.size(), stem) == 0 : column == stem) {
      chosen.abs_tol = rule.abs_tol;
      chosen.rel_tol = rule.rel_tol;
      break;
    }
  }
  return chosen;
}

bool cellsMatch(const std::string& a, const std::string& b, const CompareOptions& options, double& abs_diff) {
  abs_diff = 0.0;
  double x = 0.0;
  double y = 0.0;
  if (!asNumber(a, x) || !asNumber(b, y)) return a == b;
  if (std::isnan(x) || std::isnan(y)) return std::isnan(x) && std::isnan(y);
  if (x == y) return true;  // also equal infinities
  abs_diff = std::fabs(x - y);
  return abs_diff <= options.abs_tol + options.rel_tol * std::max(std::fabs(x), std::fabs(y));
}

bool compareCsv(const std::string& a, const std::string& b, const CompareOptions& options,
                CompareReport& report, std::string& error) {
  report = CompareReport{};
  const std::vector<Row> rows_a = parseRows(a);
  const std::vector<Row> rows_b = parseRows(b);
  if (rows_a.empty() || rows_b.empty()) {
    error = "empty CSV (no header)";
    return false;
  }
  if (rows_a.front() != rows_b.front()) {
    report.shape_differs = true;
    error = "headers differ";
    return false;
  }
  if (rows_a.size() != rows_b.size()) {
    report.shape_differs = true;
    error = "row counts differ: " + std::to_string(rows_a.size() - 1) + " vs " +
            std::to_string(rows_b.size() - 1);
    return false;
  }
  const Row& header = rows_a.front();
  std::vector<CompareOptions> column_options;
  for (const std::string& name : header) {
    report.columns.push_back({name, isIgnored(name, options), 0.0, 0});
    column_options.push_back(toleranceFor(name, options));
  }
  for (std::size_t r = 1; r < rows_a.size(); ++r) {
    if (rows_a[r].size() != header.size() || rows_b[r].size() != header.size()) {
      error = "data line " + std::to_string(r) + " has a different number of cells than the header";
      return false;
    }
    for (std::size_t c = 0; c < header.size(); ++c) {
      ColumnStats& column = report.columns[c];
      if (column.ignored) continue;
      ++report.compared_cells;
      double diff = 0.0;
      const bool match = cellsMatch(rows_a[r][c], rows_b[r][c], column_options[c], diff);
      column.max_abs_diff = std::max(column.max_abs_diff, diff);
      if (match) continue;
      ++column.mismatches;
      if (report.mismatched_cells++ == 0)
        report.first_mismatch = "data line " + std::to_string(r) + " column " + column.name + ": " +
                                rows_a[r][c] + " vs " + rows_b[r][c];
    }
  }
  report.rows = static_cast<int>(rows_a.size() - 1);
  return true;
}

bool compareCsvFiles(const std::string& path_a, const std::string& path_b, const CompareOptions& options,
                     CompareReport& report, std::string& error) {
  report = CompareReport{};
  std::string a;
  std::string b;
  if (!readFile(path_a, a)) {
    error = path_a + ": cannot read";
    return false;
  }
  if (!readFile(path_b, b)) {
    error = path_b + ": cannot read";
    return false;
  }
  if (!compareCsv(a, b, options, report, error)) {
    error = path_a + " vs " + path_b + ": " + error;
    return false;
  }
  return true;
}

std::string formatReport(const CompareReport& report, const CompareOptions& options) {
  std::string out;
  char line[256];
  int ignored = 0;
  for (const ColumnStats& column : report.columns) ignored += column.ignored ? 1 : 0;
  std::snprintf(line, sizeof line,
                "tolerance |a-b| <= %g + %g * max(|a|,|b|); %d rows, %d cells compared, %d columns ignored\n",
                options.abs_tol, options.rel_tol, report.rows, report.compared_cells, ignored);
  out += line;
  for (const ColumnStats& column : report.columns) {
    if (column.ignored || (column.max_abs_diff == 0.0 && column.mismatches == 0)) continue;
    std::snprintf(line, sizeof line, "  %-16s max |diff| %-12.4g mismatches %d\n", column.name.c_str(),
                  column.max_abs_diff, column.mismatches);
    out += line;
  }
  if (report.mismatched_cells == 0) {
    out += "match\n";
  } else {
    std::snprintf(line, sizeof line,
                  "DIFFERENT: %d cells outside the tolerance; first: ", report.mismatched_cells);
    out += line + report.first_mismatch + "\n";
  }
  return out;
}

}  // namespace visnav::csvdiff
