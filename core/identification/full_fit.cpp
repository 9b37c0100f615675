#include "core/identification/full_fit.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/identification/decoupled_model.h"
#include "core/identification/fit_problem.h"

namespace terra::identification {
namespace {

// RMS of each channel's decoupled-model residual: a noise estimate when none is given.
std::array<double, 3> decoupledResidualRms(const DataSet& data, const wheel::WheelParameters& w,
                                           const DecoupledParameters& p) {
    std::array<double, 3> sum{};
    for (const Sample& s : data.samples) {
        const HatCoefficients<double> h = hatCoefficients(p.a0, p.a1, s.slip, s.entry_angle_rad);
        const double fx = decoupledDrawbarPull(h, w.radius_m, s.fz_n, s.my_nm);
        const double fz = decoupledVerticalForce(h, w.radius_m, w.width_m, p.pressure_modulus, p.n0,
                                                 p.n1, s.slip, s.entry_angle_rad, s.my_nm);
        const double my =
            decoupledTorque(h, w.radius_m, w.width_m, p.cohesion_pa, p.friction_angle_rad,
                            p.shear_modulus_m, s.slip, s.entry_angle_rad, s.fz_n);
        sum[0] += std::pow(fx - s.fx_n, 2);
        sum[1] += std::pow(fz - s.fz_n, 2);
        sum[2] += std::pow(my - s.my_nm, 2);
    }
    for (double& v : sum) v = std::sqrt(v / static_cast<double>(data.samples.size()));
    return sum;
}

}  // namespace

RefineResult refineFullModel(const DataSet& data, const wheel::WheelParameters& wheel,
                             const DecoupledParameters& start, const RefineOptions& options) {
    wheel::requireValid(wheel);
    if (data.samples.empty()) throw std::invalid_argument("data set: no samples to fit");
    const std::array<double, 3> rms = decoupledResidualRms(data, wheel, start);
    const bool estimated = !(options.sigma_fx > 0 && options.sigma_fz > 0 && options.sigma_my > 0);
    // Noise levels: given, or the decoupled residual RMS, with a floor so a perfect channel does
    // not get an infinite weight.
    auto level = [](double given, double fallback, double floor) {
        return given > 0 ? given : std::max(fallback, floor);
    };
    DataSet measured = data;
    measured.columns = DataColumns{};
    const Result<ModelSetup> setup = setupModel(measured, DataSource::kEntryAngle, std::nullopt,
                                                options.max_shear_deformation_m);
    if (!setup) throw std::invalid_argument(setup.message());
    const ObservationModel model(measured, wheel, setup.value());
    detail::Objective objective;
    objective.model = &model;
    objective.sigma = {level(options.sigma_fx, rms[0], 1e-6), level(options.sigma_fz, rms[1], 1e-6),
                       level(options.sigma_my, rms[2], 1e-8), 1.0};
    objective.fixed = options.fixed;
    objective.fixed[kJmax] = true;  // a setting of this refinement, never estimated
    const std::vector<std::size_t> all = detail::allSamples(model.size());
    const detail::FitProblem problem(objective, all);
    ParameterVector start_vector = vectorOf(start);
    start_vector[kJmax] = options.max_shear_deformation_m;
    const ParameterVector u0 = toSolver(start_vector);
    std::vector<double> u(u0.begin(), u0.end());
    const auto begin = std::chrono::steady_clock::now();
    const detail::BoxSummary summary =
        detail::solveInBox(problem.box(), u, detail::refinementOptions());
    const auto end = std::chrono::steady_clock::now();

    RefineResult result;
    // The seven parameters it refines (j_max is held here, never estimated).
    std::string name = "IV: full model (";
    for (int k = 0; k < kJmax; ++k)
        name += (k == 0 ? "" : ", ") + reference(static_cast<FullParameter>(k));
    result.report.name = name + ")";
    result.report.usable = summary.usable;
    result.report.termination = summary.termination;
    result.report.iterations = summary.iterations;
    result.report.squared_residual_norm = 2.0 * summary.cost;  // weighted: χ²
    result.report.wall_time_ms = std::chrono::duration<double, std::milli>(end - begin).count();
    const std::array<double, kFullParameterCount> x = toPhysical(u.data());
    DecoupledParameters& p = result.parameters;
    p = decoupledOf(x);
    p.max_shear_deformation_m = start.max_shear_deformation_m;  // held, never estimated here
    if (!summary.usable) return result;

    int free = 0;
    for (bool f : objective.fixed) free += !f;
    const int residuals = problem.dataResiduals();
    if (free == 0 || residuals <= free) {
        result.uncertainty.flags.push_back(
            "the data do not determine all free parameters (rank-deficient covariance): "
            "fix some (--fix) or add data at several loads");
        return result;
    }
    const double chi2 = estimated ? 2.0 * summary.cost / (residuals - free) : 1.0;
    result.uncertainty =
        detail::analyseSolution(objective, all, u, summary.at_bound, chi2, options.correlation_flag,
                                options.bound_correlation_flag)
            .uncertainty;
    return result;
}

}  // namespace terra::identification
