// visnav-csvdiff: the tolerance rule, ignored columns, and the inputs it must refuse.
#include <gtest/gtest.h>

#include <string>

#include "visnav/csvdiff/csv_compare.hpp"

namespace visnav::csvdiff {
namespace {

TEST(CsvDiff, NumericCellsWithinAbsoluteAndRelativeTolerance) {
  CompareOptions o;
  o.abs_tol = 1e-9;
  o.rel_tol = 1e-6;
  double diff = 0.0;
  // 1000 +- 1e-9 + 1e-6 * 1000.001 = 1.000002e-3: 0.0009 inside, 0.0011 outside.
  EXPECT_TRUE(cellsMatch("1000", "1000.0009", o, diff));
  EXPECT_NEAR(diff, 0.0009, 1e-12);
  EXPECT_FALSE(cellsMatch("1000", "1000.0011", o, diff));
  // Near zero only the absolute part counts.
  EXPECT_TRUE(cellsMatch("0", "5e-10", o, diff));
  EXPECT_FALSE(cellsMatch("0", "2e-9", o, diff));
  // Same number, different spelling.
  EXPECT_TRUE(cellsMatch("1.50", "1.5e0", CompareOptions{}, diff));
}

TEST(CsvDiff, TextAndSpecialValues) {
  double diff = 0.0;
  CompareOptions loose;
  loose.abs_tol = 1.0;
  EXPECT_TRUE(cellsMatch("tracking", "tracking", loose, diff));
  EXPECT_FALSE(cellsMatch("tracking", "degraded", loose, diff));
  EXPECT_FALSE(cellsMatch("12abc", "12", loose, diff));  // not a number: compared as text
  EXPECT_TRUE(cellsMatch("nan", "nan", loose, diff));
  EXPECT_FALSE(cellsMatch("nan", "0", loose, diff));
  EXPECT_TRUE(cellsMatch("inf", "inf", CompareOptions{}, diff));
}

TEST(CsvDiff, ReportsPerColumnAndIgnoresTimingColumns) {
  const std::string a = "frame,status,x_m,t_total_us\n0,tracking,1.0,30.5\n1,lost,2.0,31.0\n";
  const std::string b = "frame,status,x_m,t_total_us\r\n0,tracking,1.0000004,99.0\r\n1,lost,2.5,12.0\r\n";
  CompareOptions o;
  o.abs_tol = 1e-6;
  o.ignored_prefixes.push_back("t_");
  CompareReport report;
  std::string error;
  ASSERT_TRUE(compareCsv(a, b, o, report, error)) << error;
  EXPECT_EQ(report.rows, 2);
  EXPECT_EQ(report.compared_cells, 6);  // 3 columns x 2 rows, t_total_us ignored
  EXPECT_EQ(report.mismatched_cells, 1);
  ASSERT_EQ(report.columns.size(), 4U);
  EXPECT_TRUE(report.columns[3].ignored);
  EXPECT_EQ(report.columns[2].mismatches, 1);
  EXPECT_NEAR(report.columns[2].max_abs_diff, 0.5, 1e-12);
  EXPECT_EQ(report.first_mismatch, "data line 2 column x_m: 2.0 vs 2.5");
  EXPECT_NE(formatReport(report, o).find("DIFFERENT: 1 cells"), std::string::npos);
}

TEST(CsvDiff, ColumnTolerancesFirstMatchWins) {
  CompareOptions o;
  o.abs_tol = 1e-9;
  ColumnTolerance rule;
  ASSERT_TRUE(parseColumnTolerance("pitch_deg=0.3", rule));
  EXPECT_EQ(rule.pattern, "pitch_deg");
  EXPECT_DOUBLE_EQ(rule.abs_tol, 0.3);
  EXPECT_DOUBLE_EQ(rule.rel_tol, 0.0);
  o.column_tols.push_back(rule);
  ASSERT_TRUE(parseColumnTolerance("cov_*=1e-5:0.05", rule));
  EXPECT_EQ(rule.pattern, "cov_*");
  EXPECT_DOUBLE_EQ(rule.rel_tol, 0.05);
  o.column_tols.push_back(rule);
  EXPECT_FALSE(parseColumnTolerance("=1", rule));
  EXPECT_FALSE(parseColumnTolerance("x_m", rule));
  EXPECT_FALSE(parseColumnTolerance("x_m=abc", rule));
  EXPECT_FALSE(parseColumnTolerance("x_m=-1", rule));
  EXPECT_FALSE(parseColumnTolerance("x_m=1:", rule));

  EXPECT_DOUBLE_EQ(toleranceFor("pitch_deg", o).abs_tol, 0.3);
  EXPECT_DOUBLE_EQ(toleranceFor("pitch_deg_x", o).abs_tol, 1e-9);  // exact name, not a prefix
  EXPECT_DOUBLE_EQ(toleranceFor("cov_1_5", o).abs_tol, 1e-5);
  EXPECT_DOUBLE_EQ(toleranceFor("x_m", o).abs_tol, 1e-9);

  const std::string a = "x_m,pitch_deg,cov_0_0\n1.0,10.0,0.002\n";
  const std::string b = "x_m,pitch_deg,cov_0_0\n1.0,10.2,0.00209\n";  // pitch inside 0.3; cov 1e-5+1.05e-4
  CompareReport report;
  std::string error;
  ASSERT_TRUE(compareCsv(a, b, o, report, error)) << error;
  EXPECT_EQ(report.mismatched_cells, 0);
  const std::string c = "x_m,pitch_deg,cov_0_0\n1.000001,10.4,0.0023\n";  // all three outside
  ASSERT_TRUE(compareCsv(a, c, o, report, error)) << error;
  EXPECT_EQ(report.mismatched_cells, 3);
}

TEST(CsvDiff, RefusesDifferentShapes) {
  CompareReport report;
  std::string error;
  EXPECT_FALSE(compareCsv("a,b\n1,2\n", "a,c\n1,2\n", CompareOptions{}, report, error));
  EXPECT_EQ(error, "headers differ");
  EXPECT_TRUE(report.shape_differs);  // two tables that differ: visnav-csvdiff exit 1
  EXPECT_FALSE(compareCsv("a,b\n1,2\n", "a,b\n1,2\n3,4\n", CompareOptions{}, report, error));
  EXPECT_EQ(error, "row counts differ: 1 vs 2");
  EXPECT_TRUE(report.shape_differs);
  // Not a table, or not readable: an invalid input (exit 3), not a difference.
  EXPECT_FALSE(compareCsv("a,b\n1,2\n", "a,b\n1\n", CompareOptions{}, report, error));
  EXPECT_FALSE(report.shape_differs);
  EXPECT_FALSE(compareCsv("", "a\n", CompareOptions{}, report, error));
  EXPECT_FALSE(report.shape_differs);
  EXPECT_FALSE(compareCsvFiles("/nonexistent/a.csv", "/nonexistent/b.csv", CompareOptions{}, report, error));
  EXPECT_EQ(error, "/nonexistent/a.csv: cannot read");
  EXPECT_FALSE(report.shape_differs);
}

}  // namespace
}  // namespace visnav::csvdiff
