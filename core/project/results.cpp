#include "core/project/results.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>

#include "core/io/atomic_file.h"
#include "core/io/json_reader.h"
#include "core/project/result_json.h"

namespace terra::project {
namespace {

using nlohmann::json;

using saved::matrixFrom;
using saved::matrixJson;
using saved::tableFrom;
using saved::tableJson;
using saved::vectorFrom;
using saved::vectorJson;

constexpr const char* kStatus[] = {"completed", "cancelled", "too many failures"};

gsa::StudyStatus statusFrom(const std::string& text) {
    for (int i = 0; i < 3; ++i) {
        if (text == kStatus[i]) return static_cast<gsa::StudyStatus>(i);
    }
    throw std::invalid_argument("unknown status \"" + text + "\"");
}

json failuresJson(const std::vector<gsa::FailureCounts>& failures) {
    json out = json::array();
    for (const gsa::FailureCounts& f : failures)
        out.push_back({f.no_equilibrium, f.load_not_matched, f.invalid_soil, f.non_finite});
    return out;
}

std::vector<gsa::FailureCounts> failuresFrom(const json& j) {
    std::vector<gsa::FailureCounts> out;
    for (const json& f : j) {
        out.push_back({f.at(0).get<std::size_t>(), f.at(1).get<std::size_t>(),
                       f.at(2).get<std::size_t>(), f.at(3).get<std::size_t>()});
    }
    return out;
}

/// The parts every study (Sobol', Morris, bands) shares: status, outputs, grid, failures.
template <typename Study>
json studyJson(const Study& s) {
    std::vector<std::string> outputs;
    for (gsa::Output o : s.outputs) outputs.emplace_back(gsa::outputName(o));
    json grid{{"slips", s.grid.slips},
              {"slip_angles_rad", s.grid.slip_angles_rad},
              {"entry_angle_rad", s.grid.entry_angle_rad}};
    if (s.grid.load_n) grid["load_n"] = *s.grid.load_n;
    return {{"status", kStatus[static_cast<int>(s.status)]},
            {"message", s.message},
            {"outputs", outputs},
            {"grid", grid},
            {"failures", failuresJson(s.failures)}};
}

template <typename Study>
void readStudy(const json& j, Study& s) {
    s.status = statusFrom(j.at("status").get<std::string>());
    s.message = j.at("message").get<std::string>();
    for (const std::string& name : j.at("outputs").get<std::vector<std::string>>()) {
        const std::optional<gsa::Output> o = gsa::findOutput(name);
        if (!o) throw std::invalid_argument("unknown output \"" + name + "\"");
        s.outputs.push_back(*o);
    }
    const json& grid = j.at("grid");
    s.grid.slips = grid.at("slips").get<std::vector<double>>();
    s.grid.slip_angles_rad = grid.at("slip_angles_rad").get<std::vector<double>>();
    s.grid.entry_angle_rad = grid.at("entry_angle_rad").get<double>();
    s.grid.load_n = grid.contains("load_n") ? std::optional<double>(grid.at("load_n").get<double>())
                                            : std::nullopt;
    s.failures = failuresFrom(j.at("failures"));
}

/// The parts both index studies share.
template <typename Study>
json commonJson(const Study& s) {
    json out = studyJson(s);
    out["parameters"] = s.parameters;
    out["evaluations"] = s.evaluations;
    return out;
}

template <typename Study>
void readCommon(const json& j, Study& s) {
    readStudy(j, s);
    s.parameters = j.at("parameters").get<std::vector<std::string>>();
    s.evaluations = j.at("evaluations").get<std::size_t>();
}

}  // namespace

bool SavedResult::operator==(const SavedResult& other) const {
    auto tables_json = [](const SavedResult& r) {
        json out = json::array();
        for (const analysis::NamedTable& t : r.tables) out.push_back({t.name, tableJson(t.table)});
        return out;
    };
    return inputs_hash == other.inputs_hash && version == other.version &&
           partial == other.partial && summary == other.summary && result == other.result &&
           tables_json(*this) == tables_json(other);
}

namespace {

// FNV-1a, 64 bits: fast, stable across platforms; not for security, only to notice a change.
std::string fnv1a(std::string_view bytes) {
    std::uint64_t h = 14695981039346656037ull;
    for (const char c : bytes) {
        h ^= static_cast<unsigned char>(c);
        h *= 1099511628211ull;
    }
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, h);
    return text;
}

}  // namespace

std::string inputsHash(const json& inputs) { return fnv1a(inputs.dump()); }

