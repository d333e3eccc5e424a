#include "rl/logging/scalar_csv_writer.hpp"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "base/input_file.hpp"
#include "base/number_text.hpp"
#include "base/split_fields.hpp"
#include "rl/runs/run_file_error.hpp"

namespace upkie_rl {

namespace {

std::string join(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) line += (i ? "," : "") + cells[i];
  return line;
}

std::string format_value(float value) {
  if (std::isnan(value)) return "";
  return shortest_text(value);
}

double parse_cell(const std::string& cell, const std::string& where) {
  if (cell.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::optional<double> value = number_from_text<double>(cell);
  if (!value) throw RunFileError(where + ": not a number: '" + cell + "'");
  return *value;
}

}  // namespace

ScalarCsvWriter::ScalarCsvWriter(const std::filesystem::path& path,
                                 std::vector<std::string> columns,
                                 std::optional<std::int64_t> resume_from_step)
    : path_(path), columns_(std::move(columns)) {
  std::vector<std::string> kept;
  if (resume_from_step && std::filesystem::exists(path)) {
    std::istringstream existing(
        read_input_file<std::runtime_error>(path, "scalar log", kMaxScalarLogBytes));
    std::string line;
    // An empty file (left by an older version killed while it rewrote the log) has no rows.
    if (std::getline(existing, line) && !line.empty() && line != join(columns_)) {
      throw RunFileError(path.string() + ": existing header differs from the logged tags");
    }
    while (std::getline(existing, line)) {
      if (line.empty()) continue;
      const std::vector<std::string> cells = split_fields(line);
      if (cells.empty() || cells[0].empty()) continue;
      double step = 0.0;
      try {
        step = parse_cell(cells[0], path.string());
      } catch (const std::runtime_error&) {
        continue;  // a line cut by a kill: drop it
      }
      if (cells.size() == columns_.size() && step <= static_cast<double>(*resume_from_step)) {
        kept.push_back(line);
      }
    }
  }
  if (!resume_from_step) {
    file_.open(path, std::ios::trunc);
    if (!file_) throw RunFileError("cannot write " + path.string());
    file_ << join(columns_) << '\n';
    file_.flush();
    return;
  }
  // The kept rows go to a file aside that replaces the old one in one rename: killed at any
  // moment, the log is either the old one or the new one, never cut.
  const std::filesystem::path aside = path.string() + ".tmp." + std::to_string(getpid());
  {
    std::ofstream out(aside, std::ios::trunc);
    out << join(columns_) << '\n';
    for (const std::string& line : kept) out << line << '\n';
    out.flush();
    if (!out) throw RunFileError("cannot write " + aside.string());
  }
  if (FILE* handle = std::fopen(aside.c_str(), "rb")) {
    fsync(fileno(handle));
    std::fclose(handle);
  }
  std::error_code error;
  std::filesystem::rename(aside, path, error);
  if (error) {
    std::filesystem::remove(aside, error);
    throw RunFileError("cannot replace " + path.string() + ": " + error.message());
  }
  file_.open(path, std::ios::app);
  if (!file_) throw RunFileError("cannot write " + path.string());
}

void ScalarCsvWriter::write_row(std::span<const ScalarValue> scalars) {
  std::vector<std::string> cells(columns_.size());
  for (const ScalarValue& scalar : scalars) {
    for (std::size_t i = 0; i < columns_.size(); ++i) {
      if (columns_[i] == scalar.tag) cells[i] = format_value(scalar.value);
    }
  }
  file_ << join(cells) << '\n';
  file_.flush();
  if (!file_) throw RunFileError("cannot write " + path_.string());
}

std::size_t ScalarTable::index(const std::string& column) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == column) return i;
  }
  throw RunFileError("no column '" + column + "' in the scalar log");
}

ScalarTable read_scalar_csv(const std::filesystem::path& path) {
  std::istringstream file(
      read_input_file<std::runtime_error>(path, "scalar log", kMaxScalarLogBytes));
  ScalarTable table;
  std::string line;
  if (!std::getline(file, line) || line.empty()) {
    throw RunFileError(path.string() + ": empty file, no header");
  }
  table.columns = split_fields(line);
  int line_number = 1;
  while (std::getline(file, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::string where = path.string() + ":" + std::to_string(line_number);
    const std::vector<std::string> cells = split_fields(line);
    if (cells.size() != table.columns.size()) {
      throw RunFileError(where + ": expected " + std::to_string(table.columns.size()) +
                         " cells, got " + std::to_string(cells.size()));
    }
    std::vector<double> row;
    row.reserve(cells.size());
    for (const std::string& cell : cells) row.push_back(parse_cell(cell, where));
    table.rows.push_back(std::move(row));
  }
  return table;
}

}  // namespace upkie_rl
