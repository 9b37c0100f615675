#pragma once
/// @file csv.h
/// CSV for tables: writing (numbers in shortest round-trip form, NaN as an empty cell) and reading
/// a header row plus numeric rows with file:line diagnostics.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/common/table.h"

namespace terra::io {

/// The table as CSV text: a header row, then one line per row.
std::string toCsv(const Table& table);

/// A CSV file read as a header and rows of cells (text), each row with its line number.
struct CsvDocument {
    std::vector<std::string> header;
    int header_line = 0;  ///< 1-based file line of the header
    std::vector<std::vector<std::string>> rows;
    std::vector<int> line_numbers;  ///< 1-based file line of each row
    /// Rows left out because their cell count differs from the header's ("file:LINE"), so a
    /// caller can stop or skip them.
    std::vector<Issue> row_issues;
};

/// Parses CSV text (comma separated, optional double quotes, blank lines and lines starting with
/// '#' skipped). Rows with a different number of cells than the header go to `row_issues`; a
/// missing header, or a header naming one column twice (which of the two would count?), fails the
/// parse.
Result<CsvDocument> parseCsv(const std::string& text, const std::string& where);

/// The header's columns against those a reader knows (`known`): an unknown column whose nearest
/// known name (nearestName: "slp", "Slip" → "slip") is absent from the header is an error,
/// since the file most likely means that column and every row would silently take its default;
/// any other unknown column is a warning (`unknown_note` says what becomes of it, e.g. "copied
/// to the output"). Both at `where` ("points.csv:1").
struct ColumnCheck {
    std::vector<Issue> errors;
    std::vector<Issue> warnings;
};
ColumnCheck checkColumns(const std::vector<std::string>& header,
                         const std::vector<std::string>& known, const std::string& where,
                         const std::string& unknown_note);

/// Reads and parses a CSV file.
Result<CsvDocument> readCsv(const std::filesystem::path& path);

/// A cell as a number; false when it is not a finite number.
bool parseNumber(const std::string& cell, double& value);

/// A cell (or any user text) for a message, in single quotes: at most `max_chars` characters, a
/// longer one cut with its length given ("'12345…' (200000 characters)"), so that a huge bad cell
/// does not flood the terminal.
std::string quoteCell(const std::string& cell, std::size_t max_chars = 80);

/// A numeric column that a reader uses: its name, the allowed range in the file's unit, that unit
/// (for messages; empty for none) and the conversion from it to SI (none: already SI).
struct NumericColumn {
    std::string name;
    Range range;
    std::string unit;
    double (*to_si)(double) = nullptr;
};

/// The column of a field of a field table (core/common/field.h): its key, range and display unit;
/// a field shown in degrees is converted to radians.
NumericColumn numericColumn(const FieldInfo& field);

/// Reads one cell of `column` and returns its value in the file's unit, or appends an issue at
/// `where` ("data.csv:12") naming the column, the value (quoted, at most ~80 characters) and the
/// allowed range, and returns nothing, when the cell is not a number, is NaN or infinite,
/// overflows or underflows a double, is subnormal (smaller than 2.2e-308 in magnitude: not a
/// measurement, and arithmetic on it loses precision), lies outside the range, or would turn
/// subnormal, zero or infinite when converted to SI.
std::optional<double> readCell(const std::string& cell, const NumericColumn& column,
                               const std::string& where, std::vector<Issue>& issues);

}  // namespace terra::io
