#include "core/analysis/validation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "core/analysis/operating_point.h"
#include "core/analysis/registry.h"
#include "core/common/units.h"
#include "core/identification/parameter_text.h"
#include "core/identification/parameters.h"
#include "core/io/declared_json.h"

namespace terra::analysis {
namespace {

namespace id = identification;
using io::kExperimentChannelCount;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A fit slip matches a point's slip to this (slips are read from files as typed).
constexpr double kSlipMatch = 1e-9;
// The channels the identification from the load can fit, and its channel of each.
constexpr std::array<std::optional<id::Channel>, kExperimentChannelCount> kFitChannel{
    id::kFxChannel, id::kMyChannel, id::kSinkageChannel, std::nullopt, std::nullopt};

const char* nameOf(std::size_t c) { return io::experimentChannels()[c].name; }

bool inFitSlips(double slip, const std::vector<double>& fit_slips) {
    if (fit_slips.empty()) return true;
    return std::any_of(fit_slips.begin(), fit_slips.end(),
                       [slip](double s) { return std::abs(s - slip) <= kSlipMatch; });
}

nlohmann::json metricsJson(const ValidationMetrics& metrics) {
    nlohmann::json out = nlohmann::json::object();
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (!metrics[c]) continue;
        const ChannelMetrics& m = *metrics[c];
        out[nameOf(c)] = {
            {"rmse", m.rmse},
            {"mae", m.mae},
            {"max_rel_error",
             std::isnan(m.max_rel_error) ? nlohmann::json() : nlohmann::json(m.max_rel_error)},
            {"count", m.count}};
    }
    return out;
}

nlohmann::json pointsJson(const std::vector<PointComparison>& points, bool with_fit) {
    nlohmann::json out = nlohmann::json::array();
    for (const PointComparison& p : points) {
        nlohmann::json j{{"load_N", p.point.load_n},
                         {"slip", p.point.slip},
                         {"slip_angle_deg", p.point.slip_angle_deg},
                         {"line", p.point.line}};
        if (p.predicted) {
            j["entry_angle_deg"] = p.entry_angle_deg;
        } else {
            j["failure"] = p.failure;
        }
        if (with_fit) j["in_fit"] = p.in_fit;
        for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
            if (!p.point.measured[c]) continue;
            j[nameOf(c)] = {
                {"measured", *p.point.measured[c]},
                {"predicted", p.predicted ? nlohmann::json(p.values[c]) : nlohmann::json()}};
        }
        out.push_back(std::move(j));
    }
    return out;
}

Table metricsTable(const ValidationMetrics& metrics) {
    Table t;
    std::vector<double> row;
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (!metrics[c]) continue;
        const std::string n = nameOf(c);
        t.columns.insert(t.columns.end(),
                         {n + "_rmse", n + "_mae", n + "_max_rel_error", n + "_count"});
        row.insert(row.end(), {metrics[c]->rmse, metrics[c]->mae, metrics[c]->max_rel_error,
                               static_cast<double>(metrics[c]->count)});
    }
    t.rows.push_back(std::move(row));
    return t;
}

Table pointsTable(const std::vector<PointComparison>& points, bool with_fit) {
    Table t;
    t.columns = {"load_N", "slip", "slip_angle_deg", "entry_angle_deg"};
    std::array<bool, kExperimentChannelCount> measured{};
    for (const PointComparison& p : points) {
        for (std::size_t c = 0; c < kExperimentChannelCount; ++c)
            measured[c] = measured[c] || p.point.measured[c].has_value();
    }
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (!measured[c]) continue;
        t.columns.push_back(std::string(nameOf(c)) + "_measured");
        t.columns.push_back(std::string(nameOf(c)) + "_predicted");
    }
    if (with_fit) t.columns.emplace_back("in_fit");
    for (const PointComparison& p : points) {
        std::vector<double> row{p.point.load_n, p.point.slip, p.point.slip_angle_deg,
                                p.predicted ? p.entry_angle_deg : kNaN};
        for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
            if (!measured[c]) continue;
            row.push_back(p.point.measured[c].value_or(kNaN));
            row.push_back(p.predicted ? p.values[c] : kNaN);
        }
        if (with_fit) row.push_back(p.in_fit ? 1.0 : 0.0);
        t.rows.push_back(std::move(row));
    }
    return t;
}

// The identification's data set of the points in the fit: θ_f solved from each point's load,
// the channels that every fitted point measures (the sinkage may be missing at some).
id::DataSet fitData(const std::vector<PointComparison>& points, std::vector<std::string>& channels,
                    std::vector<std::string>& notes) {
    std::array<std::size_t, kExperimentChannelCount> count{};
    std::size_t fitted = 0;
    for (const PointComparison& p : points) {
        if (!p.in_fit) continue;
        ++fitted;
        for (std::size_t c = 0; c < kExperimentChannelCount; ++c)
            count[c] += p.point.measured[c] ? 1 : 0;
    }
    std::array<bool, kExperimentChannelCount> use{};
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (count[c] == 0) continue;
        if (!kFitChannel[c]) {
            notes.push_back(std::string("calibration: ") + nameOf(c) +
                            " is not fitted (the identification from the load fits Fx_N, My_Nm "
                            "and sinkage_m)");
            continue;
        }
        if (c != io::kExpSinkage && count[c] < fitted) {
            notes.push_back(std::string("calibration: ") + nameOf(c) + " is measured at " +
                            std::to_string(count[c]) + " of the " + std::to_string(fitted) +
                            " fitted points only: not fitted (the identification needs it at "
                            "every point)");
            continue;
        }
        use[c] = true;
        channels.emplace_back(nameOf(c));
    }
    id::DataSet data;
    data.columns = {
        .entry_angle = false, .fx = use[io::kExpFx], .fz = false, .my = use[io::kExpMy]};
    for (const PointComparison& p : points) {
        if (!p.in_fit) continue;
        id::Sample s;
        s.slip = p.point.slip;
        s.slip_angle_rad = units::degToRad(p.point.slip_angle_deg);
        s.load_n = p.point.load_n;
        s.fx_n = p.point.measured[io::kExpFx].value_or(0.0);
        s.my_nm = p.point.measured[io::kExpMy].value_or(0.0);
        if (use[io::kExpSinkage]) s.sinkage_m = p.point.measured[io::kExpSinkage];
        data.samples.push_back(s);
    }
    return data;
}

