#include "core/analysis/soil_curves.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/bulldozing.h"
#include "core/contact/sinkage.h"
#include "core/io/declared_json.h"

namespace terra::analysis {
namespace {

double staticSinkageMm(const contact::ContactParameters<double>& p, double load_n,
                       contact::StaticContact contact) {
    const contact::SinkageSolution s = contact::solveStaticSinkage(p, load_n, contact);
    return s.ok() ? s.sinkage_m * 1e3 : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

void readSoilCurvesSettings(io::ObjectReader& r, SoilCurvesSettings& out) {
    io::readFields(r, out);
}

nlohmann::json toJson(const SoilCurvesSettings& settings) { return io::fieldsToJson(settings); }

SoilCurves computeSoilCurves(const Inputs& in, const SoilCurvesSettings& settings,
                             const Control& control) {
    // The reader's checks, in its words, for settings built in code (the forces panel's).
    if (const std::vector<Issue> issues = io::fieldIssues(settings); !issues.empty())
        throw std::invalid_argument(formatIssues(issues));
    const auto p = in.contact();
    const int n = settings.points;
    SoilCurves out;
    out.load_n = in.conditions.load_n;
    out.bulldozing.columns = {"sinkage_mm", "entry_angle_deg", "Fb_bekker_N", "Fb_hegedus_N"};
    out.static_sinkage.columns = {"load_N", "h_bekker_mm", "h_eq27_mm", "h_eq27_front_mm"};

    const double h_max = settings.max_sinkage_fraction_of_radius * p.radius_m;
    for (int i = 0; i < n; ++i) {
        const double h = h_max * i / (n - 1);
        const double theta = std::acos(std::clamp(1.0 - h / p.radius_m, -1.0, 1.0));  // Eq. 2.12
        out.bulldozing.rows.push_back(
            {h * 1e3, units::radToDeg(theta),
             contact::bulldozingForce(p, theta, contact::BulldozingModel::kBekker),
             contact::bulldozingForce(p, theta, contact::BulldozingModel::kHegedus)});
    }

    const double w_max = settings.max_load_factor * in.conditions.load_n;
    out.static_sinkage.rows.push_back({0.0, 0.0, 0.0, 0.0});  // no load, no sinkage (every model)
    for (int i = 1; i < n; ++i) {
        if (control.cancelled()) {
            out.cancelled = true;
            return out;
        }
        const double w = w_max * i / (n - 1);
        out.static_sinkage.rows.push_back(
            {w, contact::bekkerStaticSinkage(p, w) * 1e3,
             staticSinkageMm(p, w, contact::StaticContact::kSymmetric),
             staticSinkageMm(p, w, contact::StaticContact::kFrontHalf)});
    }
    return out;
}

Outcome soilCurvesOutcome(SoilCurves curves) {
    Outcome out;
    out.status = curves.cancelled ? Outcome::Status::kCancelled : Outcome::Status::kCompleted;
    out.tables.push_back({"static_sinkage", "-static-sinkage", curves.static_sinkage});
    out.tables.push_back({"bulldozing", "-bulldozing", curves.bulldozing});
    out.result = std::move(curves);
    return out;
}

AnalysisType soilCurvesType() {
    return makeAnalysisType<SoilCurvesSettings>(
        "soil-curves",
        "bulldozing resistance against sinkage and static sinkage against load (Figs. 2.15, 2.6)",
        {"static_sinkage", "bulldozing"},
        {{"bulldozing", "-bulldozing"}, {"static-sinkage", "-static-sinkage"}},
        [](io::ObjectReader& r, const ReadContext&, SoilCurvesSettings& s) {
            readSoilCurvesSettings(r, s);
        },
        [](const Inputs& in, const SoilCurvesSettings& s, const Control& c) {
            return computeSoilCurves(in, s, c);
        },
        soilCurvesOutcome);
}

}  // namespace terra::analysis
