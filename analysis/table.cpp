#include "analysis/table.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace hvi::analysis {

namespace fs = std::filesystem;

namespace {

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  const auto e = s.find_last_not_of(" \t\r\"");
  return b == std::string::npos ? std::string{} : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    out.push_back(
        trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

}  // namespace

int Table::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

double Table::number(std::size_t row, int c) const {
  if (c < 0) return NAN;
  const std::string& s = rows[row][c];
  if (s.empty() || s == "NP" || s == "NA" || s == "nan" || s == "NaN") return NAN;
  if (s == "true") return 1.0;
  if (s == "false") return 0.0;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() ? v : NAN;
}

void Table::append(const Table& other) {
  for (const auto& c : other.columns)
    if (column(c) < 0) {
      columns.push_back(c);
      for (auto& r : rows) r.emplace_back();
    }
  for (std::size_t i = 0; i < other.rows.size(); ++i) {
    std::vector<std::string> row(columns.size());
    for (std::size_t k = 0; k < other.columns.size(); ++k)
      row[column(other.columns[k])] = other.rows[i][k];
    rows.push_back(std::move(row));
    labels.push_back(other.labels[i]);
  }
}

Table read_csv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path.string()));
  Table t;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (trim(line).empty() || trim(line)[0] == '#') continue;
    auto cells = split(line);
    if (t.columns.empty()) {
      t.columns = std::move(cells);
      continue;
    }
    if (cells.size() != t.columns.size())
      throw std::runtime_error(fmt::format("{}:{}: {} cells for {} columns", path.string(), number,
                                           cells.size(), t.columns.size()));
    t.rows.push_back(std::move(cells));
    t.labels.push_back(fmt::format("{}:{}", path.string(), number));
  }
  if (t.columns.empty()) throw std::runtime_error(fmt::format("{}: no header line", path.string()));
  return t;
}

Table read_table_or_runs(const fs::path& path) {
  if (!fs::is_directory(path)) return read_csv(path);
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(path))
    if (entry.is_regular_file() && entry.path().filename() == "measurements.csv")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty())
    throw std::runtime_error(fmt::format(
        "{}: no measurements.csv below it (run hvi measure on each run)", path.string()));
  Table t;
  for (const auto& f : files) t.append(read_csv(f));
  return t;
}

}  // namespace hvi::analysis