// A setting of the identification's model held fixed in each fit and found by its profile: n₁ of
// N = n + n₁ s, or S of the slip sinkage h = h₀ (1 + S s).
struct ProfiledSetting {
    const char* name;  // in messages: "n1", "S"
    double id::IdentifyOptions::*member;
    double low, high, step;  // the coarse grid
    double h;                // the step of the curvature's central differences
    double floor;            // the lowest value the model takes (the field's range)
};

struct ProfileResult {
    std::optional<double> value, std;
    std::vector<std::pair<double, double>> profile;
};

// The setting by its profile: χ²(x) is the identification's minimum with x held (its priors
// included), over a coarse grid, then golden-section search in the best grid cell; the std from
// the curvature of χ² at the minimum (Δχ² = 1). The noise levels are held at the x = 0 fit's
// where they would be estimated, so that the χ² of different x compare.
ProfileResult profileSetting(const id::DataSet& data, const wheel::WheelParameters& wheel,
                             id::IdentifyOptions options, const ProfiledSetting& setting,
                             Calibration& cal) {
    ProfileResult out;
    options.*setting.member = 0.0;
    const id::IdentificationReport first = id::identify(data, wheel, options);
    // A channel interpolated with its noise estimated: the levels the profile would hold are
    // meaningless (the calibration is refused with this report's flags).
    if (!first.usable() ||
        std::any_of(first.interpolated.begin(), first.interpolated.end(), std::identity{})) {
        cal.report = first;
        return out;
    }
    options.noise = first.noise;
    // The profile's fits start where the x = 0 fit ended (and from the given soil): x moves the
    // minimum continuously, so the space-filling design is not needed again.
    options.starts.push_back({std::string("the ") + setting.name + " = 0 fit", first.parameters});
    options.design_points = 0;
    options.descents = 2;
    auto chi2 = [&](double x) {
        id::IdentifyOptions o = options;
        o.*setting.member = x;
        id::IdentificationReport r = id::identify(data, wheel, o);
        const double value = r.usable() ? r.chi2 : std::numeric_limits<double>::infinity();
        out.profile.emplace_back(x, value);
        return std::pair{value, std::move(r)};
    };
    const double low = setting.low, high = setting.high, step = setting.step;
    const int cells = static_cast<int>(std::lround((high - low) / step));
    double best_x = 0.0, best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= cells; ++k) {
        const double x = low + step * k;
        const double value = chi2(x).first;
        if (value < best) {
            best = value;
            best_x = x;
        }
    }
    if (!std::isfinite(best)) {
        cal.report = first;
        cal.report.status = id::IdentifyStatus::kFailed;
        cal.report.message = std::string("no ") + setting.name + " in [" + formatNumber(low) +
                             ", " + formatNumber(high) + "] gave a usable fit";
        return out;
    }
    // Golden section on [best − step, best + step] within [low, high]: 14 steps shrink it 850×.
    double a = std::max(low, best_x - step), b = std::min(high, best_x + step);
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double x1 = b - g * (b - a), x2 = a + g * (b - a);
    double f1 = chi2(x1).first, f2 = chi2(x2).first;
    for (int i = 0; i < 14; ++i) {
        if (f1 < f2) {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = chi2(x1).first;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = chi2(x2).first;
        }
    }
    const double x = f1 < f2 ? x1 : x2;
    auto [value, report] = chi2(x);
    out.value = x;
    cal.report = std::move(report);
    // Curvature by central differences (one-sided steps stay inside the setting's range: S ≥ 0).
    const double h = setting.h;
    const double centre = std::max(x, setting.floor + h);
    const double mid = centre == x ? value : chi2(centre).first;
    const double up = chi2(centre + h).first, down = chi2(centre - h).first;
    const double curvature = (up - 2.0 * mid + down) / (h * h);
    if (std::isfinite(curvature) && curvature > 0.0) out.std = std::sqrt(2.0 / curvature);
    return out;
}

// n₁ in [−0.6, 0.8], step 0.2, then refined: N = n + n₁ s stays inside n's range [0.1, 2] over
// the slips of a test for the usual n ≈ 0.5–1.2.
constexpr ProfiledSetting kN1Profile{
    "n1", &id::IdentifyOptions::sinkage_exponent_slip, -0.6, 0.8, 0.2, 0.02, -1.0};
// S in [0, 10] (the field's range), step 1: the tests' sinkage grows 2–4× from s = 0 to 0.6.
constexpr ProfiledSetting kSlipSinkageProfile{
    "S", &id::IdentifyOptions::slip_sinkage_coefficient, 0.0, 10.0, 1.0, 0.05, 0.0};

}  // namespace

std::vector<Issue> validationRuleIssues(const ValidationSettings& s) {
    std::vector<Issue> issues;
    const char* const calibration = "belongs to the calibration: add \"calibrate\": true";
    if (!s.fit_slips.empty() && !s.calibrate) issues.push_back({"fit_slips", calibration});
    if (s.fit_n1 && !s.calibrate) issues.push_back({"fit_n1", calibration});
    if (s.fit_slip_sinkage && !s.calibrate) issues.push_back({"fit_slip_sinkage", calibration});
    if (s.fit_slip_sinkage && s.fit_n1) {
        issues.push_back({"fit_slip_sinkage",
                          "fit one slip-sinkage model at a time: fit_n1 or fit_slip_sinkage, "
                          "not both"});
    }
    return issues;
}

