// What a study reads back from one run's folder: a table that `cleave run` writes (global.csv,
// crack_tips.csv, crack_fronts.csv) as columns of numbers, and one column as a time series.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cleave::study {

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;  // NaN where a cell is not a number
  int column(const std::string& name) const;  // -1 when absent
};

// Reads a CSV table with a header line. std::runtime_error naming the file when it cannot be read.
Table read_table(const std::filesystem::path& csv);

struct Series {
  std::vector<double> t, y;
};

// The column's values in the rows whose `where` columns equal the given values, against the
// table's first column (time). std::runtime_error naming the file and column when the column, or a
// `where` column, is absent, or no row matches.
Series column_series(const Table& t, const std::filesystem::path& file, const std::string& column,
                     const std::map<std::string, double>& where);

// Linear interpolation of a series at t (the end values outside it); NaN for an empty series.
double interpolate(const Series& s, double t);

}  // namespace cleave::study
