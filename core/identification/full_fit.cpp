#include "core/identification/full_fit.h"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/wheel_forces.h"
#include "core/identification/decoupled_model.h"

namespace terra::identification {
namespace {

// Solver variables are scaled to order one: K_s in MPa/m^n, c in kPa.
constexpr std::array<double, kFullParameterCount> kScale{1.0, 1.0, 1e6, 1.0, 1e3, 1.0, 1.0};
constexpr std::array<double, kFullParameterCount> kLower{0.0, -1.0, 0.01, 0.1, 0.0, 0.0, 1e-4};
constexpr std::array<double, kFullParameterCount> kUpper{1.0, 1.0, 50.0, 2.0, 200.0, 1.047, 0.5};

struct FullResidual {
    double r, b, slip, beta, theta_f, fx, fz, my, w_fx, w_fz, w_my, jmax;
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        // γ only enters the bulldozing force, which the identification leaves out.
        const contact::ContactParameters<T> p{.radius_m = T(r),
                                              .width_m = T(b),
                                              .sinkage_exponent = x[kN],
                                              .sinkage_exponent_slip = T(0.0),
                                              .pressure_modulus = x[kKs] * 1e6,
                                              .cohesion_pa = x[kC] * 1e3,
                                              .friction_angle_rad = x[kPhi],
                                              .shear_modulus_m = x[kK],
                                              .unit_weight_n_m3 = T(0.0),
                                              .max_stress_a0 = x[kA0],
                                              .max_stress_a1 = x[kA1],
                                              .max_shear_deformation_m = jmax};
        const contact::OperatingPoint<T> op{T(slip), T(beta), T(theta_f), T(0.0), std::nullopt};
        const contact::WheelForces<T> f = contact::computeForces(p, op);
        residual[0] = (f.fx - fx) * w_fx;
        residual[1] = (f.fz - fz) * w_fz;
        residual[2] = (f.my - my) * w_my;
        return true;
    }
};

std::array<double, kFullParameterCount> toVector(const DecoupledParameters& p) {
    return {p.a0,
            p.a1,
            p.pressure_modulus / kScale[kKs],
            p.n0,
            p.cohesion_pa / kScale[kC],
            p.friction_angle_rad,
            p.shear_modulus_m};
}

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

std::string pairAdvice(int i, int j) {
    const std::set<int> pair{i, j};
    if (pair == std::set<int>{kC, kPhi}) {
        return "c and phi trade off (only c + sigma tan(phi) is seen at one load): add data at "
               "several loads";
    }
    if (pair == std::set<int>{kKs, kN}) {
        return "Ks and n trade off along a flat valley: add data over a wider range of sinkage "
               "(several loads)";
    }
    return std::string(fullParameterNames()[i]) + " and " + fullParameterNames()[j] +
           " are not separable by these data";
}

}  // namespace