std::vector<Issue> fitSlipIssues(const std::vector<double>& fit_slips,
                                 const io::Experiment& experiment) {
    std::vector<Issue> issues;
    for (std::size_t i = 0; i < fit_slips.size(); ++i) {
        const double slip = fit_slips[i];
        if (std::none_of(experiment.points.begin(), experiment.points.end(),
                         [slip](const io::ExperimentPoint& p) {
                             return std::abs(p.slip - slip) <= kSlipMatch;
                         })) {
            issues.push_back({"fit_slips[" + std::to_string(i) + "]",
                              formatNumber(slip) + " is not a slip of the test"});
        }
    }
    return issues;
}

void readValidationSettings(io::ObjectReader& r, const ReadContext& context,
                            ValidationSettings& out) {
    // Required: a key the field list cannot mark (its reader's "missing" wording).
    r.value("experiments", io::Presence::kRequired, "a string");
    io::readFields(r, out, context.base_dir);
    if (!out.data && !out.experiments.empty() && r.has("experiments")) {
        Result<io::Experiment> read = io::readExperiment(out.experiments);
        if (!read) {
            for (const Issue& issue : read.issues())
                r.report("experiments", issue.where + ": " + issue.message);
        } else {
            out.data = read.value();
        }
    }
    if (out.data) {
        for (const Issue& issue : fitSlipIssues(out.fit_slips, *out.data))
            r.report(issue.where, issue.message);
    }
    for (const Issue& issue : validationRuleIssues(out)) r.report(issue.where, issue.message);
}

nlohmann::json toJson(const ValidationSettings& settings) { return io::fieldsToJson(settings); }

ValidationMetrics computeMetrics(const std::vector<PointComparison>& points,
                                 std::optional<bool> in_fit) {
    ValidationMetrics out;
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        ChannelMetrics m;
        double squares = 0.0, absolutes = 0.0;
        for (const PointComparison& p : points) {
            if (in_fit && p.in_fit != *in_fit) continue;
            if (!p.predicted || !p.point.measured[c]) continue;
            const double measured = *p.point.measured[c];
            const double error = p.values[c] - measured;
            ++m.count;
            squares += error * error;
            absolutes += std::abs(error);
            if (measured != 0.0) {
                const double rel = std::abs(error) / std::abs(measured);
                m.max_rel_error =
                    std::isnan(m.max_rel_error) ? rel : std::max(m.max_rel_error, rel);
            }
        }
        if (m.count == 0) continue;
        m.rmse = std::sqrt(squares / static_cast<double>(m.count));
        m.mae = absolutes / static_cast<double>(m.count);
        out[c] = m;
    }
    return out;
}

namespace {

// The prediction at one point: F_x, M_y, sinkage, F_s, F_z, or a failure.
struct Prediction {
    std::array<double, kExperimentChannelCount> values{};
    double entry_angle_deg = kNaN;
    std::string failure;
};

Prediction predict(const contact::ContactParameters<double>& p, contact::ContactModel model,
                   double slip, double slip_angle_deg, double load_n) {
    Prediction out;
    PointSpec spec;
    spec.slip = slip;
    spec.slip_angle_deg = slip_angle_deg;
    spec.load_n = load_n;
    spec.contact_model = model;
    try {
        const PointResult r = evaluatePoint(p, spec);
        if (r.failure.empty()) {
            out.entry_angle_deg = r.entry_angle_deg;
            out.values = {r.forces.fx, r.forces.my, r.sinkage_m, r.forces.fs, r.forces.fz};
        } else {
            out.failure = r.failure;
        }
    } catch (const std::invalid_argument& e) {
        out.failure = e.what();
    }
    return out;
}

Table modelCurves(const contact::ContactParameters<double>& p, contact::ContactModel model,
                  const io::Experiment& experiment) {
    Table t;
    t.columns = {"load_N", "slip_angle_deg", "slip"};
    for (const io::ExperimentColumn& c : io::experimentChannels()) t.columns.emplace_back(c.name);
    // The test's (load, slip angle) groups in the order they first appear, with their slips.
    struct Group {
        double load_n, slip_angle_deg, low, high;
    };
    std::vector<Group> groups;
    for (const io::ExperimentPoint& point : experiment.points) {
        auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
            return g.load_n == point.load_n && g.slip_angle_deg == point.slip_angle_deg;
        });
        if (it == groups.end()) {
            groups.push_back(
                {point.load_n, point.slip_angle_deg, std::min(0.0, point.slip), point.slip});
        } else {
            it->low = std::min(it->low, point.slip);
            it->high = std::max(it->high, point.slip);
        }
    }
    for (Group& g : groups) {
        g.high = std::min(1.0, std::max(g.high, g.low + 0.05));
        for (int k = 0; k < kValidationCurveSlips; ++k) {
            const double slip = g.low + (g.high - g.low) * k / (kValidationCurveSlips - 1);
            const Prediction r = predict(p, model, slip, g.slip_angle_deg, g.load_n);
            std::vector<double> row{g.load_n, g.slip_angle_deg, slip};
            for (const double v : r.values) row.push_back(r.failure.empty() ? v : kNaN);
            t.rows.push_back(std::move(row));
        }
    }
    return t;
}

}  // namespace

