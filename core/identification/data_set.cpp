#include "core/identification/data_set.h"

#include <cmath>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace terra::identification {
namespace {

// The columns' ranges (docs/identification.md, "Data sets"). Forces and torques up to 1e7 N
// (N·m), a thousand tonnes on one wheel, as the CLI's loads; times up to 1e12 s, so that Unix
// time stamps (1.7e9 s) fit.
constexpr double kMaxForce = 1e7;
constexpr double kMaxTime = 1e12;
const io::NumericColumn kSlip{"slip", {-1.0, 1.0}, ""};
const io::NumericColumn kEntryAngleDeg{
    "entry_angle_deg", {0.0, 90.0, true, true}, "deg", units::degToRad};
const io::NumericColumn kEntryAngleRad{"entry_angle_rad", {0.0, units::kPi / 2, true, true}, "rad"};
// Sinkage up to the largest wheel radius anyone puts in a file (10 m).
const io::NumericColumn kSinkage{"sinkage_m", {0.0, 10.0}, "m"};
// The slip's standard error (a robot's observer): at most the slip's whole range.
const io::NumericColumn kSlipStd{"slip_std", {0.0, 2.0}, ""};
const io::NumericColumn kSlipAngleDeg{
    "slip_angle_deg", {-90.0, 90.0, true, true}, "deg", units::degToRad};

io::NumericColumn forceColumn(const char* name) { return {name, {-kMaxForce, kMaxForce}, "N"}; }

int find(const std::vector<std::string>& header, const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
        if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
}

}  // namespace

const std::vector<std::string>& dataSetColumns() {
    static const std::vector<std::string> columns{
        "slip", "entry_angle_deg", "entry_angle_rad", "Fx_N",
        "Fz_N", "My_Nm",           "slip_angle_deg",  "Fy_N",
        "W_N",  "time_s",          "sinkage_m",       "slip_std"};
    return columns;
}

Result<DataSetRead> parseDataSet(const std::string& text, const std::string& where, BadRows policy,
                                 ColumnNeeds needs) {
    Result<io::CsvDocument> parsed = io::parseCsv(text, where);
    if (!parsed) return parsed.issues();
    const io::CsvDocument& doc = parsed.value();
    const int c_slip = find(doc.header, "slip"), c_deg = find(doc.header, "entry_angle_deg"),
              c_rad = find(doc.header, "entry_angle_rad"), c_fx = find(doc.header, "Fx_N"),
              c_fz = find(doc.header, "Fz_N"), c_my = find(doc.header, "My_Nm"),
              c_beta = find(doc.header, "slip_angle_deg"), c_fy = find(doc.header, "Fy_N"),
              c_load = find(doc.header, "W_N"), c_time = find(doc.header, "time_s"),
              c_sinkage = find(doc.header, "sinkage_m"), c_slip_std = find(doc.header, "slip_std");
    // A column the reader does not know is data the fit would lose without a word: a misspelt
    // channel ("Fz_M", "fz_N") whose known name is absent stops the read (every row would lose
    // that channel), any other unknown column is listed as a warning.
    const io::ColumnCheck unknown = io::checkColumns(
        doc.header, dataSetColumns(), where + ":" + std::to_string(doc.header_line), "");
    std::vector<Issue> missing = unknown.errors;
    if (needs == ColumnNeeds::kDecoupled) {
        const std::pair<const char*, int> required[] = {
            {"slip", c_slip}, {"Fx_N", c_fx}, {"Fz_N", c_fz}, {"My_Nm", c_my}};
        for (const auto& [name, column] : required) {
            if (column < 0)
                missing.push_back({where, std::string("missing column '") + name + "'"});
        }
        if (c_deg < 0 && c_rad < 0) {
            missing.push_back({where, "missing column 'entry_angle_deg' (or 'entry_angle_rad')"});
        }
    } else {
        if (c_slip < 0) missing.push_back({where, "missing column 'slip'"});
        if (c_fx < 0 && c_fz < 0 && c_my < 0 && c_sinkage < 0) {
            missing.push_back({where,
                               "no measured channel: give at least one of the columns 'Fx_N', "
                               "'Fz_N', 'My_Nm', 'sinkage_m'"});
        }
    }
    if (c_deg >= 0 && c_rad >= 0) {
        missing.push_back({where,
                           "columns 'entry_angle_deg' and 'entry_angle_rad' both given; "
                           "give the entry angle once"});
    }
    if (!missing.empty()) return missing;

    DataSetRead out;
    out.warnings = unknown.warnings;
    out.data.columns = {c_deg >= 0 || c_rad >= 0, c_fx >= 0, c_fz >= 0, c_my >= 0};
    std::vector<Issue> bad = doc.row_issues;
    for (std::size_t r = 0; r < doc.rows.size(); ++r) {
        const auto& cells = doc.rows[r];
        const std::string at = where + ":" + std::to_string(doc.line_numbers[r]);
        const std::size_t before = bad.size();
        auto number = [&](int column, const io::NumericColumn& spec) {
            return io::readCell(cells[column], spec, at, bad).value_or(0.0);
        };
        auto optional = [&](int column, const io::NumericColumn& spec) -> std::optional<double> {
            if (column < 0 || cells[column].empty()) return std::nullopt;
            return io::readCell(cells[column], spec, at, bad);
        };
        // A measured column: every row needs a number in it (0 when the file lacks the column).
        auto measured = [&](int column, const io::NumericColumn& spec) {
            return column < 0 ? 0.0 : number(column, spec);
        };
        Sample s;
        s.slip = number(c_slip, kSlip);
        s.entry_angle_rad = c_deg >= 0   ? units::degToRad(number(c_deg, kEntryAngleDeg))
                            : c_rad >= 0 ? number(c_rad, kEntryAngleRad)
                                         : 0.0;
        s.fx_n = measured(c_fx, forceColumn("Fx_N"));
        s.fz_n = measured(c_fz, forceColumn("Fz_N"));
        s.my_nm = measured(c_my, {"My_Nm", {-kMaxForce, kMaxForce}, "N·m"});
        if (auto beta = optional(c_beta, kSlipAngleDeg)) s.slip_angle_rad = units::degToRad(*beta);
        s.fy_n = optional(c_fy, forceColumn("Fy_N"));
        s.load_n = optional(c_load, {"W_N", {0.0, kMaxForce, true, false}, "N"});
        s.time_s = optional(c_time, {"time_s", {-kMaxTime, kMaxTime}, "s"});
        s.sinkage_m = optional(c_sinkage, kSinkage);
        s.slip_std = optional(c_slip_std, kSlipStd);
        if (bad.size() == before) out.data.samples.push_back(s);
    }
    if (!bad.empty() && policy == BadRows::kStop) return bad;
    out.skipped = std::move(bad);
    return out;
}

