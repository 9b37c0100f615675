#include "core/analysis/identification.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/analysis/sweep.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/contact/wheel_forces.h"
#include "core/identification/synthetic.h"

namespace terra::analysis {
namespace {

namespace id = identification;

const Range kNoisePercent{0.0, 100.0};
const Range kSigma{0.0, 1e6};

// The data of the settings: given, read from the CSV, or synthesised from the inputs' soil.
void loadData(const Inputs& in, const IdentificationSettings& s, IdentificationResult& out) {
    if (s.data) {
        out.data = *s.data;
        return;
    }
    if (!s.csv.empty()) {
        auto read =
            id::readDataSet(s.csv, s.skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop);
        if (!read) {
            out.data_issues = read.issues();
            out.message = read.message();
            return;
        }
        out.data = read->data;
        out.skipped = read->skipped;
        return;
    }
    id::SyntheticSpec spec;
    spec.loads_n = s.synthetic.loads_n.empty() ? std::vector<double>{in.conditions.load_n}
                                               : s.synthetic.loads_n;
    spec.slips = linspace(0.0, std::min(in.conditions.slip_max, SyntheticSource::kMaxSlip),
                          s.synthetic.slip_count);
    const double relative = s.synthetic.noise_percent / 100.0;
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = relative;
    spec.seed = s.synthetic.seed;
    id::SyntheticData synthetic = id::synthesize(in.contact(), spec);
    out.data = std::move(synthetic.data);
    out.warnings = std::move(synthetic.warnings);
}

}  // namespace

void readIdentificationSettings(io::ObjectReader& r, const ReadContext& context,
                                IdentificationSettings& out) {
    r.boolean("skip_bad_rows", out.skip_bad_rows);
    if (r.text("csv", out.csv) && !out.csv.empty()) {
        std::filesystem::path path(out.csv);
        if (path.is_relative() && !context.base_dir.empty()) path = context.base_dir / path;
        out.csv = path.string();
        auto read =
            id::readDataSet(path, out.skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop);
        if (!read) {
            for (const Issue& issue : read.issues())
                r.report("csv", issue.where + ": " + issue.message);
        } else if (read->data.samples.empty()) {
            r.report("csv", out.csv + ": no valid samples");
        } else {
            out.data = read->data;
        }
    }
    r.number("noise_percent", out.synthetic.noise_percent, kNoisePercent, "%");
    r.integer("seed", out.synthetic.seed, 0, std::numeric_limits<std::uint64_t>::max());
    const FieldInfo& load = contact::loadField();
    r.numbers("loads_N", out.synthetic.loads_n, load.range, load.displayUnit(), 1);
    const FieldInfo& count = slipCountField();
    r.integer(count.key, out.synthetic.slip_count, static_cast<int>(count.range.low),
              static_cast<int>(count.range.high));
    r.boolean("refine", out.refine);
    if (r.has("fix")) {
        io::ObjectReader fix = r.object("fix");
        for (const IdentifiedField& field : identifiedFields()) {
            if (!fullParameterOf(field)) continue;  // n1 is not refined
            double value = 0.0;
            if (fix.number(field.key, value, field.range, field.displayUnit()))
                out.fixed.emplace_back(field.key, value);
        }
        fix.finish();
    } else {
        r.allow("fix");
    }
    if (r.has("noise")) {
        io::ObjectReader noise = r.object("noise");
        noise.number("Fx_N", out.sigma_fx_n, kSigma, "N");
        noise.number("Fz_N", out.sigma_fz_n, kSigma, "N");
        noise.number("My_Nm", out.sigma_my_nm, kSigma, "N·m");
        noise.finish();
    } else {
        r.allow("noise");
    }
    const soil::SoilField* jmax = soil::findSoilField("jmax_m");
    double value = 0.0;
    if (r.field(*jmax, value)) out.max_shear_deformation_m = value;
}

nlohmann::json toJson(const IdentificationSettings& s) {
    nlohmann::json out{{"csv", s.csv},
                       {"noise_percent", s.synthetic.noise_percent},
                       {"seed", s.synthetic.seed},
                       {"slip_count", s.synthetic.slip_count},
                       {"refine", s.refine}};
    if (s.skip_bad_rows) out["skip_bad_rows"] = true;
    if (!s.synthetic.loads_n.empty()) out["loads_N"] = s.synthetic.loads_n;
    for (const auto& [key, value] : s.fixed) out["fix"][key] = value;
    if (s.sigma_fx_n > 0 || s.sigma_fz_n > 0 || s.sigma_my_nm > 0) {
        out["noise"] = {{"Fx_N", s.sigma_fx_n}, {"Fz_N", s.sigma_fz_n}, {"My_Nm", s.sigma_my_nm}};
    }
    if (s.max_shear_deformation_m) out["jmax_m"] = *s.max_shear_deformation_m;
    return out;
}

std::vector<id::StepReport> IdentificationResult::steps() const {
    std::vector<id::StepReport> out = fit.steps;
    if (refined) out.push_back(refined->report);
    return out;
}

bool IdentificationResult::usable() const {
    if (!message.empty()) return false;
    bool ok = fit.usable();
    if (refined) ok = ok && refined->report.usable;
    return ok;
}

IdentificationResult computeIdentification(const Inputs& in, const IdentificationSettings& s,
                                           const Control&) {
    std::vector<Issue> issues;
    checkRange(issues, "noise_percent", s.synthetic.noise_percent, kNoisePercent, "%");
    for (const auto& [key, value] : s.fixed) {
        const IdentifiedField* field = findIdentifiedField(key);
        if (field == nullptr || !fullParameterOf(*field)) {
            issues.push_back({"fix", "'" + key + "' is not a refined parameter"});
        } else {
            checkRange(issues, "fix " + key, value, field->range, field->displayUnit());
        }
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    IdentificationResult out;
    loadData(in, s, out);
    if (!out.message.empty()) return out;
    if (out.data.samples.empty()) {
        out.message = "the data set has no samples";
        return out;
    }
    const auto start = std::chrono::steady_clock::now();
    out.fit = id::fitDecoupled(out.data, in.wheel, s.guess);
    id::DecoupledParameters p = out.fit.parameters;
    const double jmax = s.max_shear_deformation_m.value_or(in.soil.max_shear_deformation_m);
    if (s.refine) {
        id::RefineOptions options;
        for (const auto& [key, value] : s.fixed) {
            const IdentifiedField& field = *findIdentifiedField(key);
            field.setUserValue(p, value);
            options.fixed[*fullParameterOf(field)] = true;
        }
        options.sigma_fx = s.sigma_fx_n;
        options.sigma_fz = s.sigma_fz_n;
        options.sigma_my = s.sigma_my_nm;
        options.max_shear_deformation_m = jmax;
        out.refined = id::refineFullModel(out.data, in.wheel, p, options);
        p = out.refined->parameters;
    }
    out.identified = p;
    out.fit_time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    out.curves.columns = {"slip",     "entry_angle_deg", "Fx_N",      "Fz_N", "My_Nm",
                          "Fx_fit_N", "Fz_fit_N",        "My_fit_Nm", "W_N"};
    // Fitted curves: the full model with the identified parameters when refined (its forward
    // model), else the decoupled model the fit used. γ only enters bulldozing, left out here.
    std::optional<contact::ContactParameters<double>> full;
    if (out.refined) {
        full = contact::ContactParameters<double>{.radius_m = in.wheel.radius_m,
                                                  .width_m = in.wheel.width_m,
                                                  .sinkage_exponent = p.n0,
                                                  .sinkage_exponent_slip = 0.0,
                                                  .pressure_modulus = p.pressure_modulus,
                                                  .cohesion_pa = p.cohesion_pa,
                                                  .friction_angle_rad = p.friction_angle_rad,
                                                  .shear_modulus_m = p.shear_modulus_m,
                                                  .unit_weight_n_m3 = in.soil.unit_weight_n_m3,
                                                  .max_stress_a0 = p.a0,
                                                  .max_stress_a1 = p.a1,
                                                  .max_shear_deformation_m = jmax};
    }
    for (const id::Sample& sample : out.data.samples) {
        double fx, fz, my;
        if (full) {
            const contact::OperatingPoint<double> op{sample.slip,
                                                     sample.slip_angle_rad.value_or(0.0),
                                                     sample.entry_angle_rad, 0.0, std::nullopt};
            const auto f = contact::computeForces(*full, op);
            fx = f.fx;
            fz = f.fz;
            my = f.my;
        } else {
            const auto f = id::decoupledForward(p, in.wheel, sample.slip, sample.entry_angle_rad);
            fx = f.fx_n;
            fz = f.fz_n;
            my = f.my_nm;
        }
        out.curves.rows.push_back({sample.slip, units::radToDeg(sample.entry_angle_rad),
                                   sample.fx_n, sample.fz_n, sample.my_nm, fx, fz, my,
                                   sample.load_n.value_or(std::nan(""))});
    }
    std::vector<double> row;
    for (const IdentifiedField& field : identifiedFields()) {
        out.parameters.columns.emplace_back(field.key);
        row.push_back(field.toUser(p.*field.member));
    }
    if (out.refined && out.refined->uncertainty.computed) {
        const auto& sd = out.refined->uncertainty.std;
        for (int k = 0; k < id::kFullParameterCount; ++k) {
            const IdentifiedField& field = fieldOf(static_cast<id::FullParameter>(k));
            out.parameters.columns.push_back(std::string(field.key) + "_std");
            row.push_back(sd[static_cast<std::size_t>(k)] / field.to_si);
        }
    }
    out.parameters.rows.push_back(std::move(row));
    return out;
}

Outcome identificationOutcome(IdentificationResult result) {
    Outcome out;
    if (!result.message.empty()) {
        out.status = Outcome::Status::kFailed;
        out.message = result.message;
    }
    out.tables.push_back({"parameters", "-parameters", result.parameters});
    out.tables.push_back({"curves", "", result.curves});
    out.notes = result.warnings;
    for (const Issue& skipped : result.skipped)
        out.notes.push_back("skipped " + skipped.where + ": " + skipped.message);
    for (const id::StepReport& step : result.steps()) {
        out.notes.push_back(step.name + ": " + step.termination +
                            ", Σr² = " + formatNumber(step.squared_residual_norm));
    }
    out.result = std::move(result);
    return out;
}

AnalysisType identificationType() {
    return makeAnalysisType<IdentificationSettings>(
        "identification",
        "soil parameters from wheel data (CSV or synthetic): decoupled fit, refined through the "
        "full model (chapter 5, Figs. 5.1-5.6)",
        {"parameters", "curves"}, {{"Fx", "-Fx"}, {"Fz", "-Fz"}, {"My", "-My"}},
        readIdentificationSettings,
        [](const Inputs& in, const IdentificationSettings& s, const Control& c) {
            return computeIdentification(in, s, c);
        },
        identificationOutcome);
}

}  // namespace terra::analysis
