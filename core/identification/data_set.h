#pragma once
/// @file data_set.h
/// Measured or synthetic wheel data for soil identification (thesis chapter 5): a time series of
/// samples (s, θ_f, F_x, F_z, M_y; optionally β, F_y, W, sinkage, time), with CSV import/export.
///
/// CSV columns (header row, any order; another column is listed as a warning, or stops the read
/// when it looks like a misspelt known column that the file lacks): `slip`, `entry_angle_deg` (or
/// `entry_angle_rad`), `Fx_N`, `Fz_N`, `My_Nm`; optional `slip_angle_deg`, `Fy_N`, `W_N`,
/// `sinkage_m`, `time_s`. The decoupled fit needs the first five; the full-model identification
/// (identify.h) also reads data without an entry angle (θ_f is then solved from the load W) and
/// with any of F_x, F_z, M_y, sinkage as its measured channels (ColumnNeeds).

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
    std::optional<double> sinkage_m;  ///< h [m], measured sinkage (Eq. 2.12: r (1 − cos θ_f))
    /// σ_s [-]: the standard error of `slip` when it is an estimate (a robot's observer, whose
    /// slip is 1 − v̂/(r ω) with v̂ uncertain); column `slip_std`. Every fit of the full wheel
    /// model, batch and streaming, carries it (ObservationModel::residuals: errors in variables,
    /// docs/identification.md §8); the decoupled fits take the slip as exact.
    std::optional<double> slip_std;
};

/// Which of the columns that a sample always carries were measured (a column the file lacks
/// leaves its field at 0). The default is the decoupled fit's data: θ_f, F_x, F_z, M_y.
struct DataColumns {
    bool entry_angle = true;  ///< θ_f
    bool fx = true;           ///< F_x
    bool fz = true;           ///< F_z
    bool my = true;           ///< M_y
};

/// A data set: samples in file (time) order.
struct DataSet {
    DataSet() = default;
    explicit DataSet(std::vector<Sample> samples_in, DataColumns columns_in = {})
        : samples(std::move(samples_in)), columns(columns_in) {}

    std::vector<Sample> samples;
    DataColumns columns;
};

/// The columns a reader insists on.
enum class ColumnNeeds {
    kDecoupled,  ///< slip, an entry angle, Fx_N, Fz_N, My_Nm (thesis chapters 4–5)
    /// slip and at least one measured channel (Fx_N, Fz_N, My_Nm, sinkage_m); the entry angle and
    /// W_N are optional (whether a load is known is checked by the identification)
    kFullModel,
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
    /// Columns of the header that no reader uses, at FILE:LINE of the header (io::checkColumns).
    std::vector<Issue> warnings;
};

/// The columns the reader knows (the file comment above).
const std::vector<std::string>& dataSetColumns();

/// Parses CSV text; `where` names the source in messages ("data.csv").
Result<DataSetRead> parseDataSet(const std::string& text, const std::string& where, BadRows policy,
                                 ColumnNeeds needs = ColumnNeeds::kDecoupled);

/// Reads a CSV file.
Result<DataSetRead> readDataSet(const std::filesystem::path& path, BadRows policy,
                                ColumnNeeds needs = ColumnNeeds::kDecoupled);

/// The data set as CSV text: slip and the measured columns of `columns`, then each optional column
/// that any sample has (a sample without it leaves the cell empty).
std::string toCsv(const DataSet& data);

}  // namespace terra::identification