Result<DataSetRead> readDataSet(const std::filesystem::path& path, BadRows policy,
                                ColumnNeeds needs) {
    std::string text;
    if (const auto error = io::readFile(path, text))
        return std::vector<Issue>{{pathLabel(path.string()), *error}};
    return parseDataSet(text, path.string(), policy, needs);
}

std::string toCsv(const DataSet& data) {
    bool beta = false, fy = false, load = false, time = false, sinkage = false, slip_std = false;
    for (const Sample& s : data.samples) {
        beta |= s.slip_angle_rad.has_value();
        fy |= s.fy_n.has_value();
        load |= s.load_n.has_value();
        time |= s.time_s.has_value();
        sinkage |= s.sinkage_m.has_value();
        slip_std |= s.slip_std.has_value();
    }
    const DataColumns& c = data.columns;
    std::string out = "slip";
    if (c.entry_angle) out += ",entry_angle_deg";
    if (c.fx) out += ",Fx_N";
    if (c.fz) out += ",Fz_N";
    if (c.my) out += ",My_Nm";
    if (beta) out += ",slip_angle_deg";
    if (fy) out += ",Fy_N";
    if (load) out += ",W_N";
    if (time) out += ",time_s";
    if (sinkage) out += ",sinkage_m";
    if (slip_std) out += ",slip_std";
    out += '\n';
    auto cell = [](const std::optional<double>& v) {
        return v ? "," + formatNumber(*v) : std::string(",");
    };
    for (const Sample& s : data.samples) {
        out += formatNumber(s.slip);
        if (c.entry_angle) out += "," + formatNumber(units::radToDeg(s.entry_angle_rad));
        if (c.fx) out += "," + formatNumber(s.fx_n);
        if (c.fz) out += "," + formatNumber(s.fz_n);
        if (c.my) out += "," + formatNumber(s.my_nm);
        if (beta) {
            out += cell(s.slip_angle_rad ? std::optional<double>(units::radToDeg(*s.slip_angle_rad))
                                         : std::nullopt);
        }
        if (fy) out += cell(s.fy_n);
        if (load) out += cell(s.load_n);
        if (time) out += cell(s.time_s);
        if (sinkage) out += cell(s.sinkage_m);
        if (slip_std) out += cell(s.slip_std);
        out += '\n';
    }
    return out;
}

}  // namespace terra::identification
