#include "core/io/raster_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "core/common/range.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/geotiff.h"

namespace terra::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// Splits text into whitespace-separated tokens with their 1-based line numbers.
struct Token {
    std::string text;
    int line = 0;
};

std::vector<Token> tokenize(const std::string& text) {
    std::vector<Token> tokens;
    int line = 1;
    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            ++i;
        } else if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
        } else {
            const std::size_t start = i;
            while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
            tokens.push_back({text.substr(start, i - start), line});
        }
    }
    return tokens;
}

std::string at(const std::string& where, int line) { return where + ":" + std::to_string(line); }

}  // namespace

Result<field::Raster> parseAsciiGrid(const std::string& text, const std::string& where) {
    const std::vector<Token> tokens = tokenize(text);
    std::vector<Issue> issues;
    std::map<std::string, double> header;
    std::map<std::string, int> header_line;
    std::size_t i = 0;
    static const std::set<std::string> kKeys = {"ncols",     "nrows",       "xllcorner",
                                                "xllcenter", "yllcorner",   "yllcenter",
                                                "cellsize",  "nodata_value"};
    // Header lines: a key (letters) and a number; the data start at the first number.
    while (i + 1 < tokens.size() && std::isalpha(static_cast<unsigned char>(tokens[i].text[0]))) {
        const std::string key = lower(tokens[i].text);
        double value = 0.0;
        if (kKeys.count(key) == 0) {
            issues.push_back({at(where, tokens[i].line),
                              "unknown header key '" + tokens[i].text +
                                  "' (ESRI ASCII grid: ncols, nrows, xllcorner or xllcenter, "
                                  "yllcorner or yllcenter, cellsize, NODATA_value)"});
        } else if (header.count(key) != 0) {
            issues.push_back({at(where, tokens[i].line), "'" + key + "' is given twice"});
        } else if (!parseNumber(tokens[i + 1].text, value)) {
            issues.push_back({at(where, tokens[i + 1].line),
                              key + " = " + quoteCell(tokens[i + 1].text) + " is not a number"});
        } else {
            header[key] = value;
            header_line[key] = tokens[i].line;
        }
        i += 2;
    }
    for (const char* key : {"ncols", "nrows", "cellsize"}) {
        if (header.count(key) == 0 && issues.empty())
            issues.push_back({where, std::string("the header has no ") + key});
    }
    const bool x_corner = header.count("xllcorner") != 0, x_centre = header.count("xllcenter") != 0;
    const bool y_corner = header.count("yllcorner") != 0, y_centre = header.count("yllcenter") != 0;
    if (issues.empty() && x_corner == x_centre)
        issues.push_back({where, "the header needs exactly one of xllcorner and xllcenter"});
    if (issues.empty() && y_corner == y_centre)
        issues.push_back({where, "the header needs exactly one of yllcorner and yllcenter"});
    if (!issues.empty()) return issues;

    field::Raster r;
    const double cols = header["ncols"], rows = header["nrows"];
    for (const auto& [key, v] : {std::pair{"ncols", cols}, std::pair{"nrows", rows}}) {
        if (v != std::round(v) || v < 1 || v > 100000)
            issues.push_back(
                {at(where, header_line[key]), std::string(key) + " = " + formatNumber(v) +
                                                  " must be a whole number in [1, 100000]"});
    }
    r.cell_m = header["cellsize"];
    if (!(r.cell_m > 0.0 && r.cell_m <= 1e4))
        issues.push_back({at(where, header_line["cellsize"]),
                          "cellsize = " + formatNumber(r.cell_m) + " must be in (0, 10000] m"});
    if (!issues.empty()) return issues;
    r.cols = static_cast<int>(cols);
    r.rows = static_cast<int>(rows);
    r.x_min_m = x_corner ? header["xllcorner"] : header["xllcenter"] - 0.5 * r.cell_m;
    r.y_min_m = y_corner ? header["yllcorner"] : header["yllcenter"] - 0.5 * r.cell_m;
    const bool has_nodata = header.count("nodata_value") != 0;
    const double nodata = has_nodata ? header["nodata_value"] : 0.0;
    std::vector<Issue> layout =
        field::validate(field::makeRaster(r.cols, r.rows, r.x_min_m, r.y_min_m, r.cell_m), where);
    if (!layout.empty()) return layout;

    const std::size_t count = static_cast<std::size_t>(r.cols) * r.rows;
    const std::size_t available = tokens.size() - i;
    if (available != count) {
        return std::vector<Issue>{
            {where, "holds " + std::to_string(available) +
                        " values for ncols × nrows = " + std::to_string(r.cols) + " × " +
                        std::to_string(r.rows) + " = " + std::to_string(count)}};
    }
    r.values.resize(count);
    for (std::size_t k = 0; k < count; ++k, ++i) {
        double v = 0.0;
        if (!parseNumber(tokens[i].text, v)) {
            if (issues.size() < kMaxIssuesShown)
                issues.push_back({at(where, tokens[i].line), "value " + std::to_string(k + 1) +
                                                                 " " + quoteCell(tokens[i].text) +
                                                                 " is not a finite number"});
            continue;
        }
        r.values[k] = has_nodata && v == nodata ? kNaN : v;
    }
    if (!issues.empty()) return issues;
    return r;
}