ValidationRun predictExperiment(const Inputs& in, const io::Experiment& experiment, bool curves) {
    ValidationRun out;
    out.soil = in.soil;
    const contact::ContactParameters<double> p = in.contact();
    for (const io::ExperimentPoint& point : experiment.points) {
        PointComparison c;
        c.point = point;
        const Prediction r =
            predict(p, in.conditions.model(), point.slip, point.slip_angle_deg, point.load_n);
        c.predicted = r.failure.empty();
        c.failure = r.failure;
        if (c.predicted) {
            c.entry_angle_deg = r.entry_angle_deg;
            c.values = r.values;
        }
        out.points.push_back(std::move(c));
    }
    out.metrics = computeMetrics(out.points);
    if (curves) out.curves = modelCurves(p, in.conditions.model(), experiment);
    return out;
}

soil::SoilParameters soilFromParameters(const soil::SoilParameters& prior,
                                        const wheel::WheelParameters& wheel,
                                        const id::ParameterVector& p, double n1,
                                        double slip_sinkage) {
    soil::SoilParameters out = prior;
    const double ks_prior = prior.cohesive_modulus / wheel.width_m + prior.frictional_modulus;
    if (!(ks_prior > 0.0)) {
        throw std::invalid_argument("soilFromParameters: K_s of the prior soil on this wheel is " +
                                    formatNumber(ks_prior) + ", must be > 0");
    }
    const double scale = p[id::kKs] / ks_prior;
    out.cohesive_modulus = prior.cohesive_modulus * scale;
    out.frictional_modulus = prior.frictional_modulus * scale;
    out.max_stress_a0 = p[id::kA0];
    out.max_stress_a1 = p[id::kA1];
    out.sinkage_exponent = p[id::kN];
    out.sinkage_exponent_slip = n1;
    out.slip_sinkage_coefficient = slip_sinkage;
    out.cohesion_pa = p[id::kC];
    out.friction_angle_rad = p[id::kPhi];
    out.shear_modulus_m = p[id::kK];
    return out;
}

