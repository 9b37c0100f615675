#pragma once
/// @file table.h
/// Plain tabular results (sweeps, sensitivity): named columns of doubles, ready to print, write
/// as CSV/JSON, or plot.

#include <cstddef>
#include <string>
#include <vector>

namespace terra {

struct Table {
    std::vector<std::string> columns;       ///< unit-suffixed names ("Fx_N")
    std::vector<std::vector<double>> rows;  ///< each row has columns.size() values
    /// Optional text column written before the numeric ones (CSV, JSON): its name, and one label
    /// per row ("phi_deg" for a tornado's rows). Empty name: no label column.
    std::string label_column = {};
    std::vector<std::string> labels = {};

    /// Index of a column; throws std::out_of_range when absent.
    std::size_t column(const std::string& name) const;
    /// All values of one column.
    std::vector<double> values(const std::string& name) const;
};

}  // namespace terra
