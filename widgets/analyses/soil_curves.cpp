#include "widgets/analyses/soil_curves.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/common/units.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"

namespace terra::ui {
namespace {

bool cancelled(const std::atomic<bool>* cancel) { return cancel && cancel->load(); }

double staticSinkageMm(const contact::ContactParameters<double>& p, double load_n,
                       contact::StaticContact contact) {
    const contact::SinkageSolution s = contact::solveStaticSinkage(p, load_n, contact);
    return s.ok() ? s.sinkage_m * 1e3 : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

SoilCurves computeSoilCurves(const AnalysisInputs& in, const SoilCurvesSettings& settings,
                             const std::atomic<bool>* cancel) {
    const auto p = contact::makeContactParameters(in.soil, in.wheel);
    const int n = std::max(settings.points, 2);
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
        if (cancelled(cancel)) return out;
        const double w = w_max * i / (n - 1);
        out.static_sinkage.rows.push_back(
            {w, contact::bekkerStaticSinkage(p, w) * 1e3,
             staticSinkageMm(p, w, contact::StaticContact::kSymmetric),
             staticSinkageMm(p, w, contact::StaticContact::kFrontHalf)});
    }
    return out;
}

}  // namespace terra::ui
