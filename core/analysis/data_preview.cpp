#include "core/analysis/data_preview.h"

#include <algorithm>
#include <fstream>
#include <limits>

namespace terra::analysis {
namespace {

std::string trimmedCell(const std::string& text) {
    const char* space = " \t\r\n\v\f";
    const std::size_t begin = text.find_first_not_of(space);
    if (begin == std::string::npos) return {};
    return text.substr(begin, text.find_last_not_of(space) - begin + 1);
}

// One CSV line's cells (the data files have no quoted fields; a quote is kept as typed). An empty
// line is one empty cell, as a header that has nothing.
std::vector<std::string> previewCells(const std::string& line) {
    std::vector<std::string> cells;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = line.find(',', start);
        cells.push_back(trimmedCell(line.substr(start, comma - start)));
        if (comma == std::string::npos) return cells;
        start = comma + 1;
    }
}

}  // namespace

DataPreview previewDataFile(const std::filesystem::path& path, identification::ColumnNeeds needs,
                            std::size_t first_rows) {
    namespace id = identification;
    DataPreview preview;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return preview;
    std::ifstream file(path);
    if (!file) return preview;
    preview.readable = true;

    // The first rows as the file has them, with their line numbers (blank lines are counted).
    std::string line;
    int line_number = 0;
    while (preview.rows.size() < first_rows && std::getline(file, line)) {
        ++line_number;
        line = trimmedCell(line);
        if (line_number == 1) {
            preview.header = previewCells(line);
            continue;
        }
        if (line.empty()) continue;
        preview.rows.push_back({line_number, previewCells(line)});
    }
    const std::vector<std::string>& known = id::dataSetColumns();
    for (const std::string& column : preview.header) {
        const bool read = std::find(known.begin(), known.end(), column) != known.end();
        (read ? preview.known_columns : preview.ignored_columns).push_back(column);
    }

    // Read as the fit reads it (the same columns needed), every bad row kept: the fit itself
    // refuses a file with bad rows.
    Result<id::DataSetRead> read = id::readDataSet(path, id::BadRows::kSkip, needs);
    if (!read) {
        preview.read_error = read.message();
        return preview;
    }
    preview.samples = read->data.samples.size();
    preview.bad_rows = read->skipped;
    if (needs == id::ColumnNeeds::kFullModel) {
        // The identification's automatic choice: θ_f when measured, else solved from the load.
        Result<id::ModelSetup> setup =
            id::setupModel(read->data, id::DataSource::kAuto, std::nullopt,
                           std::numeric_limits<double>::infinity());
        if (setup)
            preview.setup = std::move(setup).value();
        else
            preview.setup_error = setup.message();
    }
    return preview;
}

}  // namespace terra::analysis