const std::array<const char*, kFullParameterCount>& fullParameterNames() {
    static const std::array<const char*, kFullParameterCount> names{"a0",    "a1",      "Ks", "n",
                                                                    "c_kPa", "phi_deg", "K_m"};
    return names;
}

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
    const double s_fx = level(options.sigma_fx, rms[0], 1e-6),
                 s_fz = level(options.sigma_fz, rms[1], 1e-6),
                 s_my = level(options.sigma_my, rms[2], 1e-8);

    std::array<double, kFullParameterCount> x = toVector(start);
    for (int k = 0; k < kFullParameterCount; ++k) x[k] = std::clamp(x[k], kLower[k], kUpper[k]);
    ceres::Problem problem;
    for (const Sample& s : data.samples) {
        problem.AddResidualBlock(
            new ceres::AutoDiffCostFunction<FullResidual, 3, kFullParameterCount>(new FullResidual{
                wheel.radius_m, wheel.width_m, s.slip, s.slip_angle_rad.value_or(0.0),
                s.entry_angle_rad, s.fx_n, s.fz_n, s.my_nm, 1.0 / s_fx, 1.0 / s_fz, 1.0 / s_my,
                options.max_shear_deformation_m}),
            nullptr, x.data());
    }
    std::vector<int> fixed;
    for (int k = 0; k < kFullParameterCount; ++k) {
        if (options.fixed[k]) fixed.push_back(k);
    }
    if (static_cast<int>(fixed.size()) == kFullParameterCount) {
        problem.SetParameterBlockConstant(x.data());
    } else if (!fixed.empty()) {
        problem.SetManifold(x.data(), new ceres::SubsetManifold(kFullParameterCount, fixed));
    }
    for (int k = 0; k < kFullParameterCount; ++k) {
        if (options.fixed[k]) continue;
        problem.SetParameterLowerBound(x.data(), k, kLower[k]);
        problem.SetParameterUpperBound(x.data(), k, kUpper[k]);
    }
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::DENSE_QR;
    solver.max_num_iterations = 1000;
    // The K_s–n and c–φ valleys are long and flat: let the trust region walk along them.
    solver.use_nonmonotonic_steps = true;
    solver.function_tolerance = 1e-15;
    solver.parameter_tolerance = 1e-14;
    solver.gradient_tolerance = 1e-16;
    solver.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    const auto begin = std::chrono::steady_clock::now();
    ceres::Solve(solver, &problem, &summary);
    const auto end = std::chrono::steady_clock::now();

    RefineResult result;
    result.report.name = "IV: full model (a0, a1, Ks, n, c, phi, K)";
    result.report.usable = summary.IsSolutionUsable();
    result.report.termination = ceres::TerminationTypeToString(summary.termination_type) +
                                std::string(": ") + summary.message;
    result.report.iterations = static_cast<int>(summary.iterations.size());
    result.report.squared_residual_norm = 2.0 * summary.final_cost;  // weighted: χ²
    result.report.wall_time_ms = std::chrono::duration<double, std::milli>(end - begin).count();
    DecoupledParameters& p = result.parameters;
    p = start;
    p.a0 = x[kA0];
    p.a1 = x[kA1];
    p.pressure_modulus = x[kKs] * kScale[kKs];
    p.n0 = x[kN];
    p.n1 = 0.0;
    p.cohesion_pa = x[kC] * kScale[kC];
    p.friction_angle_rad = x[kPhi];
    p.shear_modulus_m = x[kK];

    // Uncertainty: covariance of the scaled variables, to SI.
    Uncertainty& u = result.uncertainty;
    const int free = kFullParameterCount - static_cast<int>(fixed.size());
    const int residuals = 3 * static_cast<int>(data.samples.size());
    ceres::Covariance::Options covariance_options;
    covariance_options.algorithm_type = ceres::DENSE_SVD;
    covariance_options.null_space_rank = -1;  // report rank deficiency instead of guessing
    ceres::Covariance covariance(covariance_options);
    std::vector<std::pair<const double*, const double*>> blocks{{x.data(), x.data()}};
    if (free > 0 && residuals > free && covariance.Compute(blocks, &problem)) {
        std::array<double, kFullParameterCount * kFullParameterCount> c{};
        covariance.GetCovarianceMatrix({x.data()}, c.data());
        const double chi2 = estimated ? 2.0 * summary.final_cost / (residuals - free) : 1.0;
        u.computed = true;
        for (int i = 0; i < kFullParameterCount; ++i) {
            u.std[i] =
                options.fixed[i]
                    ? 0.0
                    : std::sqrt(std::max(0.0, c[i * kFullParameterCount + i] * chi2)) * kScale[i];
        }
        for (int i = 0; i < kFullParameterCount; ++i) {
            for (int j = 0; j < kFullParameterCount; ++j) {
                const double d =
                    std::sqrt(c[i * kFullParameterCount + i] * c[j * kFullParameterCount + j]);
                u.correlation[i][j] =
                    d > 0 ? c[i * kFullParameterCount + j] / d : (i == j ? 1.0 : 0.0);
            }
        }
        for (int i = 0; i < kFullParameterCount; ++i) {
            for (int j = i + 1; j < kFullParameterCount; ++j) {
                if (options.fixed[i] || options.fixed[j]) continue;
                if (std::abs(u.correlation[i][j]) > options.correlation_flag) {
                    u.flags.push_back(pairAdvice(i, j) + " (correlation " +
                                      formatNumber(roundSignificant(u.correlation[i][j], 4)) + ")");
                }
            }
        }
    } else {
        u.flags.push_back(
            "the data do not determine all free parameters (rank-deficient covariance): "
            "fix some (--fix) or add data at several loads");
    }
    for (int k = 0; k < kFullParameterCount; ++k) {
        if (options.fixed[k]) continue;
        const double span = kUpper[k] - kLower[k];
        if (x[k] - kLower[k] < 1e-6 * span || kUpper[k] - x[k] < 1e-6 * span) {
            u.flags.push_back(std::string(fullParameterNames()[k]) +
                              " ended at its bound: not determined by the data");
            // The covariance is conditional on k held at its bound: a parameter that trades off
            // with k has compensated for it, and its standard deviation understates its error.
            if (!u.computed) continue;
            for (int j = 0; j < kFullParameterCount; ++j) {
                if (j == k || options.fixed[j] ||
                    std::abs(u.correlation[k][j]) < options.bound_correlation_flag) {
                    continue;
                }
                u.flags.push_back(std::string(fullParameterNames()[j]) +
                                  " is uncertain beyond its std: it trades off with " +
                                  fullParameterNames()[k] + " (correlation " +
                                  formatNumber(roundSignificant(u.correlation[k][j], 3)) +
                                  "), which ended at its bound");
            }
        }
    }
    return result;
}

}  // namespace terra::identification
