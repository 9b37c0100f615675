#include "core/analysis/soil_posterior.h"

#include "core/identification/parameters.h"
#include "core/io/json.h"
#include "core/soil/soil_parameters.h"

namespace terra::analysis {

std::string soilKeyOf(const std::string& name) {
    // The identification's key (or its old one, "Ks", issue 26) of K_s and n₀, whose soil keys
    // differ; every other identification key is its soil key.
    const identification::ParameterLookup found = identification::lookupParameter(name);
    return found ? identification::soilKeyOf(*found.field) : name;
}

void readPosterior(io::ObjectReader& r, SoilPosterior& out) {
    r.texts("parameters", out.parameters, io::Presence::kRequired);
    for (std::string& name : out.parameters) {
        // An old identification key (issue 26) is read as its new one, with the note the flags
        // give; "n" is also the soil file's key of n₀, which a posterior may use: no note.
        if (identification::lookupParameter(name).deprecated && !soil::findSoilField(name))
            out.notes.push_back(r.where("parameters") + ": " +
                                identification::deprecationNote(name));
        name = soilKeyOf(name);
    }
    r.numbers("mean", out.mean, Range{-1e300, 1e300}, {}, 1, 100, io::Presence::kRequired);
    if (const nlohmann::json* rows = r.array("covariance", io::Presence::kRequired)) {
        for (std::size_t i = 0; i < rows->size(); ++i) {
            const nlohmann::json& row = (*rows)[i];
            std::vector<double> values;
            bool ok = row.is_array();
            for (const nlohmann::json& v : row) {
                ok = ok && v.is_number();
                if (ok) values.push_back(v.get<double>());
            }
            if (!ok) {
                r.report("covariance", "row " + std::to_string(i) + " is not an array of numbers");
                continue;
            }
            out.covariance.push_back(std::move(values));
        }
    }
}

Result<SoilPosterior> readPosteriorFile(const std::filesystem::path& path) {
    Result<nlohmann::json> file = io::readJsonFile(path);
    if (!file) {
        // A file that cannot be opened names itself in the message already.
        std::vector<Issue> issues = file.issues();
        for (Issue& issue : issues) {
            if (issue.message.find(path.string()) != std::string::npos) issue.where.clear();
        }
        return issues;
    }
    const nlohmann::json& doc = file.value();
    std::vector<Issue> issues;
    const bool nested = doc.is_object() && doc.contains("posterior");
    io::ObjectReader r(nested ? doc["posterior"] : doc, issues, path.string(),
                       nested ? "posterior" : "");
    SoilPosterior p;
    readPosterior(r, p);
    r.finish();
    if (!issues.empty()) return issues;
    return p;
}

bool isSoilFile(const std::filesystem::path& path) {
    Result<nlohmann::json> file = io::readJsonFile(path);
    return file && file.value().is_object() && file.value().contains("phi_deg");
}

}  // namespace terra::analysis
