// Comparing the stats.csv of two runs column by column, leaving out the columns that measure time
// (they change from run to run even when the physics is identical).
#pragma once

#include <string>
#include <vector>

namespace haif {

/// One column whose values differ between the runs.
struct ColumnDiff {
  std::string column;
  int rows = 0;                ///< rows (steps) where the values differ
  int firstRow = -1;           ///< first such row (0 = the first step)
  std::string reference, test; ///< the values at firstRow
  double maxAbsDiff = 0.0;     ///< largest numeric difference (0 when the column is not numeric)
};

/// What compareStatsCsv found.
struct StatsDiff {
  int referenceRows = 0, testRows = 0;
  std::vector<std::string> ignoredColumns;  ///< timing columns left out
  std::vector<std::string> missingColumns;  ///< in one file only
  std::vector<ColumnDiff> differing;        ///< compared columns that differ
  bool equal() const { return referenceRows == testRows && missingColumns.empty() && differing.empty(); }
};

/// True for columns that measure wall-clock time: they are not compared.
bool isTimingColumn(const std::string& name);

/// Compares the CSV texts; false with an error naming `referenceName`/`testName` when either is not a
/// header-plus-rows CSV.
bool compareStatsCsv(const std::string& referenceCsv, const std::string& testCsv, const std::string& referenceName,
                     const std::string& testName, StatsDiff& out, std::string& error);

}  // namespace haif
