#pragma once
/// @file csv.h
/// CSV for tables: writing (numbers in shortest round-trip form, NaN as an empty cell) and reading
/// a header row plus numeric rows with file:line diagnostics.

#include <filesystem>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/table.h"

namespace terra::io {

/// The table as CSV text: a header row, then one line per row.
std::string toCsv(const Table& table);

/// A CSV file read as a header and rows of cells (text), each row with its line number.
struct CsvDocument {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
    std::vector<int> line_numbers;  ///< 1-based file line of each row
    /// Rows left out because their cell count differs from the header's ("file:LINE"), so a
    /// caller can stop or skip them.
    std::vector<Issue> row_issues;
};

/// Parses CSV text (comma separated, optional double quotes, blank lines and lines starting with
/// '#' skipped). Rows with a different number of cells than the header go to `row_issues`; only a
/// missing header fails the parse.
Result<CsvDocument> parseCsv(const std::string& text, const std::string& where);

/// Reads and parses a CSV file.
Result<CsvDocument> readCsv(const std::filesystem::path& path);

/// A cell as a number; false when it is not a finite number.
bool parseNumber(const std::string& cell, double& value);

}  // namespace terra::io
