#pragma once
// A small CSV table: a header of column names, then one row per line; '#' starts a comment line.
// Cells are text; number() reads one as a double, with an empty cell, "NP", "NA" and "nan" as
// missing (NaN) and "true"/"false" as 1/0.
#include <filesystem>
#include <string>
#include <vector>

namespace hvi::analysis {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // each as long as columns
  std::vector<std::string> labels;             // where each row comes from (file:line)

  // Index of `column`, or -1.
  int column(const std::string& name) const;
  // The cell as a number; NaN when missing or not a number.
  double number(std::size_t row, int column) const;
  // Appends the rows of `other`, adding its new columns (cells missing elsewhere stay empty).
  void append(const Table& other);
};

// Throws std::runtime_error for a file that cannot be read or a row of the wrong length.
Table read_csv(const std::filesystem::path& path);

// `path` itself if it is a file; for a directory, every measurements.csv below it (hvi measure's
// one-line tables), in path order, merged.
Table read_table_or_runs(const std::filesystem::path& path);

}  // namespace hvi::analysis
