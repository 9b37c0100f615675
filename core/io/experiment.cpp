#include "core/io/experiment.h"

#include <algorithm>

#include "core/common/quoted.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"

namespace terra::io {
namespace {

namespace fs = std::filesystem;

// Forces and torques up to 1e6 (a planetary rover wheel measures tens of newtons, a tractor tyre
// tens of kilonewtons); a sinkage up to 5 m, the largest wheel radius the wheel files accept.
// The conditions' ranges are the operating point's (core/contact/operating_fields.h: W in
// (0, 1e5] N, s in [−1, 1], β in (−90°, 90°)), repeated here because io sits below contact.
const std::array<ExperimentColumn, kExperimentChannelCount> kChannels{{
    {"Fx_N", "N", {-1e6, 1e6}, "drawbar pull", "F_x"},
    {"My_Nm", "N·m", {-1e6, 1e6}, "driving torque", "M_y"},
    {"sinkage_m", "m", {0.0, 5.0}, "sinkage", "h"},
    {"Fy_N", "N", {-1e6, 1e6}, "side force", "F_s"},
    {"Fz_N", "N", {-1e6, 1e6}, "vertical force", "F_z"},
}};
const std::array<ExperimentColumn, 3> kConditions{{
    {"load_N", "N", {0.0, 1e5, true, false}, "wheel load"},
    {"slip", "", {-1.0, 1.0}, "slip"},
    {"slip_angle_deg", "deg", {-90.0, 90.0, true, true}, "slip angle"},
}};

NumericColumn numericOf(const ExperimentColumn& c) {
    return {c.name, c.range, std::string(c.unit), nullptr};
}

std::vector<std::string> columnNames() {
    std::vector<std::string> names;
    for (const ExperimentColumn& c : kConditions) names.emplace_back(c.name);
    for (const ExperimentColumn& c : kChannels) names.emplace_back(c.name);
    return names;
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// "Ding, Gao, …, title, journal 48(1):27-45 (2011), doi:…" from the citation object.
std::string readCitation(ObjectReader& r) {
    ObjectReader c = r.object("citation");
    std::vector<std::string> authors;
    std::string title, journal, volume, issue, pages, doi, check;
    int year = 0;
    c.texts("authors", authors);
    c.text("title", title);
    c.text("journal", journal);
    c.text("volume", volume);
    c.text("issue", issue);
    c.text("pages", pages);
    c.integer("year", year, 1800, 2200);
    c.text("doi", doi);
    c.text("citation_check", check);
    c.finish();
    std::string out = joined(authors);
    auto add = [&](const std::string& part, const char* separator) {
        if (!part.empty()) out += (out.empty() ? "" : separator) + part;
    };
    add(title, ", ");
    add(journal, ", ");
    if (!volume.empty()) out += " " + volume + (issue.empty() ? "" : "(" + issue + ")");
    if (!pages.empty()) out += ":" + pages;
    if (year != 0) out += " (" + std::to_string(year) + ")";
    add(doi.empty() ? "" : "doi:" + doi, ", ");
    return out;
}

}  // namespace

const std::array<ExperimentColumn, kExperimentChannelCount>& experimentChannels() {
    return kChannels;
}
const std::array<ExperimentColumn, 3>& experimentConditions() { return kConditions; }

bool Experiment::measures(ExperimentChannel c) const {
    return std::any_of(points.begin(), points.end(),
                       [c](const ExperimentPoint& p) { return p.measured[c].has_value(); });
}

Result<Experiment> parseExperimentCsv(const std::string& text, const std::string& where) {
    Result<CsvDocument> read = parseCsv(text, where);
    if (!read) return read.issues();
    const CsvDocument& doc = read.value();
    std::vector<Issue> issues;
    const std::vector<std::string> names = columnNames();
    std::vector<int> index(names.size(), -1);
    for (std::size_t i = 0; i < doc.header.size(); ++i) {
        const auto it = std::find(names.begin(), names.end(), doc.header[i]);
        if (it == names.end()) {
            const std::string near = nearestName(doc.header[i], names);
            issues.push_back({where, "unknown column " + quoteCell(doc.header[i]) +
                                         " (columns: " + joined(names) + ")" +
                                         (near.empty() ? "" : "; did you mean " + near + "?")});
            continue;
        }
        index[static_cast<std::size_t>(it - names.begin())] = static_cast<int>(i);
    }
    for (int k : {0, 1}) {
        if (index[static_cast<std::size_t>(k)] < 0)
            issues.push_back({where, "missing column " + names[static_cast<std::size_t>(k)]});
    }
    bool any_channel = false;
    for (std::size_t k = kConditions.size(); k < names.size(); ++k) any_channel |= index[k] >= 0;
    if (!any_channel) {
        issues.push_back({where,
                          "no measured channel: expected at least one of Fx_N, My_Nm, "
                          "sinkage_m, Fy_N, Fz_N"});
    }
    if (!issues.empty()) return issues;  // the header: no row can be read
    issues = doc.row_issues;             // rows with the wrong number of cells

    Experiment out;
    out.source = where;
    for (std::size_t row = 0; row < doc.rows.size(); ++row) {
        const std::vector<std::string>& cells = doc.rows[row];
        const std::string at = where + ":" + std::to_string(doc.line_numbers[row]);
        const std::size_t before = issues.size();
        ExperimentPoint p;
        p.line = doc.line_numbers[row];
        auto cell = [&](std::size_t k, const ExperimentColumn& column, bool required) {
            const int c = index[k];
            if (c < 0) return std::optional<double>{};
            const std::string& value = cells[static_cast<std::size_t>(c)];
            if (value.find_first_not_of(" \t") == std::string::npos) {
                if (required) issues.push_back({at, std::string(column.name) + " is empty"});
                return std::optional<double>{};
            }
            return readCell(value, numericOf(column), at, issues);
        };
        p.load_n = cell(0, kConditions[0], true).value_or(0.0);
        p.slip = cell(1, kConditions[1], true).value_or(0.0);
        p.slip_angle_deg = cell(2, kConditions[2], false).value_or(0.0);
        bool measured = false;
        for (std::size_t c = 0; c < kChannels.size(); ++c) {
            p.measured[c] = cell(kConditions.size() + c, kChannels[c], false);
            measured |= p.measured[c].has_value();
        }
        if (!measured && issues.size() == before) {
            issues.push_back({at, "no channel measured (every channel cell is empty)"});
        }
        if (issues.size() == before) out.points.push_back(p);
    }
    if (issues.empty() && out.points.empty()) {
        issues.push_back({where, "no measured points (only a header)"});
    }
    if (!issues.empty()) {
        // In line order: rows with a wrong cell count come from the CSV reader, the rest from here.
        auto line = [&](const Issue& issue) {
            const std::string prefix = where + ":";
            return issue.where.rfind(prefix, 0) == 0
                       ? std::atol(issue.where.c_str() + prefix.size())
                       : 0L;
        };
        std::stable_sort(issues.begin(), issues.end(),
                         [&](const Issue& a, const Issue& b) { return line(a) < line(b); });
        return issues;
    }
    return out;
}

namespace {

Result<ExperimentMetadata> readExperimentMetadata(const nlohmann::json& json,
                                                  const std::string& where) {
    std::vector<Issue> issues;
    ObjectReader r(json, issues, where);
    ExperimentMetadata m;
    std::string format;
    r.choiceName("format", format, {"terrastudio-experiment"}, Presence::kRequired);
    int version = 0;
    r.integer("format_version", version, 1, 1, Presence::kRequired);
    r.text("test", m.test);
    r.text("data_file", m.data_file);
    if (r.has("wheel")) {
        ObjectReader w = r.object("wheel");
        m.wheel = readWheel(w);
        w.finish();
    } else {
        r.allow("wheel");
    }
    {
        ObjectReader s = r.object("soil");
        s.text("preset", m.soil_preset);
        s.text("name", m.soil_name);
        // The parameters the paper gives, in the soil-file keys (docs/soils.md), each checked;
        // a paper need not give all of them (γ is often missing), so none is required.
        ObjectReader p = s.object("parameters");
        soil::SoilParameters probe;
        for (const soil::SoilField& field : soil::soilFields()) p.field(field, probe.*field.member);
        p.finish();
        std::string note;
        s.text("parameters_source", note);
        s.finish();
    }
    r.text("rig", m.rig);
    if (r.has("citation")) {
        m.citation = readCitation(r);
    } else {
        r.allow("citation");
    }
    r.text("figures", m.figures);
    {
        // Per channel: where its values come from, how they were obtained, how uncertain.
        ObjectReader c = r.object("channels");
        for (const std::string& name : columnNames()) {
            ObjectReader ch = c.object(name);
            std::string origin, kind, uncertainty;
            ch.text("origin", origin);
            ch.text("kind", kind);
            ch.text("uncertainty", uncertainty);
            ch.finish();
        }
        c.finish();
    }
    r.text("notes", m.notes);
    r.finish();
    if (!issues.empty()) return issues;
    return m;
}

}  // namespace

Result<ExperimentMetadata> parseExperimentMetadata(const std::string& text,
                                                   const std::string& where) {
    return readJsonTextWith<ExperimentMetadata>(text, where, readExperimentMetadata);
}

Result<Experiment> readExperiment(const fs::path& path) {
    fs::path csv = path, sidecar;
    std::optional<ExperimentMetadata> metadata;
    std::string text;
    if (path.extension() == ".json") {
        if (const auto error = readFile(path, text))
            return std::vector<Issue>{{pathLabel(path.string()), *error}};
        Result<ExperimentMetadata> m = parseExperimentMetadata(text, path.string());
        if (!m) return m.issues();
        if (m->data_file.empty()) {
            return std::vector<Issue>{
                {path.string() + ": data_file", "missing: the CSV of the measured points"}};
        }
        metadata = m.value();
        csv = path.parent_path() / m->data_file;
    } else {
        sidecar = fs::path(path).replace_extension(".json");
        std::error_code ec;
        if (fs::is_regular_file(sidecar, ec)) {
            if (const auto error = readFile(sidecar, text))
                return std::vector<Issue>{{pathLabel(sidecar.string()), *error}};
            Result<ExperimentMetadata> m = parseExperimentMetadata(text, sidecar.string());
            if (!m) return m.issues();
            metadata = m.value();
        }
    }
    if (const auto error = readFile(csv, text))
        return std::vector<Issue>{{pathLabel(csv.string()), *error}};
    Result<Experiment> read = parseExperimentCsv(text, csv.string());
    if (!read) return read.issues();
    Experiment out = read.value();
    out.metadata = metadata;
    return out;
}

}  // namespace terra::io
