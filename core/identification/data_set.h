#pragma once
/// @file data_set.h
/// Measured or synthetic wheel data for soil identification (thesis chapter 5): a time series of
/// samples (s, θ_f, F_x, F_z, M_y; optionally β, F_y, W, time), with CSV import/export.
///
/// CSV columns (header row, any order, extra columns ignored): `slip`, `entry_angle_deg` (or
/// `entry_angle_rad`), `Fx_N`, `Fz_N`, `My_Nm`; optional `slip_angle_deg`, `Fy_N`, `W_N`, `time_s`.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"

namespace terra::identification {

/// One sample, SI.
struct Sample {
    double slip = 0.0;                     ///< s [-], in [−1, 1]
    double entry_angle_rad = 0.0;          ///< θ_f [rad], in (0, π/2)
    double fx_n = 0.0;                     ///< F_x [N], drawbar pull
    double fz_n = 0.0;                     ///< F_z [N], vertical force
    double my_nm = 0.0;                    ///< M_y [N·m], wheel torque
    std::optional<double> slip_angle_rad;  ///< β [rad]
    std::optional<double> fy_n;            ///< F_y [N]
    std::optional<double> load_n;          ///< W [N]
    std::optional<double> time_s;          ///< t [s]
};

/// A data set: samples in file (time) order.
struct DataSet {
    std::vector<Sample> samples;
};

/// What to do with a bad row (non-numeric cell, NaN, s ∉ [−1, 1], θ_f ∉ (0°, 90°)).
enum class BadRows {
    kStop,  ///< the read fails, listing every bad row
    kSkip,  ///< the read succeeds without them; they are listed in `skipped`
};

/// A data set read from CSV, with the rows left out (file:line and why).
struct DataSetRead {
    DataSet data;
    std::vector<Issue> skipped;
};

/// Parses CSV text; `where` names the source in messages ("data.csv").
Result<DataSetRead> parseDataSet(const std::string& text, const std::string& where, BadRows policy);

/// Reads a CSV file.
Result<DataSetRead> readDataSet(const std::filesystem::path& path, BadRows policy);

/// The data set as CSV text: the required columns, then each optional column that any sample has
/// (a sample without it leaves the cell empty).
std::string toCsv(const DataSet& data);

}  // namespace terra::identification
