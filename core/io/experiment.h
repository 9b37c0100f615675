#pragma once
/// @file experiment.h
/// Measured single-wheel tests (docs/validation.md, resources/experiments/README.md): a CSV of
/// measured points and an optional sidecar JSON of metadata (the wheel, the soil, the rig, the
/// citation and the figures the values come from).
///
/// CSV columns (header row, any order, every column at most once, no other column):
/// `load_N` (W [N], required), `slip` (s [-], required), `slip_angle_deg` (β [deg], optional,
/// default 0) and the measured channels `Fx_N` (drawbar pull), `My_Nm` (driving torque),
/// `sinkage_m`, `Fy_N` (side force), `Fz_N` (vertical force), any subset. An empty cell is a
/// channel not measured at that point; each row must measure at least one channel. Every bad cell
/// is reported with its file:line, the column, the value and the allowed range.

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::io {

/// The measured channels of an experiment, in column order.
enum ExperimentChannel { kExpFx, kExpMy, kExpSinkage, kExpFy, kExpFz, kExperimentChannelCount };

/// A channel's column: its name ("Fx_N"), unit, allowed range and what it is.
struct ExperimentColumn {
    const char* name;
    const char* unit;
    Range range;
    const char* label;        ///< "drawbar pull"
    const char* symbol = "";  ///< "F_x", as the studio names it ("" for the conditions)
};

/// The channel columns, in ExperimentChannel order.
const std::array<ExperimentColumn, kExperimentChannelCount>& experimentChannels();
/// The condition columns: load_N, slip, slip_angle_deg.
const std::array<ExperimentColumn, 3>& experimentConditions();

/// One measured point, SI (β in degrees, as in the file).
struct ExperimentPoint {
    double load_n = 0.0;          ///< W [N]
    double slip = 0.0;            ///< s [-]
    double slip_angle_deg = 0.0;  ///< β [deg]
    /// The measured value of each channel (SI: N, N·m, m); empty: not measured here.
    std::array<std::optional<double>, kExperimentChannelCount> measured{};
    int line = 0;  ///< 1-based line of the CSV
};

/// The metadata of a test (the sidecar JSON, docs/validation.md "Experiment files").
struct ExperimentMetadata {
    std::string test;       ///< what was measured
    std::string data_file;  ///< the CSV, relative to the JSON
    std::optional<wheel::WheelParameters> wheel;
    std::string soil_preset;  ///< a soil preset name ("hit-lss1"), empty: none
    std::string soil_name;
    std::string rig;
    std::string citation;  ///< "authors, title, journal volume(issue):pages (year), doi"
    std::string figures;
    std::string notes;
};

/// A test: its points and, when there is a sidecar, its metadata.
struct Experiment {
    std::string source;  ///< the CSV's path, for messages
    std::vector<ExperimentPoint> points;
    std::optional<ExperimentMetadata> metadata;

    /// Whether any point measures channel c.
    bool measures(ExperimentChannel c) const;
};

/// Parses experiment CSV text; `where` names the source in messages ("test.csv").
Result<Experiment> parseExperimentCsv(const std::string& text, const std::string& where);

/// Parses sidecar metadata (strict: unknown keys, wrong types and bad values are issues).
Result<ExperimentMetadata> parseExperimentMetadata(const std::string& text,
                                                   const std::string& where);

/// Reads a test from its CSV or its sidecar JSON: FILE.csv (and FILE.json beside it when there
/// is one) or FILE.json (and the CSV its `data_file` names, relative to it).
Result<Experiment> readExperiment(const std::filesystem::path& path);

}  // namespace terra::io