ValidationResult computeValidation(const Inputs& in, const ValidationSettings& s,
                                   const Control& control) {
    // The reader's checks, in its words, for settings built in code (a panel's, a dialog's).
    std::vector<Issue> issues = validate(in);
    for (Issue& issue : io::fieldIssues(s)) issues.push_back(std::move(issue));
    for (Issue& issue : validationRuleIssues(s)) issues.push_back(std::move(issue));
    if (!s.data && s.experiments.empty()) issues.push_back({"experiments", "no test given"});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    io::Experiment experiment;
    if (s.data) {
        experiment = *s.data;
    } else {
        // A test named but not read (code's settings): one that cannot be read is the input's
        // problem, not the code's.
        Result<io::Experiment> read = io::readExperiment(s.experiments);
        if (!read) {
            ValidationResult out;
            out.status = Outcome::Status::kInvalidInput;
            out.source = s.experiments;
            out.soil = in.soil.name;
            out.wheel = in.wheel.name;
            out.issues = read.issues();
            out.message = read.message();
            return out;
        }
        experiment = read.value();
    }
    if (const std::vector<Issue> slips = fitSlipIssues(s.fit_slips, experiment); !slips.empty())
        throw std::invalid_argument(formatIssues(slips));

    ValidationResult out;
    out.source = experiment.source;
    out.soil = in.soil.name;
    out.wheel = in.wheel.name;
    if (experiment.metadata && experiment.metadata->wheel) {
        const wheel::WheelParameters& w = *experiment.metadata->wheel;
        if (w.radius_m != in.wheel.radius_m || w.width_m != in.wheel.width_m) {
            out.notes.push_back("the wheel (r = " + formatNumber(in.wheel.radius_m) +
                                " m, b = " + formatNumber(in.wheel.width_m) +
                                " m) is not the test's (r = " + formatNumber(w.radius_m) +
                                " m, b = " + formatNumber(w.width_m) + " m)");
        }
    }
    if (in.wheel.lugged() && in.wheel.lugShearOffset() > 0.0) {
        out.notes.push_back(
            "lug model: the soil shears at r_s = r + lug_effect_coefficient * "
            "grouser_height_m = " +
            formatNumber(in.wheel.radius_m + in.wheel.lugShearOffset()) +
            " m, and the slip is taken on r_s (docs/model.md, \"Lugs\")");
    } else if (in.wheel.lugged()) {
        out.notes.push_back(
            "the wheel has grousers; the thesis model treats it as smooth (give "
            "lug_effect_coefficient in the wheel file for the lug model, docs/model.md, \"Lugs\")");
    }
    out.before = predictExperiment(in, experiment, s.curves);
    for (PointComparison& p : out.before.points) p.in_fit = inFitSlips(p.point.slip, s.fit_slips);
    for (const PointComparison& p : out.before.points) {
        if (!p.predicted) {
            out.notes.push_back(out.source + ":" + std::to_string(p.point.line) +
                                ": no prediction: " + p.failure);
        }
    }
    if (control.cancelled()) {
        out.status = Outcome::Status::kCancelled;
        out.message = "cancelled: the given soil's predictions only";
        return out;
    }
    if (!s.calibrate) {
        if (const std::string failure = validationFailure(out); !failure.empty()) {
            out.status = Outcome::Status::kFailed;
            out.message = failure;
        }
        return out;
    }

    Calibration cal;
    cal.prior = id::fromSoil(in.soil, in.wheel);
    const id::DataSet data = fitData(out.before.points, cal.channels, out.notes);
    if (in.soil.sinkage_exponent_slip != 0.0 && !s.fit_n1) {
        out.notes.push_back(
            "calibration: n1 is not fitted (add fit_n1): the calibrated soil's n1 is 0");
    }
    if (in.soil.slip_sinkage_coefficient != 0.0 && !s.fit_slip_sinkage) {
        out.notes.push_back(
            "calibration: the slip-sinkage coefficient S is not fitted (add fit_slip_sinkage): "
            "the calibrated soil's S is 0");
    }
    id::IdentifyOptions options;
    options.source = id::DataSource::kLoad;
    options.max_shear_deformation_m = in.soil.max_shear_deformation_m;
    options.priors = id::priorsFromSoil(in.soil, in.wheel);
    options.starts = {{"given soil (" + in.soil.name + ")", cal.prior}};
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (kFitChannel[c]) options.noise[*kFitChannel[c]] = s.noise[c];
    }
    if (control.cancel != nullptr || control.progress) {
        options.progress = [&control](double f) {
            control.report(f);
            return !control.cancelled();
        };
    }
    if (cal.channels.empty()) {
        cal.report.status = id::IdentifyStatus::kInvalidInput;
        cal.report.message = "no channel to fit (Fx_N, My_Nm or sinkage_m)";
    } else if (s.fit_n1) {
        ProfileResult n1 = profileSetting(data, in.wheel, options, kN1Profile, cal);
        cal.n1 = n1.value;
        cal.n1_std = n1.std;
        cal.n1_profile = std::move(n1.profile);
    } else if (s.fit_slip_sinkage) {
        ProfileResult slip = profileSetting(data, in.wheel, options, kSlipSinkageProfile, cal);
        cal.slip_sinkage = slip.value;
        cal.slip_sinkage_std = slip.std;
        cal.slip_sinkage_profile = std::move(slip.profile);
    } else {
        cal.report = id::identify(data, in.wheel, options);
    }
    if (cal.report.status == id::IdentifyStatus::kNotConverged) {
        // The solver stopped on its iteration budget: its point is no minimum, and the soil made
        // of it would be printed and saved as calibrated, its metrics looking like a result.
        cal.report.status = id::IdentifyStatus::kFailed;
        cal.report.message = "the fit did not converge (" + cal.report.termination +
                             "); its soil is not a calibration (give noise levels, more points "
                             "or points at several loads)";
    }
    if (cal.report.usable()) {
        // A channel that the fit can pass through with its noise estimated: the estimate
        // collapses onto those points, and the calibrated soil would look exact there.
        std::string interpolated;
        for (int c = 0; c < id::kChannelCount; ++c) {
            const auto k = static_cast<std::size_t>(c);
            if (!cal.report.interpolated[k]) continue;
            interpolated += (interpolated.empty() ? "" : "; ") +
                            std::string(id::channelNames()[k]) + " has " +
                            std::to_string(cal.report.channel_values[k]) + " measured values for " +
                            std::to_string(cal.report.free_parameters) +
                            " free parameters and its noise is estimated: the fit passes "
                            "through every one (RMS residual " +
                            formatNumber(roundSignificant(cal.report.rms[k], 3)) + ")";
        }
        if (!interpolated.empty()) {
            cal.report.status = id::IdentifyStatus::kFailed;
            cal.report.message = "the fit interpolates: " + interpolated +
                                 ", so the estimated noise has collapsed and the calibration "
                                 "says nothing; give the channel's noise level or fit more points";
        }
    }
    if (cal.report.usable()) {
        cal.soil = soilFromParameters(in.soil, in.wheel, cal.report.parameters,
                                      cal.n1.value_or(0.0), cal.slip_sinkage.value_or(0.0));
        if (const std::vector<Issue> bad = soil::validate(cal.soil); !bad.empty()) {
            cal.report.status = id::IdentifyStatus::kFailed;
            cal.report.message = "the calibrated soil is not a valid soil: " + formatIssues(bad);
        }
    }
    if (cal.report.usable()) {
        cal.soil.name = in.soil.name + " (calibrated)";
        cal.soil.source = "calibrated by terrastudio validate to " + experiment.source + " with " +
                          in.soil.name + " as prior";
        Inputs calibrated = in;
        calibrated.soil = cal.soil;
        cal.after = predictExperiment(calibrated, experiment, s.curves);
        for (PointComparison& p : cal.after->points)
            p.in_fit = inFitSlips(p.point.slip, s.fit_slips);
        if (cal.report.residuals <= cal.report.free_parameters) {
            out.notes.push_back(
                "calibration: " + std::to_string(cal.report.residuals) + " measured values for " +
                std::to_string(cal.report.free_parameters) +
                " free parameters: the fit can pass through every point, so the metrics of the "
                "fitted points say little about the model; hold some out (fit_slips)");
        }
        if (!s.fit_slips.empty() &&
            std::any_of(cal.after->points.begin(), cal.after->points.end(),
                        [](const PointComparison& p) { return !p.in_fit; })) {
            cal.held_out_before = computeMetrics(out.before.points, false);
            cal.held_out = computeMetrics(cal.after->points, false);
        }
    }
    if (control.cancelled() || cal.report.status == id::IdentifyStatus::kCancelled) {
        // A calibration stopped halfway is no calibration: the given soil's predictions only.
        out.status = Outcome::Status::kCancelled;
        out.message = "cancelled: the calibration was stopped; the given soil's predictions only";
        return out;
    }
    out.calibration = std::move(cal);
    if (const std::string failure = validationFailure(out); !failure.empty()) {
        out.status = Outcome::Status::kFailed;
        out.message = failure;
    }
    return out;
}

