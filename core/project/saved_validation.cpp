#include "core/project/saved_validation.h"

#include <stdexcept>

#include "core/io/parameters_json.h"
#include "core/project/result_json.h"
#include "core/project/saved_identification.h"

namespace terra::project {
namespace {

using nlohmann::json;
using saved::arrayFrom;
using saved::arrayJson;
using saved::number;
using saved::numberAt;
using saved::numberOf;
using saved::optionalAt;
using saved::optionalJson;
using saved::readKey;
using saved::tableFrom;
using saved::tableJson;

constexpr std::size_t kExpChannels = io::kExperimentChannelCount;

soil::SoilParameters calibrationSoilFrom(const json& j) {
    Result<soil::SoilParameters> soil = io::soilFromJson(j, "soil");
    if (!soil) throw std::invalid_argument(soil.message());
    return soil.value();
}

json channelMetricsJson(const analysis::ValidationMetrics& metrics) {
    json out = json::array();
    for (const auto& m : metrics) {
        if (!m) {
            out.push_back(nullptr);
            continue;
        }
        out.push_back({{"count", m->count},
                       {"rmse", number(m->rmse)},
                       {"mae", number(m->mae)},
                       {"max_rel_error", number(m->max_rel_error)}});
    }
    return out;
}

analysis::ValidationMetrics channelMetricsFrom(const json& j) {
    if (!j.is_array() || j.size() != kExpChannels)
        throw std::invalid_argument("expected " + std::to_string(kExpChannels) + " channels");
    analysis::ValidationMetrics out;
    for (std::size_t c = 0; c < kExpChannels; ++c) {
        if (j[c].is_null()) continue;
        analysis::ChannelMetrics m;
        m.count = j[c].at("count").get<std::size_t>();
        m.rmse = numberAt(j[c], "rmse");
        m.mae = numberAt(j[c], "mae");
        m.max_rel_error = numberAt(j[c], "max_rel_error");
        out[c] = m;
    }
    return out;
}

json comparisonJson(const analysis::PointComparison& p) {
    json measured = json::array();
    for (const std::optional<double>& v : p.point.measured) measured.push_back(optionalJson(v));
    return {{"load_n", number(p.point.load_n)},
            {"slip", number(p.point.slip)},
            {"slip_angle_deg", number(p.point.slip_angle_deg)},
            {"measured", std::move(measured)},
            {"line", p.point.line},
            {"predicted", p.predicted},
            {"failure", p.failure},
            {"entry_angle_deg", number(p.entry_angle_deg)},
            {"values", arrayJson(p.values)},
            {"in_fit", p.in_fit}};
}

analysis::PointComparison comparisonFrom(const json& j) {
    analysis::PointComparison p;
    p.point.load_n = numberAt(j, "load_n");
    p.point.slip = numberAt(j, "slip");
    p.point.slip_angle_deg = numberAt(j, "slip_angle_deg");
    const json& measured = j.at("measured");
    if (!measured.is_array() || measured.size() != kExpChannels)
        throw std::invalid_argument("measured: expected " + std::to_string(kExpChannels) +
                                    " channels");
    for (std::size_t c = 0; c < kExpChannels; ++c) {
        if (!measured[c].is_null()) p.point.measured[c] = numberOf(measured[c]);
    }
    p.point.line = j.at("line").get<int>();
    p.predicted = j.at("predicted").get<bool>();
    p.failure = j.at("failure").get<std::string>();
    p.entry_angle_deg = numberAt(j, "entry_angle_deg");
    p.values = arrayFrom<kExpChannels>(j.at("values"));
    p.in_fit = j.at("in_fit").get<bool>();
    return p;
}

json validationRunJson(const analysis::ValidationRun& run) {
    json points = json::array();
    for (const analysis::PointComparison& p : run.points) points.push_back(comparisonJson(p));
    return {{"soil", io::toJson(run.soil)},
            {"points", std::move(points)},
            {"metrics", channelMetricsJson(run.metrics)},
            {"curves", tableJson(run.curves)}};
}

analysis::ValidationRun validationRunFrom(const json& j) {
    analysis::ValidationRun run;
    run.soil = readKey(j, "soil", calibrationSoilFrom);
    run.points = readKey(j, "points", [](const json& points) {
        std::vector<analysis::PointComparison> out;
        for (const json& p : points) out.push_back(comparisonFrom(p));
        return out;
    });
    run.metrics = readKey(j, "metrics", channelMetricsFrom);
    run.curves = readKey(j, "curves", tableFrom);
    return run;
}

json chi2ProfileJson(const std::vector<std::pair<double, double>>& profile) {
    json out = json::array();
    for (const auto& [x, chi2] : profile) out.push_back({number(x), number(chi2)});
    return out;
}

std::vector<std::pair<double, double>> chi2ProfileFrom(const json& j) {
    std::vector<std::pair<double, double>> out;
    for (const json& point : j) out.emplace_back(numberOf(point.at(0)), numberOf(point.at(1)));
    return out;
}

json calibrationSectionJson(const analysis::Calibration& c) {
    json out{
        {"report", savedJson(c.report)},
        {"prior", arrayJson(c.prior)},
        {"channels", c.channels},
        {"soil", io::toJson(c.soil)},
        {"n1", optionalJson(c.n1)},
        {"n1_std", optionalJson(c.n1_std)},
        {"n1_profile", chi2ProfileJson(c.n1_profile)},
        {"slip_sinkage", optionalJson(c.slip_sinkage)},
        {"slip_sinkage_std", optionalJson(c.slip_sinkage_std)},
        {"slip_sinkage_profile", chi2ProfileJson(c.slip_sinkage_profile)},
        {"after", c.after ? validationRunJson(*c.after) : json(nullptr)},
        {"held_out_before", c.held_out_before ? channelMetricsJson(*c.held_out_before) : json()},
        {"held_out", c.held_out ? channelMetricsJson(*c.held_out) : json(nullptr)}};
    return out;
}

analysis::Calibration calibrationSectionFrom(const json& j) {
    analysis::Calibration c;
    c.report = readKey(j, "report", identificationReportFromJson);
    c.prior = readKey(j, "prior", arrayFrom<identification::kFullParameterCount>);
    c.channels = j.at("channels").get<std::vector<std::string>>();
    c.soil = readKey(j, "soil", calibrationSoilFrom);
    c.n1 = optionalAt(j, "n1");
    c.n1_std = optionalAt(j, "n1_std");
    c.n1_profile = readKey(j, "n1_profile", chi2ProfileFrom);
    c.slip_sinkage = optionalAt(j, "slip_sinkage");
    c.slip_sinkage_std = optionalAt(j, "slip_sinkage_std");
    c.slip_sinkage_profile = readKey(j, "slip_sinkage_profile", chi2ProfileFrom);
    if (!j.at("after").is_null()) c.after = readKey(j, "after", validationRunFrom);
    if (!j.at("held_out_before").is_null())
        c.held_out_before = readKey(j, "held_out_before", channelMetricsFrom);
    if (!j.at("held_out").is_null()) c.held_out = readKey(j, "held_out", channelMetricsFrom);
    return c;
}

}  // namespace

json savedJson(const analysis::ValidationResult& r) {
    return {{"source", r.source},
            {"before", validationRunJson(r.before)},
            {"calibration", r.calibration ? calibrationSectionJson(*r.calibration) : json(nullptr)},
            {"notes", r.notes}};
}

Result<analysis::ValidationResult> validationResultFromJson(const json& j,
                                                            const std::string& where) {
    try {
        analysis::ValidationResult r;
        r.source = j.at("source").get<std::string>();
        r.before = readKey(j, "before", validationRunFrom);
        if (!j.at("calibration").is_null())
            r.calibration = readKey(j, "calibration", calibrationSectionFrom);
        r.notes = j.at("notes").get<std::vector<std::string>>();
        // Its status as computed (a saved result is never cancelled nor an invalid input).
        r.soil = r.before.soil.name;
        r.message = analysis::validationFailure(r);
        if (!r.message.empty()) r.status = analysis::Outcome::Status::kFailed;
        return r;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
