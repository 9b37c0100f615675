#include "widgets/analyses/analyses.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/common/units.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"
#include "core/identification/synthetic.h"

namespace terra::ui {
namespace {

analysis::SweepSpec sweepSpec(const AnalysisInputs& in, const std::atomic<bool>* cancel) {
    analysis::SweepSpec spec;
    spec.slips = analysis::linspace(0.0, in.conditions.slip_max, in.conditions.slip_count);
    for (double beta : in.conditions.slip_angles_deg)
        spec.slip_angles_rad.push_back(units::degToRad(beta));
    spec.load_n = in.conditions.load_n;
    spec.model =
        in.conditions.quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    spec.cancel = cancel;
    return spec;
}

}  // namespace

analysis::SweepResult computeForceSweep(const AnalysisInputs& in, const std::atomic<bool>* cancel) {
    return analysis::sweepSlip(contact::makeContactParameters(in.soil, in.wheel),
                               sweepSpec(in, cancel));
}

StressResult computeStresses(const AnalysisInputs& in, const StressSettings& settings) {
    const auto params = contact::makeContactParameters(in.soil, in.wheel);
    contact::EntryAngleProblem problem;
    problem.load_n = in.conditions.load_n;
    problem.slip = settings.slip;
    problem.slip_angle_rad = units::degToRad(settings.slip_angle_deg);
    problem.model =
        in.conditions.quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    const contact::SinkageSolution solution = contact::solveEntryAngle(params, problem);
    StressResult out;
    out.table.columns = {"theta_deg",    "sigma_kPa",      "tau_kPa",
                         "tau_t_kPa",    "tau_l_kPa",      "sigma_quad_kPa",
                         "tau_quad_kPa", "tau_t_quad_kPa", "tau_l_quad_kPa"};
    if (!solution.ok()) {
        out.message = solution.message;
        return out;
    }
    const contact::OperatingPoint<double> op =
        contact::operatingPoint(problem, solution.entry_angle_rad);
    const contact::StressField<double> field(params, op);
    const contact::QuadraticStress<double> quad = contact::fitQuadraticStress(field);
    out.entry_angle_deg = units::radToDeg(field.entryAngle());
    out.max_stress_angle_deg = units::radToDeg(field.maxStressAngle());
    const int n = std::max(settings.points, 3);
    for (int i = 0; i < n; ++i) {
        const double theta =
            field.exitAngle() + (field.entryAngle() - field.exitAngle()) * i / (n - 1);
        const auto e = field.at(theta);
        const auto q = quad.at(theta);
        out.table.rows.push_back({units::radToDeg(theta), e.sigma / 1e3, e.tau / 1e3, e.tau_t / 1e3,
                                  e.tau_l / 1e3, q.sigma / 1e3, q.tau / 1e3, q.tau_t / 1e3,
                                  q.tau_l / 1e3});
    }
    // MODEL-NOTES: Tables 2.4–2.5 are computed on a 0.01° grid.
    out.errors = contact::quadraticApproximationErrors(params, op, units::degToRad(0.01));
    return out;
}

SensitivityResult computeSensitivity(const AnalysisInputs& in, const SensitivitySettings& settings,
                                     const std::atomic<bool>* cancel) {
    SensitivityResult out;
    analysis::SweepSpec spec = sweepSpec(in, cancel);
    spec.slip_angles_rad = {units::degToRad(settings.slip_angle_deg)};
    spec.slips = analysis::linspace(0.0, in.conditions.slip_max, settings.slip_count);
    const auto parameters = analysis::thesisSensitivityParameters();
    for (const auto& parameter : parameters) {
        if (parameter.key == settings.parameter) {
            out.family = analysis::sensitivity(in.soil, in.wheel, parameter, spec);
        }
    }
    if (out.family.table.columns.empty()) {
        throw std::invalid_argument(
            "sensitivity parameter \"" + settings.parameter +
            "\" is not one of Table 4.1 (n, c_kPa, phi_deg, kc, kphi, K_m)");
    }
    // Tornado: F_x at one slip for the extreme variations of each parameter.
    analysis::SweepSpec point = spec;
    point.slips = {settings.tornado_slip};
    const analysis::SweepResult base =
        analysis::sweepSlip(contact::makeContactParameters(in.soil, in.wheel), point);
    const double base_fx =
        base.table.rows.empty() ? std::nan("") : base.table.values("Fx_N").front();
    out.tornado.columns = {"parameter_index", "Fx_low_N", "Fx_high_N", "Fx_base_N"};
    for (std::size_t i = 0; i < parameters.size(); ++i) {
        if (cancel && cancel->load()) break;
        analysis::SensitivityParameter extremes{
            parameters[i].key, {parameters[i].values.front(), parameters[i].values.back()}};
        const analysis::SweepResult r = analysis::sensitivity(in.soil, in.wheel, extremes, point);
        double low = std::nan(""), high = std::nan("");
        const std::size_t key = r.table.column(extremes.key), fx = r.table.column("Fx_N");
        for (const auto& row : r.table.rows) {
            if (row[key] == extremes.values[0]) low = row[fx];
            if (row[key] == extremes.values[1]) high = row[fx];
        }
        out.tornado.rows.push_back({static_cast<double>(i), low, high, base_fx});
        out.tornado_keys.push_back(extremes.key);
    }
    return out;
}

IdentificationResult computeIdentification(const AnalysisInputs& in,
                                           const IdentificationSettings& settings) {
    namespace id = identification;
    IdentificationResult out;
    if (!settings.csv.empty()) {
        auto read = id::readDataSet(settings.csv, id::BadRows::kSkip);
        if (!read) {
            out.message = read.message();
            return out;
        }
        out.data = read->data;
    } else {
        id::SyntheticSpec spec;
        spec.loads_n =
            settings.loads_n.empty() ? std::vector<double>{in.conditions.load_n} : settings.loads_n;
        spec.slips =
            analysis::linspace(0.0, std::min(in.conditions.slip_max, 0.9), settings.slip_count);
        spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative =
            settings.noise_relative;
        spec.seed = settings.seed;
        out.data = id::synthesize(contact::makeContactParameters(in.soil, in.wheel), spec).data;
    }
    if (out.data.samples.empty()) {
        out.message = "the data set has no samples";
        return out;
    }
    const auto start = std::chrono::steady_clock::now();
    out.fit = id::fitDecoupled(out.data, in.wheel, id::DecoupledParameters{});
    id::DecoupledParameters p = out.fit.parameters;
    if (settings.refine) {
        id::RefineOptions options;
        // j_max is a setting of the forward model, not identified: the project soil's.
        options.max_shear_deformation_m = in.soil.max_shear_deformation_m;
        out.refined = id::refineFullModel(out.data, in.wheel, p, options);
        p = out.refined->parameters;
    }
    out.fit_time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    out.curves.columns = {"slip",     "entry_angle_deg", "Fx_N",      "Fz_N", "My_Nm",
                          "Fx_fit_N", "Fz_fit_N",        "My_fit_Nm", "W_N"};
    // Fitted curves: the full model with the identified parameters when refined (its forward
    // model), else the decoupled model the fit used.
    std::optional<contact::ContactParameters<double>> full;
    if (out.refined) {
        full = contact::ContactParameters<double>{in.wheel.radius_m,
                                                  in.wheel.width_m,
                                                  p.n0,
                                                  0.0,
                                                  p.pressure_modulus,
                                                  p.cohesion_pa,
                                                  p.friction_angle_rad,
                                                  p.shear_modulus_m,
                                                  in.soil.unit_weight_n_m3,
                                                  p.a0,
                                                  p.a1,
                                                  in.soil.max_shear_deformation_m};
    }
    for (const auto& s : out.data.samples) {
        double fx, fz, my;
        if (full) {
            const contact::OperatingPoint<double> op{s.slip, s.slip_angle_rad.value_or(0.0),
                                                     s.entry_angle_rad, 0.0, std::nullopt};
            const auto f = contact::computeForces(*full, op);
            fx = f.fx;
            fz = f.fz;
            my = f.my;
        } else {
            const auto f = id::decoupledForward(p, in.wheel, s.slip, s.entry_angle_rad);
            fx = f.fx_n;
            fz = f.fz_n;
            my = f.my_nm;
        }
        out.curves.rows.push_back({s.slip, units::radToDeg(s.entry_angle_rad), s.fx_n, s.fz_n,
                                   s.my_nm, fx, fz, my, s.load_n.value_or(std::nan(""))});
    }
    out.parameters.columns = {"a0", "a1", "Ks_kPa", "n0", "n1", "c_kPa", "phi_deg", "K_m"};
    out.parameters.rows.push_back({p.a0, p.a1, p.pressure_modulus / 1e3, p.n0, p.n1,
                                   p.cohesion_pa / 1e3, units::radToDeg(p.friction_angle_rad),
                                   p.shear_modulus_m});
    if (out.refined && out.refined->uncertainty.computed) {
        const auto& sd = out.refined->uncertainty.std;
        using id::FullParameter;
        for (const char* c :
             {"a0_std", "a1_std", "Ks_kPa_std", "n0_std", "c_kPa_std", "phi_deg_std", "K_m_std"}) {
            out.parameters.columns.push_back(c);
        }
        auto& row = out.parameters.rows.front();
        row.insert(row.end(), {sd[id::kA0], sd[id::kA1], sd[id::kKs] / 1e3, sd[id::kN],
                               sd[id::kC] / 1e3, units::radToDeg(sd[id::kPhi]), sd[id::kK]});
    }
    return out;
}

}  // namespace terra::ui