nlohmann::json toJson(const ValidationResult& r) {
    const bool with_fit = r.calibration.has_value();
    nlohmann::json out{{"experiments", r.source},
                       {"soil", r.before.soil.name},
                       {"points", pointsJson(r.before.points, false)},
                       {"metrics", metricsJson(r.before.metrics)}};
    if (!r.notes.empty()) out["notes"] = r.notes;
    if (!with_fit) return out;
    const Calibration& c = *r.calibration;
    const id::IdentificationReport& rep = c.report;
    nlohmann::json cal{{"usable", rep.usable()}, {"channels", c.channels}};
    if (!rep.message.empty()) cal["message"] = rep.message;
    if (!rep.issues.empty()) cal["issues"] = formatIssues(rep.issues);
    if (rep.usable()) {
        nlohmann::json params = nlohmann::json::object();
        // j_max is held at the soil's (never calibrated): the seven parameters.
        for (int k = 0; k < id::kJmax; ++k) {
            const id::ParameterInfo& info = id::parameterInfo()[static_cast<std::size_t>(k)];
            const auto i = static_cast<std::size_t>(k);
            // The keys this output has always had ("Ks", "n"; scripts read them).
            params[id::oldKeyOf(id::fieldOf(static_cast<id::FullParameter>(k)))] = {
                {"value", rep.parameters[i] * info.to_user},
                {"std", rep.uncertainty.computed
                            ? nlohmann::json(rep.uncertainty.std[i] * info.to_user)
                            : nlohmann::json()},
                {"prior", c.prior[i] * info.to_user},
                {"at_bound", rep.at_bound[i]}};
        }
        if (c.n1) {
            params["n1"] = {{"value", *c.n1},
                            {"std", c.n1_std ? nlohmann::json(*c.n1_std) : nlohmann::json()},
                            {"prior", 0.0},
                            {"at_bound", false}};
            nlohmann::json profile = nlohmann::json::array();
            for (const auto& [n1, chi2] : c.n1_profile) {
                profile.push_back(
                    {{"n1", n1},
                     {"chi2", std::isfinite(chi2) ? nlohmann::json(chi2) : nlohmann::json()}});
            }
            cal["n1_profile"] = profile;
        }
        if (c.slip_sinkage) {
            params["slip_sinkage"] = {
                {"value", *c.slip_sinkage},
                {"std",
                 c.slip_sinkage_std ? nlohmann::json(*c.slip_sinkage_std) : nlohmann::json()},
                {"prior", 0.0},
                {"at_bound", *c.slip_sinkage <= kSlipSinkageProfile.low ||
                                 *c.slip_sinkage >= kSlipSinkageProfile.high}};
            nlohmann::json profile = nlohmann::json::array();
            for (const auto& [value, chi2] : c.slip_sinkage_profile) {
                profile.push_back(
                    {{"slip_sinkage", value},
                     {"chi2", std::isfinite(chi2) ? nlohmann::json(chi2) : nlohmann::json()}});
            }
            cal["slip_sinkage_profile"] = profile;
        }
        cal["parameters"] = params;
        cal["termination"] = rep.termination;
        cal["chi2"] = rep.chi2;
        cal["noise_estimated"] = rep.noise_estimated;
        nlohmann::json noise = nlohmann::json::object();
        for (int ch = 0; ch < id::kChannelCount; ++ch) {
            if (rep.setup.channels[static_cast<std::size_t>(ch)])
                noise[id::channelNames()[static_cast<std::size_t>(ch)]] =
                    rep.noise[static_cast<std::size_t>(ch)];
        }
        cal["noise"] = noise;
        if (!rep.uncertainty.flags.empty())
            cal["flags"] = id::worded(rep.uncertainty.flags, id::ParameterNaming::kKey);
        cal["soil"] = io::toJson(c.soil);
        cal["points"] = pointsJson(c.after->points, true);
        cal["metrics"] = metricsJson(c.after->metrics);
        if (c.held_out) {
            cal["held_out"] = {{"metrics_before", metricsJson(*c.held_out_before)},
                               {"metrics", metricsJson(*c.held_out)}};
        }
    }
    out["calibration"] = cal;
    return out;
}

std::string validationFailure(const ValidationResult& result) {
    auto firstFailure = [](const ValidationRun& run) {
        for (const PointComparison& p : run.points) {
            if (!p.predicted) return p.failure;
        }
        return std::string();
    };
    auto nonePredicted = [](const ValidationRun& run) {
        return std::none_of(run.points.begin(), run.points.end(),
                            [](const PointComparison& p) { return p.predicted; });
    };
    if (result.calibration) {
        const Calibration& c = *result.calibration;
        if (!c.report.usable()) {
            return "calibration failed: " +
                   (c.report.message.empty() ? formatIssues(c.report.issues) : c.report.message);
        }
        if (c.after && nonePredicted(*c.after)) {
            return "the calibrated soil predicts none of the test's points (" +
                   firstFailure(*c.after) + ")";
        }
        return {};
    }
    if (nonePredicted(result.before)) {
        return "no point of the test has a prediction with the given soil, so there is nothing "
               "to compare (" +
               firstFailure(result.before) + ")";
    }
    return {};
}

namespace {

using Row = SummaryRow;
using Emphasis = SummaryRow::Emphasis;

// A channel for a person: "Fx", "My", "sinkage" (the column name without its unit); the sinkage
// shown in mm.
std::string channelLabel(std::size_t c) {
    const std::string name = nameOf(c);
    return c == io::kExpSinkage ? "sinkage" : name.substr(0, name.find('_'));
}
double channelScale(std::size_t c) { return c == io::kExpSinkage ? 1e3 : 1.0; }
std::string channelUnit(std::size_t c) {
    return c == io::kExpSinkage ? "mm" : io::experimentChannels()[c].unit;
}

// The three numbers of a channel's metrics as cells (RMSE, MAE, largest relative error), each
// formatted once, here: the summary's metric rows and the metrics table show these texts.
// `pointer` is the metrics' object in toJson.
std::array<Row, 3> metricCells(const ChannelMetrics& m, std::size_t c, const std::string& pointer) {
    const double k = channelScale(c);
    const std::string unit = channelUnit(c), at = pointer + "/" + nameOf(c);
    const bool relative = !std::isnan(m.max_rel_error);
    return {
        {{"RMSE", formatFixed(m.rmse * k, 3), unit, "", Emphasis::kNormal, at + "/rmse", m.rmse},
         {"MAE", formatFixed(m.mae * k, 3), unit, "", Emphasis::kNormal, at + "/mae", m.mae},
         {"max relative error", relative ? formatFixed(100.0 * m.max_rel_error, 1) : "-",
          relative ? "%" : "", "", Emphasis::kNormal, relative ? at + "/max_rel_error" : "",
          m.max_rel_error}}};
}

// The rows of one set of metrics, under its heading; `pointer` is its object in toJson. One row
// per channel: its RMSE, the MAE, the largest relative error and the count said after it.
void addMetricRows(Summary& out, const ValidationMetrics& metrics, const std::string& title,
                   const std::string& pointer) {
    out.push_back({title, "", "", "", Emphasis::kHeading, pointer});
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (!metrics[c]) continue;
        const ChannelMetrics& m = *metrics[c];
        std::array<Row, 3> cells = metricCells(m, c, pointer);
        Row& rmse = cells[0];
        rmse.label = channelLabel(c) + " RMSE";
        rmse.detail = "MAE " + cellText(cells[1]) + ", max relative error " + cellText(cells[2]) +
                      ", " + std::to_string(m.count) + " points";
        out.push_back(std::move(rmse));
    }
}

