#pragma once
/// @file data_preview.h
/// What the identification would make of a CSV, before it runs: the file's first rows as typed
/// (with their line numbers), the columns it reads and those it ignores, the rows read and every
/// bad row by line, and the channels the full model will compare (or why it cannot fit the file).
/// Read exactly as the fit reads it (identification::readDataSet with the fit's column needs,
/// identification::setupModel with the fit's automatic choice of θ_f), so that the preview and the
/// fit never disagree. The studio's identification panel shows it ("Data preview"), computed on a
/// worker; it never throws for a bad file.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/identification/data_set.h"
#include "core/identification/observation_model.h"

namespace terra::analysis {

/// One data row of the file as typed: its cells, trimmed, and its line number (1: the header).
struct PreviewRow {
    int line = 0;
    std::vector<std::string> cells;
};

/// The preview of one data file.
struct DataPreview {
    /// False: the path is not a regular file or cannot be opened (nothing else is filled in).
    bool readable = false;
    std::vector<std::string> header;         ///< the cells of line 1, trimmed
    std::vector<PreviewRow> rows;            ///< the first non-blank data rows (up to `first_rows`)
    std::vector<std::string> known_columns;  ///< header columns a reader uses, header order
    std::vector<std::string> ignored_columns;  ///< the other header columns, header order
    /// Why the fit cannot read the file (readDataSet's message); empty when it reads it.
    std::string read_error;
    std::size_t samples = 0;      ///< rows read (bad rows left out)
    std::vector<Issue> bad_rows;  ///< every bad row: `where` is "FILE:LINE", `message` why
    /// The full model's choice (ColumnNeeds::kFullModel only, once the file reads): its channels
    /// and where θ_f comes from; empty with `setup_error` saying why it cannot fit the data.
    std::optional<identification::ModelSetup> setup;
    std::string setup_error;
};

/// The preview of the CSV at `path` for a fit with `needs` (kFullModel: the global identification
/// on the full model; kDecoupled: the thesis's decoupled fit). `first_rows`: how many data rows
/// to keep as typed.
DataPreview previewDataFile(const std::filesystem::path& path, identification::ColumnNeeds needs,
                            std::size_t first_rows = 5);

}  // namespace terra::analysis