json fileStamp(const std::filesystem::path& path) {
    if (path.empty()) return nullptr;
    // The panels ask on every change of their settings: a file is read again only when its size
    // or time changed (a file edited within the clock's resolution and to the same size would
    // keep its old hash: the name, size and time are then all that tells it).
    struct Seen {
        std::uintmax_t size;
        std::filesystem::file_time_type time;
        std::string hash;
    };
    static std::mutex mutex;
    static std::map<std::string, Seen> seen;
    std::error_code size_error, time_error;
    const std::uintmax_t size = std::filesystem::file_size(path, size_error);
    const std::filesystem::file_time_type time = std::filesystem::last_write_time(path, time_error);
    const bool stat_ok = !size_error && !time_error;
    const std::string key = std::filesystem::absolute(path).lexically_normal().string();
    if (stat_ok) {
        const std::lock_guard lock(mutex);
        const auto it = seen.find(key);
        if (it != seen.end() && it->second.size == size && it->second.time == time)
            return it->second.hash;
    }
    std::string bytes;
    if (io::readFile(path, bytes)) return "missing";  // an error message: not readable
    std::string hash = fnv1a(bytes);
    if (stat_ok) {
        const std::lock_guard lock(mutex);
        if (seen.size() > 64) seen.clear();  // a few data files per session, never a leak
        seen[key] = {size, time, hash};
    }
    return hash;
}

std::filesystem::path resultsPathFor(const std::filesystem::path& project_file) {
    std::filesystem::path out = project_file;
    out += ".results";
    return out;
}

json toJson(const SavedResults& results) {
    json panels = json::object();
    for (const auto& [name, r] : results.panels) {
        json tables = json::array();
        for (const analysis::NamedTable& t : r.tables)
            tables.push_back({{"name", t.name}, {"table", tableJson(t.table)}});
        panels[name] = {{"inputs_hash", r.inputs_hash}, {"version", r.version},
                        {"partial", r.partial},         {"summary", r.summary},
                        {"result", r.result},           {"tables", std::move(tables)}};
    }
    return {{"format", kResultsFormat}, {"version", kResultsVersion}, {"panels", panels}};
}

Result<SavedResults> savedResultsFromJson(const json& j, const std::string& where) {
    if (!j.is_object() || j.value("format", std::string()) != kResultsFormat)
        return std::vector<Issue>{{where, "not TerraStudio results (\"format\": \"" +
                                              std::string(kResultsFormat) + "\")"}};
    const json version = j.contains("version") ? j["version"] : json();
    if (!version.is_number_integer() || version.get<int>() < 1 ||
        version.get<int>() > kResultsVersion)
        return std::vector<Issue>{
            {where + ": version",
             version.dump() + " is not a results version this studio reads (1 to " +
                 std::to_string(kResultsVersion) +
                 "; a newer studio wrote it?): the results will be computed again"}};
    if (!j.contains("panels") || !j["panels"].is_object())
        return std::vector<Issue>{{where + ": panels", "missing or not an object"}};
    SavedResults out;
    for (const auto& [name, p] : j["panels"].items()) {
        // One broken section costs that section only: the others are shown.
        try {
            SavedResult r;
            r.inputs_hash = p.at("inputs_hash").get<std::string>();
            r.partial = p.at("partial").get<bool>();
            r.summary = p.at("summary").get<std::string>();
            // Version 1 had no section versions: its one section (the global study) is 1.
            r.version = p.contains("version") ? p.at("version").get<int>() : 1;
            r.result = p.at("result");
            for (const json& t : p.at("tables"))
                r.tables.push_back(
                    {t.at("name").get<std::string>(), std::nullopt, tableFrom(t.at("table"))});
            out.panels[name] = std::move(r);
        } catch (const std::exception& e) {
            out.unreadable.push_back({where + ": panels." + name, e.what()});
        }
    }
    return out;
}

Result<SavedResults> loadResults(const std::filesystem::path& path) {
    return io::readJsonFileWith<SavedResults>(path,
                                              [](const json& document, const std::string& source) {
                                                  return savedResultsFromJson(document, source);
                                              });
}

std::optional<std::string> saveResults(const std::filesystem::path& path,
                                       const SavedResults& results) {
    if (results.panels.empty()) {
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
        return std::nullopt;
    }
    // Compact: a rover run's time series is 10⁵ numbers, one a line with an indent.
    return io::writeFileAtomically(path, toJson(results).dump() + "\n");
}

json savedJson(const analysis::GlobalSensitivityResult& result) {
    if (result.sobol) {
        const gsa::SobolStudyResult& s = *result.sobol;
        json out = commonJson(s);
        out["method"] = "sobol";
        out["base_samples"] = s.base_samples;
        out["dropped_samples"] = s.dropped_samples;
        out["S1"] = matrixJson(s.indices.first_order);
        out["ST"] = matrixJson(s.indices.total);
        out["S1_conf"] = matrixJson(s.indices.first_order_conf);
        out["ST_conf"] = matrixJson(s.indices.total_conf);
        out["mean"] = vectorJson(s.indices.mean);
        out["variance"] = vectorJson(s.indices.variance);
        out["samples_used"] = s.indices.samples_used;
        out["constant"] = s.indices.constant;
        return out;
    }
    const gsa::MorrisStudyResult& m = *result.morris;
    json out = commonJson(m);
    out["method"] = "morris";
    out["dropped_trajectories"] = m.dropped_trajectories;
    out["mu"] = matrixJson(m.indices.mu);
    out["mu_star"] = matrixJson(m.indices.mu_star);
    out["sigma"] = matrixJson(m.indices.sigma);
    out["mu_star_conf"] = matrixJson(m.indices.mu_star_conf);
    out["trajectories_used"] = m.indices.trajectories_used;
    return out;
}

