#include "core/io/csv.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"

namespace terra::io {
namespace {

std::string trim(const std::string& s) {
    const auto begin = s.find_first_not_of(" \t\r");
    if (begin == std::string::npos) return {};
    const auto end = s.find_last_not_of(" \t\r");
    return s.substr(begin, end - begin + 1);
}

// The cells of one line; `open_quote` is set to the 1-based column of a quoted cell that the
// line does not close (0: none).
std::vector<std::string> splitLine(const std::string& line, std::size_t& open_quote) {
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char ch = line[i];
        if (quoted) {
            if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                cell += '"';
                ++i;
            } else if (ch == '"') {
                quoted = false;
            } else {
                cell += ch;
            }
        } else if (ch == '"') {
            quoted = true;
            open_quote = cells.size() + 1;
        } else if (ch == ',') {
            cells.push_back(trim(cell));
            cell.clear();
        } else {
            cell += ch;
        }
    }
    cells.push_back(trim(cell));
    if (!quoted) open_quote = 0;
    return cells;
}

// The end of the line that starts at `start`: the next LF, CR LF or lone CR (old Mac files and
// some loggers end lines with CR alone), or the end of the text. `next` is where the following
// line starts.
std::size_t lineEnd(const std::string& text, std::size_t start, std::size_t& next) {
    const std::size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) {
        next = text.size() + 1;
        return text.size();
    }
    next = end + (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n' ? 2 : 1);
    return end;
}

// A text cell: quoted (with doubled quotes) when it holds a comma, a quote or a line break.
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string out = "\"";
    for (const char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return out + '"';
}

}  // namespace

std::string toCsv(const Table& table) {
    std::string out;
    const bool labelled = !table.label_column.empty();
    if (labelled) out += csvField(table.label_column);
    for (std::size_t i = 0; i < table.columns.size(); ++i) {
        out += (i || labelled ? "," : "") + table.columns[i];
    }
    out += '\n';
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const auto& row = table.rows[r];
        if (labelled) out += csvField(r < table.labels.size() ? table.labels[r] : std::string());
        for (std::size_t i = 0; i < row.size(); ++i) {
            if (i || labelled) out += ',';
            if (std::isfinite(row[i])) out += formatNumber(row[i]);
        }
        out += '\n';
    }
    return out;
}

Result<CsvDocument> parseCsv(const std::string& text, const std::string& where) {
    CsvDocument doc;
    std::vector<Issue> issues;
    int line_number = 0;
    std::size_t start = 0;
    bool have_header = false;
    while (start <= text.size()) {
        std::size_t next = 0;
        const std::size_t end = lineEnd(text, start, next);
        std::string line = text.substr(start, end - start);
        start = next;
        ++line_number;
        if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // BOM
        const std::string stripped = trim(line);
        if (stripped.empty() || stripped[0] == '#') {
            if (end == text.size()) break;
            continue;
        }
        std::size_t open_quote = 0;
        std::vector<std::string> cells = splitLine(line, open_quote);
        const std::string at = where + ":" + std::to_string(line_number);
        // A quote opened and never closed would swallow the rest of the line into one cell and
        // the message would only count cells: say what it is.
        const std::string unbalanced =
            open_quote == 0 ? std::string()
                            : "unbalanced double quote: the quoted cell in column " +
                                  std::to_string(open_quote) +
                                  " is not closed on its line (a quote inside a quoted cell is "
                                  "written twice: \"\")";
        if (!have_header && !unbalanced.empty()) {
            issues.push_back({at, "header: " + unbalanced});
            have_header = true;
        } else if (!unbalanced.empty()) {
            doc.row_issues.push_back({at, unbalanced});
        } else if (!have_header) {
            doc.header = std::move(cells);
            doc.header_line = line_number;
            have_header = true;
            for (std::size_t i = 0; i < doc.header.size(); ++i) {
                if (doc.header[i].empty()) continue;  // an unnamed column is never read
                for (std::size_t k = 0; k < i; ++k) {
                    if (doc.header[k] != doc.header[i]) continue;
                    issues.push_back({where + ":" + std::to_string(line_number),
                                      "column " + quoteCell(doc.header[i]) +
                                          " appears twice (columns " + std::to_string(k + 1) +
                                          " and " + std::to_string(i + 1) +
                                          "); each column may be given once"});
                    break;
                }
            }
        } else if (cells.size() != doc.header.size()) {
            doc.row_issues.push_back({where + ":" + std::to_string(line_number),
                                      std::to_string(cells.size()) + " cells, the header has " +
                                          std::to_string(doc.header.size())});
        } else {
            doc.rows.push_back(std::move(cells));
            doc.line_numbers.push_back(line_number);
        }
        if (end == text.size()) break;
    }
    if (!have_header) issues.push_back({where, "empty file: expected a header row"});
    if (!issues.empty()) return issues;
    return doc;
}