// "0.7302 ± 0.035": the value to the place of its std (formatAtStd); `digits` significant
// digits without one.
std::string valueWithStd(double value, std::optional<double> std, int digits = 5) {
    if (!std || !(*std > 0.0)) return formatNumber(roundSignificant(value, digits));
    return formatAtStd(value, *std) + " ± " + formatStd(*std);
}

}  // namespace

Summary validationSummary(const ValidationResult& r) {
    Summary out;
    out.push_back({"validation", r.soil + " on " + r.wheel + " against " + r.source, "", "",
                   Emphasis::kHeading, ""});
    if (r.status == Outcome::Status::kInvalidInput) {
        out.push_back({"invalid input", formatIssues(r.issues), "", "", Emphasis::kWarning, ""});
        return out;
    }
    addMetricRows(out, r.before.metrics, "metrics (given soil)", "/metrics");
    if (r.calibration) {
        const Calibration& c = *r.calibration;
        std::string title =
            "calibration (identification from the load, " + r.soil + " as prior; channels";
        for (const std::string& ch : c.channels) title += " " + ch;
        title += ")";
        if (!c.report.usable()) {
            out.push_back({title + ": FAILED", c.report.message, "", "", Emphasis::kWarning,
                           c.report.message.empty() ? "" : "/calibration/message"});
        } else {
            out.push_back({title, identification::solverOutcome(c.report.termination), "", "",
                           Emphasis::kHeading, "/calibration"});
            out.push_back({"chi2", formatNumber(roundSignificant(c.report.chi2, 5)), "", "",
                           Emphasis::kNormal, "/calibration/chi2", c.report.chi2});
            // j_max is held at the soil's (the shear limit is the soil file's): seven parameters.
            for (int k = 0; k < id::kJmax; ++k) {
                const auto i = static_cast<std::size_t>(k);
                const id::ParameterInfo& info = id::parameterInfo()[i];
                const std::string unit = std::string(info.unit) == "-" ? "" : info.unit;
                const double value = c.report.parameters[i] * info.to_user;
                const id::ParameterField& field = id::fieldOf(static_cast<id::FullParameter>(k));
                // Labelled by symbol, as the identification's summary; the JSON keeps the keys of
                // before (oldKeyOf) for the scripts that read them.
                const std::string key = id::oldKeyOf(field);
                out.push_back(
                    {field.symbol,
                     valueWithStd(value,
                                  c.report.uncertainty.computed
                                      ? std::optional(c.report.uncertainty.std[i] * info.to_user)
                                      : std::nullopt),
                     unit,
                     "prior " + formatNumber(roundSignificant(c.prior[i] * info.to_user, 5)) +
                         (c.report.at_bound[i] ? ", ended at its bound" : ""),
                     Emphasis::kNormal, "/calibration/parameters/" + key + "/value", value});
            }
            if (c.n1) {
                out.push_back({id::fieldOf(&id::DecoupledParameters::n1).symbol,
                               valueWithStd(*c.n1, c.n1_std, 4), "",
                               "thesis model: 0; from the profile of chi2 over n1",
                               Emphasis::kNormal, "/calibration/parameters/n1/value", *c.n1});
            }
            if (c.slip_sinkage) {
                out.push_back({soil::findSoilField("slip_sinkage")->symbol,
                               valueWithStd(*c.slip_sinkage, c.slip_sinkage_std, 4), "",
                               "thesis model: 0; Lyasko's S of h = h0 (1 + S s), from the "
                               "profile of chi2 over S",
                               Emphasis::kNormal, "/calibration/parameters/slip_sinkage/value",
                               *c.slip_sinkage});
            }
            // The advice names the parameters by symbol here, by key in the JSON.
            const std::vector<std::string> flags =
                id::worded(c.report.uncertainty.flags, id::ParameterNaming::kSymbol);
            for (std::size_t f = 0; f < flags.size(); ++f) {
                out.push_back({"note", flags[f], "", "", Emphasis::kWarning,
                               "/calibration/flags/" + std::to_string(f)});
            }
            addMetricRows(out, c.after->metrics, "metrics (calibrated soil)",
                          "/calibration/metrics");
            if (c.held_out) {
                addMetricRows(out, *c.held_out_before, "held-out points, given soil",
                              "/calibration/held_out/metrics_before");
                addMetricRows(out, *c.held_out, "held-out points, calibrated soil",
                              "/calibration/held_out/metrics");
            }
        }
    }
    for (std::size_t n = 0; n < r.notes.size(); ++n) {
        out.push_back(
            {"note", r.notes[n], "", "", Emphasis::kWarning, "/notes/" + std::to_string(n)});
    }
    if (r.status == Outcome::Status::kCancelled)
        out.push_back({"cancelled", r.message, "", "", Emphasis::kWarning, ""});
    return out;
}

