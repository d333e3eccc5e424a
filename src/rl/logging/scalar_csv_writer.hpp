#pragma once
/// @file
/// A CSV of logged scalars (like SB3's progress.csv): a header of tags, then one row per
/// update; empty cells for values not available (e.g. no finished episode yet).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rl/logging/tensorboard_writer.hpp"

namespace upkie_rl {

class ScalarCsvWriter {
 public:
  /// Opens `path` with these columns; the first column must be the step counter. With
  /// `resume_from_step`, rows of an existing file up to that step are kept (rows after it
  /// belong to the part of the run being redone) and new rows are appended; the kept rows
  /// are written to a file aside that is renamed over the old one, so the existing file is
  /// never cut in place. Otherwise the file is created anew. Throws std::runtime_error if the file
  /// cannot be written or the existing header differs.
  ScalarCsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
                  std::optional<std::int64_t> resume_from_step = std::nullopt);

  /// Writes one row; scalars whose tag is not a column are ignored, missing ones are empty.
  void write_row(std::span<const ScalarValue> scalars);

  const std::vector<std::string>& columns() const { return columns_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::ofstream file_;
};

/// Largest scalar log read (progress.csv, resumed or plotted): a row takes about 300 bytes,
/// so 1 GiB holds millions of updates.
inline constexpr std::uintmax_t kMaxScalarLogBytes = std::uintmax_t{1} << 30;

/// Reads a CSV written by ScalarCsvWriter (at most kMaxScalarLogBytes, a regular file): the header
/// and the rows, NaN for empty cells. Throws std::runtime_error naming the file and line on
/// malformed content.
struct ScalarTable {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  /// Index of `column`, or throws std::runtime_error naming it.
  std::size_t index(const std::string& column) const;
};
ScalarTable read_scalar_csv(const std::filesystem::path& path);

}  // namespace upkie_rl