std::string toAsciiGrid(const field::Raster& r) {
    std::ostringstream out;
    out << "ncols " << r.cols << "\nnrows " << r.rows << "\nxllcorner " << formatNumber(r.x_min_m)
        << "\nyllcorner " << formatNumber(r.y_min_m) << "\ncellsize " << formatNumber(r.cell_m)
        << "\nNODATA_value -9999\n";
    for (int row = 0; row < r.rows; ++row) {
        for (int col = 0; col < r.cols; ++col) {
            const double v = r.value(col, row);
            out << (col > 0 ? " " : "") << (std::isnan(v) ? std::string("-9999") : formatNumber(v));
        }
        out << '\n';
    }
    return out.str();
}

Result<field::Raster> parseRasterCsv(const std::string& text, const std::string& where,
                                     const std::string& value_column) {
    Result<CsvDocument> doc = parseCsv(text, where);
    if (!doc) return doc.issues();
    const std::vector<std::string>& header = doc->header;
    const auto column = [&](const std::string& name) -> int {
        const auto it = std::find(header.begin(), header.end(), name);
        return it == header.end() ? -1 : static_cast<int>(it - header.begin());
    };
    const std::string head = where + ":" + std::to_string(doc->header_line);
    const int cx = column("x_m"), cy = column("y_m");
    int cv = -1;
    if (!value_column.empty()) {
        cv = column(value_column);
    } else if (header.size() == 3 && cx >= 0 && cy >= 0) {
        cv = 3 - cx - cy;
    }
    if (cx < 0 || cy < 0 || cv < 0) {
        return std::vector<Issue>{{head, "a raster CSV needs the columns x_m, y_m and " +
                                             (value_column.empty() ? std::string("one value column")
                                                                   : "'" + value_column + "'")}};
    }
    if (!doc->row_issues.empty()) return doc->row_issues;
    std::vector<Issue> issues;
    std::vector<double> xs, ys, vs;
    std::vector<int> lines;  // the file line of each cell read
    for (std::size_t k = 0; k < doc->rows.size(); ++k) {
        double x = 0.0, y = 0.0, v = 0.0;
        const std::vector<std::string>& row = doc->rows[k];
        const std::string line = where + ":" + std::to_string(doc->line_numbers[k]);
        if (!parseNumber(row[cx], x) || !parseNumber(row[cy], y)) {
            issues.push_back({line, "x_m and y_m must be finite numbers"});
        } else if (row[cv].empty()) {
            continue;  // no data
        } else if (!parseNumber(row[cv], v)) {
            issues.push_back({line, header[cv] + " = " + quoteCell(row[cv]) +
                                        " is not a finite number (leave it empty for no data)"});
        } else {
            xs.push_back(x);
            ys.push_back(y);
            vs.push_back(v);
            lines.push_back(doc->line_numbers[k]);
        }
        if (issues.size() >= kMaxIssuesShown) break;
    }
    if (!issues.empty()) return issues;
    if (xs.empty()) return std::vector<Issue>{{where, "has no cell with a value"}};
    const auto spacing = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
        double d = std::numeric_limits<double>::infinity();
        for (std::size_t k = 1; k < v.size(); ++k) d = std::min(d, v[k] - v[k - 1]);
        return d;
    };
    double cell = std::min(spacing(xs), spacing(ys));
    if (!std::isfinite(cell)) cell = 1.0;  // one cell: its size cannot be told; 1 m
    const double x0 = *std::min_element(xs.begin(), xs.end());
    const double y0 = *std::min_element(ys.begin(), ys.end());
    const double x1 = *std::max_element(xs.begin(), xs.end());
    const double y1 = *std::max_element(ys.begin(), ys.end());
    const double cols = std::round((x1 - x0) / cell) + 1, rows = std::round((y1 - y0) / cell) + 1;
    if (cols * rows > 1e8)
        return std::vector<Issue>{{where, "the centres span " + formatNumber(cols) + " × " +
                                              formatNumber(rows) + " cells of " +
                                              formatNumber(cell) + " m: too many (1e8 at most)"}};
    field::Raster r = field::makeRaster(static_cast<int>(cols), static_cast<int>(rows),
                                        x0 - 0.5 * cell, y0 - 0.5 * cell, cell, kNaN);
    constexpr double kOnGrid = 1e-6;  // of a cell
    for (std::size_t k = 0; k < xs.size(); ++k) {
        const double fc = (xs[k] - x0) / cell, fr = (y1 - ys[k]) / cell;
        const double col = std::round(fc), row = std::round(fr);
        const std::string line = where + ":" + std::to_string(lines[k]);
        // Messages built piece by piece: GCC 12 warns falsely (-Wstringop-overflow) on the long
        // operator+ chain.
        std::string point = "(";
        point += formatNumber(xs[k]);
        point += ", ";
        point += formatNumber(ys[k]);
        point += ")";
        if (std::abs(fc - col) > kOnGrid || std::abs(fr - row) > kOnGrid) {
            std::string message = point;
            message += " is not on the grid of ";
            message += formatNumber(cell);
            message += " m cells through (";
            message += formatNumber(x0);
            message += ", ";
            message += formatNumber(y1);
            message += ")";
            issues.push_back({line, std::move(message)});
        } else if (double& cellv = r.value(static_cast<int>(col), static_cast<int>(row));
                   !std::isnan(cellv)) {
            issues.push_back({line, "the cell at " + point + " is given twice"});
        } else {
            cellv = vs[k];
        }
        if (issues.size() >= kMaxIssuesShown) break;
    }
    if (!issues.empty()) return issues;
    return r;
}

