#include "core/identification/data_set.h"

#include <array>
#include <cmath>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace terra::identification {
namespace {

int find(const std::vector<std::string>& header, const std::string& name) {
    for (std::size_t i = 0; i < header.size(); ++i) {
        if (header[i] == name) return static_cast<int>(i);
    }
    return -1;
}

}  // namespace

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
              c_sinkage = find(doc.header, "sinkage_m");
    std::vector<Issue> missing;
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
    if (!missing.empty()) return missing;

    DataSetRead out;
    out.data.columns = {c_deg >= 0 || c_rad >= 0, c_fx >= 0, c_fz >= 0, c_my >= 0};
    std::vector<Issue> bad = doc.row_issues;
    for (std::size_t r = 0; r < doc.rows.size(); ++r) {
        const auto& cells = doc.rows[r];
        const std::string at = where + ":" + std::to_string(doc.line_numbers[r]);
        const std::size_t before = bad.size();
        auto number = [&](int column, const char* name) {
            double value = std::nan("");
            if (!io::parseNumber(cells[column], value)) {
                bad.push_back(
                    {at, std::string(name) + " = '" + cells[column] + "' is not a finite number"});
            }
            return value;
        };
        auto optional = [&](int column, const char* name) -> std::optional<double> {
            if (column < 0 || cells[column].empty()) return std::nullopt;
            return number(column, name);
        };
        // A measured column: every row needs a number in it (0 when the file lacks the column).
        auto measured = [&](int column, const char* name) {
            return column < 0 ? 0.0 : number(column, name);
        };
        Sample s;
        s.slip = number(c_slip, "slip");
        const double theta = c_deg >= 0   ? number(c_deg, "entry_angle_deg")
                             : c_rad >= 0 ? number(c_rad, "entry_angle_rad")
                                          : 0.0;
        s.entry_angle_rad = c_deg >= 0 ? units::degToRad(theta) : theta;
        s.fx_n = measured(c_fx, "Fx_N");
        s.fz_n = measured(c_fz, "Fz_N");
        s.my_nm = measured(c_my, "My_Nm");
        if (auto beta = optional(c_beta, "slip_angle_deg"))
            s.slip_angle_rad = units::degToRad(*beta);
        s.fy_n = optional(c_fy, "Fy_N");
        s.load_n = optional(c_load, "W_N");
        s.time_s = optional(c_time, "time_s");
        s.sinkage_m = optional(c_sinkage, "sinkage_m");
        if (bad.size() == before) {
            checkRange(bad, at + ": slip", s.slip, {-1.0, 1.0, true, true});
            if (s.sinkage_m) {
                checkRange(bad, at + ": sinkage_m", *s.sinkage_m, {0.0, 1e3, false, false}, "m");
            }
            if (c_deg >= 0) {
                checkRange(bad, at + ": entry_angle_deg", theta, {0.0, 90.0, true, true}, "deg");
            } else if (c_rad >= 0) {
                checkRange(bad, at + ": entry_angle_rad", theta, {0.0, units::kPi / 2, true, true},
                           "rad");
            }
        }
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
        return std::vector<Issue>{{path.string(), *error}};
    return parseDataSet(text, path.string(), policy, needs);
}

std::string toCsv(const DataSet& data) {
    bool beta = false, fy = false, load = false, time = false, sinkage = false;
    for (const Sample& s : data.samples) {
        beta |= s.slip_angle_rad.has_value();
        fy |= s.fy_n.has_value();
        load |= s.load_n.has_value();
        time |= s.time_s.has_value();
        sinkage |= s.sinkage_m.has_value();
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
        out += '\n';
    }
    return out;
}

}  // namespace terra::identification