Result<analysis::GlobalSensitivityResult> globalSensitivityResultFromJson(
    const json& j, const std::string& where) {
    try {
        analysis::GlobalSensitivityResult out;
        const std::string method = j.at("method").get<std::string>();
        if (method == "sobol") {
            gsa::SobolStudyResult s;
            readCommon(j, s);
            s.base_samples = j.at("base_samples").get<std::size_t>();
            s.dropped_samples = j.at("dropped_samples").get<std::vector<std::size_t>>();
            s.indices.first_order = matrixFrom(j.at("S1"));
            s.indices.total = matrixFrom(j.at("ST"));
            s.indices.first_order_conf = matrixFrom(j.at("S1_conf"));
            s.indices.total_conf = matrixFrom(j.at("ST_conf"));
            s.indices.mean = vectorFrom(j.at("mean"));
            s.indices.variance = vectorFrom(j.at("variance"));
            s.indices.samples_used = j.at("samples_used").get<std::vector<std::size_t>>();
            s.indices.constant = j.at("constant").get<std::vector<bool>>();
            out.method = analysis::GsaMethod::kSobol;
            out.sobol = std::move(s);
        } else if (method == "morris") {
            gsa::MorrisStudyResult m;
            readCommon(j, m);
            m.dropped_trajectories = j.at("dropped_trajectories").get<std::vector<std::size_t>>();
            m.indices.mu = matrixFrom(j.at("mu"));
            m.indices.mu_star = matrixFrom(j.at("mu_star"));
            m.indices.sigma = matrixFrom(j.at("sigma"));
            m.indices.mu_star_conf = matrixFrom(j.at("mu_star_conf"));
            m.indices.trajectories_used = j.at("trajectories_used").get<std::vector<std::size_t>>();
            out.method = analysis::GsaMethod::kMorris;
            out.morris = std::move(m);
        } else {
            return std::vector<Issue>{
                {where + ".method", "\"" + method + "\" is not sobol or morris"}};
        }
        // The indices must fit the grid: parameters × (outputs × points) in every matrix.
        const std::size_t rows = out.parameters().size();
        const std::size_t cols = out.outputs().size() * out.grid().size();
        const Eigen::MatrixXd& check =
            out.sobol ? out.sobol->indices.first_order : out.morris->indices.mu_star;
        const std::vector<std::size_t>& used =
            out.sobol ? out.sobol->indices.samples_used : out.morris->indices.trajectories_used;
        if (out.status() != gsa::StudyStatus::kTooManyFailures &&
            (static_cast<std::size_t>(check.rows()) != rows ||
             static_cast<std::size_t>(check.cols()) != cols || used.size() != cols))
            return std::vector<Issue>{{where, "the indices do not match the parameters and grid"}};
        return out;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

json savedJson(const analysis::UncertaintyBandResult& result) {
    const gsa::BandResult& b = result.bands;
    json out = studyJson(b);
    out["percentiles"] = b.percentiles;
    json bands = json::array();
    for (const Eigen::MatrixXd& m : b.bands) bands.push_back(matrixJson(m));
    out["bands"] = std::move(bands);
    out["mean"] = matrixJson(b.mean);
    out["used"] = b.used;
    out["nominal"] = matrixJson(result.nominal);
    return out;
}

Result<analysis::UncertaintyBandResult> uncertaintyBandsFromJson(const json& j,
                                                                 const std::string& where) {
    try {
        analysis::UncertaintyBandResult out;
        gsa::BandResult& b = out.bands;
        readStudy(j, b);
        b.percentiles = j.at("percentiles").get<std::vector<double>>();
        for (const json& m : j.at("bands")) b.bands.push_back(matrixFrom(m));
        b.mean = matrixFrom(j.at("mean"));
        b.used = j.at("used").get<std::vector<std::size_t>>();
        out.nominal = matrixFrom(j.at("nominal"));
        // Every matrix must fit the grid: percentiles × points per output, outputs × points.
        const auto points = static_cast<Eigen::Index>(b.grid.size());
        const auto outputs = static_cast<Eigen::Index>(b.outputs.size());
        bool fits = out.nominal.size() == 0 ||
                    (out.nominal.rows() == outputs && out.nominal.cols() == points);
        if (b.usable()) {
            fits = fits && b.used.size() == b.grid.size() && b.bands.size() == b.outputs.size() &&
                   b.mean.rows() == outputs && b.mean.cols() == points;
            for (const Eigen::MatrixXd& m : b.bands)
                fits = fits && m.rows() == static_cast<Eigen::Index>(b.percentiles.size()) &&
                       m.cols() == points;
        }
        if (!fits)
            return std::vector<Issue>{{where, "the bands do not match the outputs and grid"}};
        return out;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