ColumnCheck checkColumns(const std::vector<std::string>& header,
                         const std::vector<std::string>& known, const std::string& where,
                         const std::string& unknown_note) {
    ColumnCheck out;
    auto present = [&](const std::string& name) {
        return std::find(header.begin(), header.end(), name) != header.end();
    };
    std::string all;
    for (const std::string& name : known) all += (all.empty() ? "" : ", ") + name;
    for (const std::string& column : header) {
        if (column.empty() || std::find(known.begin(), known.end(), column) != known.end())
            continue;
        const std::string near = nearestName(column, known);
        if (!near.empty() && !present(near)) {
            out.errors.push_back({where, "unknown column " + quoteCell(column) + "; did you mean " +
                                             near + "? (the file has no " + near +
                                             " column; columns read: " + all + ")"});
        } else {
            out.warnings.push_back({where, "column " + quoteCell(column) +
                                               " is not read (columns read: " + all + ")" +
                                               (unknown_note.empty() ? "" : "; " + unknown_note)});
        }
    }
    return out;
}

Result<CsvDocument> readCsv(const std::filesystem::path& path) {
    std::string text;
    if (const auto error = readFile(path, text))
        return std::vector<Issue>{{pathLabel(path.string()), *error}};
    return parseCsv(text, path.string());
}

bool parseNumber(const std::string& cell, double& value) {
    const std::string s = trim(cell);
    if (s.empty()) return false;
    const char* first = s.data();
    if (*first == '+') {
        ++first;
        if (first == s.data() + s.size() || *first == '-' || *first == '+') return false;
    }
    const auto [end, error] = std::from_chars(first, s.data() + s.size(), value);
    return error == std::errc{} && end == s.data() + s.size() && std::isfinite(value);
}

std::string quoteCell(const std::string& cell, std::size_t max_chars) {
    return quoteText(cell, '\'', max_chars);
}

std::optional<double> readCell(const std::string& cell, const NumericColumn& column,
                               const std::string& where, std::vector<Issue>& issues) {
    const std::string unit = column.unit.empty() ? "" : " " + column.unit;
    const std::string allowed = "allowed range " + column.range.describe() + unit;
    auto fail = [&](const std::string& what) {
        issues.push_back({where, column.name + " = " + what});
        return std::nullopt;
    };
    const std::string text = trim(cell);
    double value = 0.0;
    if (!parseNumber(text, value)) {
        // Tell an overflow or underflow (from_chars: out of range) from text that is no number.
        const char* first = text.c_str() + (!text.empty() && text[0] == '+' ? 1 : 0);
        const auto [end, error] = std::from_chars(first, text.c_str() + text.size(), value);
        if (error == std::errc::result_out_of_range && end == text.c_str() + text.size()) {
            const bool tiny = std::abs(std::strtod(first, nullptr)) < 1.0;
            return fail(quoteCell(text) + (tiny ? " underflows" : " overflows") + " a double; " +
                        allowed);
        }
        if (error == std::errc{} && end == text.c_str() + text.size() && !std::isfinite(value)) {
            return fail(quoteCell(text) + " is not a finite number; " + allowed);
        }
        return fail(quoteCell(text) + " is not a number; " + allowed);
    }
    if (value != 0.0 && std::abs(value) < std::numeric_limits<double>::min()) {
        return fail(quoteCell(text) + " is subnormal (magnitude below 2.2e-308), too small to " +
                    "compute with; " + allowed);
    }
    if (!column.range.contains(value)) {
        return fail(formatNumber(value) + " is outside the " + allowed);
    }
    const double si = column.to_si ? column.to_si(value) : value;
    if (!std::isfinite(si) ||
        (value != 0.0 && !(std::abs(si) >= std::numeric_limits<double>::min()))) {
        return fail(formatNumber(value) + unit +
                    (std::isfinite(si) ? " underflows" : " overflows") +
                    " when converted to SI units (" + formatNumber(si) + "); " + allowed);
    }
    return value;
}

NumericColumn numericColumn(const FieldInfo& field) {
    const bool degrees = field.displayUnit() == "deg";
    return {field.key, field.range, field.displayUnit(), degrees ? units::degToRad : nullptr};
}

}  // namespace terra::io