std::string cellText(const SummaryRow& cell) {
    return cell.unit.empty() ? cell.value : cell.value + " " + cell.unit;
}

MetricsTable validationMetricsTable(const ValidationResult& r) {
    MetricsTable out;
    std::vector<std::pair<const ValidationMetrics*, std::string>> sets{
        {&r.before.metrics, "/metrics"}};
    out.columns.push_back("given soil");
    if (r.calibration && r.calibration->report.usable() && r.calibration->after) {
        const Calibration& c = *r.calibration;
        sets.emplace_back(&c.after->metrics, "/calibration/metrics");
        out.columns.push_back("calibrated");
        if (c.held_out && c.held_out_before) {
            sets.emplace_back(&*c.held_out_before, "/calibration/held_out/metrics_before");
            sets.emplace_back(&*c.held_out, "/calibration/held_out/metrics");
            out.columns.insert(out.columns.end(), {"held out, given soil", "held out, calibrated"});
        }
    }
    // A row per channel the given soil's metrics have, and metric.
    for (std::size_t c = 0; c < kExperimentChannelCount; ++c) {
        if (!r.before.metrics[c]) continue;
        const std::size_t first = out.rows.size();
        for (const char* metric : {"RMSE", "MAE", "max relative error"})
            out.rows.push_back(
                {std::string(io::experimentChannels()[c].symbol) + " " + metric, {}});
        for (const auto& [metrics, pointer] : sets) {
            const std::optional<ChannelMetrics>& m = (*metrics)[c];
            for (std::size_t i = 0; i < 3; ++i) {
                Row cell{out.rows[first + i].label, "", "", "", Emphasis::kNormal, ""};
                if (m) cell = metricCells(*m, c, pointer)[i];
                cell.label = out.rows[first + i].label;
                out.rows[first + i].cells.push_back(std::move(cell));
            }
        }
    }
    return out;
}

Outcome validationOutcome(ValidationResult result) {
    Outcome out;
    out.status = result.status;
    out.message = result.message;
    out.tables.push_back({"metrics", "-metrics", metricsTable(result.before.metrics)});
    out.tables.push_back({"points", "-points", pointsTable(result.before.points, false)});
    out.tables.push_back({"curves", "-curves", result.before.curves});
    out.notes = result.notes;
    for (const Issue& issue : result.issues)
        out.notes.push_back(issue.where + ": " + issue.message);
    if (result.calibration) {
        const Calibration& c = *result.calibration;
        if (c.report.usable()) {
            out.tables.push_back(
                {"calibrated_metrics", "-calibrated-metrics", metricsTable(c.after->metrics)});
            out.tables.push_back(
                {"calibrated_points", "-calibrated-points", pointsTable(c.after->points, true)});
            out.tables.push_back({"calibrated_curves", "-calibrated-curves", c.after->curves});
            if (c.held_out) {
                out.tables.push_back(
                    {"held_out_metrics", "-held-out-metrics", metricsTable(*c.held_out)});
            }
            Table parameters;
            std::vector<double> row;
            for (int k = 0; k < id::kJmax; ++k) {
                const auto i = static_cast<std::size_t>(k);
                const id::ParameterInfo& info = id::parameterInfo()[i];
                const std::string key =
                    id::oldKeyOf(id::fieldOf(static_cast<id::FullParameter>(k)));
                parameters.columns.insert(parameters.columns.end(),
                                          {key, key + "_std", key + "_prior"});
                row.insert(row.end(), {c.report.parameters[i] * info.to_user,
                                       c.report.uncertainty.computed
                                           ? c.report.uncertainty.std[i] * info.to_user
                                           : kNaN,
                                       c.prior[i] * info.to_user});
            }
            if (c.n1) {
                parameters.columns.insert(parameters.columns.end(), {"n1", "n1_std", "n1_prior"});
                row.insert(row.end(), {*c.n1, c.n1_std.value_or(kNaN), 0.0});
            }
            if (c.slip_sinkage) {
                parameters.columns.insert(
                    parameters.columns.end(),
                    {"slip_sinkage", "slip_sinkage_std", "slip_sinkage_prior"});
                row.insert(row.end(), {*c.slip_sinkage, c.slip_sinkage_std.value_or(kNaN), 0.0});
            }
            parameters.rows.push_back(std::move(row));
            out.tables.push_back({"parameters", "-parameters", std::move(parameters)});
            out.notes.push_back(
                "calibration: " + identification::solverOutcome(c.report.termination) +
                ", χ² = " + formatNumber(roundSignificant(c.report.chi2, 6)));
            for (const id::ParameterText& flag : c.report.uncertainty.flags)
                out.notes.push_back("calibration: " + flag.worded(id::ParameterNaming::kKey));
        }
    }
    out.documents.emplace_back("-validation.json", toJson(result));
    out.result = std::move(result);
    return out;
}

AnalysisType validationType() {
    return makeAnalysisType<ValidationSettings>(
        "validation",
        "the model against a measured single-wheel test (io/experiment.h): per point and channel, "
        "RMSE, MAE, largest relative error; optionally calibrated to the test first",
        {"metrics", "points", "curves", "calibrated_metrics", "calibrated_points",
         "calibrated_curves", "held_out_metrics", "parameters"},
        {{"Fx", "-Fx"}, {"sinkage", "-sinkage"}, {"My", "-My"}, {"Fy", "-Fy"}},
        readValidationSettings,
        [](const Inputs& in, const ValidationSettings& s, const Control& c) {
            return computeValidation(in, s, c);
        },
        validationOutcome);
}

}  // namespace terra::analysis
