#include "study/run_tables.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace cleave::study {

int Table::column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

Table read_table(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error(csv.string() + ": cannot open");
  Table t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(csv.string() + ": empty (no header)");
  for (std::stringstream ss(line); std::getline(ss, line, ',');) t.header.push_back(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      row.push_back(end != cell.c_str() && *end == '\0' ? v : std::numeric_limits<double>::quiet_NaN());
    }
    if (row.size() == t.header.size()) t.rows.push_back(std::move(row));  // a row cut by a stop is left out
  }
  return t;
}

Series column_series(const Table& t, const std::filesystem::path& file, const std::string& column,
                     const std::map<std::string, double>& where) {
  auto need = [&](const std::string& name) {
    const int c = t.column(name);
    if (c < 0) {
      std::string cols;
      for (const auto& h : t.header) cols += (cols.empty() ? "" : ", ") + h;
      throw std::runtime_error(file.string() + ": no column '" + name + "' (it has " + cols + ")");
    }
    return c;
  };
  const int c = need(column);
  std::vector<std::pair<int, double>> filters;
  for (const auto& [k, v] : where) filters.push_back({need(k), v});
  Series s;
  for (const auto& row : t.rows) {
    bool ok = true;
    for (const auto& [fc, v] : filters) ok = ok && row[fc] == v;
    if (ok) s.t.push_back(row[0]), s.y.push_back(row[c]);
  }
  if (s.t.empty()) throw std::runtime_error(file.string() + ": no row of '" + column + "' matches the study's where");
  return s;
}

double interpolate(const Series& s, double t) {
  if (s.t.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (t <= s.t.front()) return s.y.front();
  if (t >= s.t.back()) return s.y.back();
  const auto it = std::upper_bound(s.t.begin(), s.t.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - s.t.begin());
  const double t0 = s.t[k - 1], t1 = s.t[k];
  const double w = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
  return (1 - w) * s.y[k - 1] + w * s.y[k];
}

}  // namespace cleave::study