std::string toRasterCsv(const field::Raster& r, const std::string& value_column) {
    std::ostringstream out;
    out << "x_m,y_m," << value_column << '\n';
    for (int row = 0; row < r.rows; ++row) {
        for (int col = 0; col < r.cols; ++col) {
            const double v = r.value(col, row);
            if (std::isnan(v)) continue;
            out << formatNumber(r.centreX(col)) << ',' << formatNumber(r.centreY(row)) << ','
                << formatNumber(v) << '\n';
        }
    }
    return out.str();
}

Result<field::Raster> readRaster(const std::filesystem::path& path,
                                 const std::string& value_column) {
    const std::string ext = lower(path.extension().string());
    const bool tiff = ext == ".tif" || ext == ".tiff";
    if (ext != ".asc" && ext != ".csv" && !tiff) {
        return std::vector<Issue>{{path.string(),
                                   "raster files are read as ESRI ASCII grid (.asc), CSV (.csv) or "
                                   "GeoTIFF (.tif, .tiff); '" +
                                       path.extension().string() + "' is none of them"}};
    }
    std::string text;
    if (std::optional<std::string> error = readFile(path, text))
        return std::vector<Issue>{{path.string(), *error}};
    if (tiff) return parseGeoTiff(text, path.string());
    return ext == ".asc" ? parseAsciiGrid(text, path.string())
                         : parseRasterCsv(text, path.string(), value_column);
}

std::optional<std::string> writeRaster(const std::filesystem::path& path,
                                       const field::Raster& raster,
                                       const std::string& value_column) {
    const std::string ext = lower(path.extension().string());
    if (ext == ".tif" || ext == ".tiff") {
        Result<std::string> bytes = toGeoTiff(raster);
        if (!bytes) return path.string() + ": " + bytes.message();
        return writeFileAtomically(path, *bytes);
    }
    if (ext != ".asc" && ext != ".csv")
        return path.string() + ": rasters are written as .asc, .csv, .tif or .tiff";
    return writeFileAtomically(
        path, ext == ".asc" ? toAsciiGrid(raster) : toRasterCsv(raster, value_column));
}

}  // namespace terra::io
