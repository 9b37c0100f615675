#include "core/analysis/traction.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/analysis/operating_point.h"
#include "core/analysis/registry.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"
#include "core/io/json.h"
#include "core/io/parameters_json.h"
#include "core/scenario/traction_control.h"
#include "core/soil/soil_parameters.h"

namespace terra::analysis {
namespace {

constexpr double kMinusInfinity = -std::numeric_limits<double>::infinity();

// The posterior's own rules (a field list cannot say them): soil fields, sizes, definiteness.
void addPosteriorIssues(const SoilPosterior& p, std::vector<Issue>& issues) {
    const std::size_t n = p.parameters.size();
    if (n == 0) issues.push_back({"posterior.parameters", "no parameters"});
    for (const std::string& key : p.parameters) {
        if (!soil::findSoilField(key))
            issues.push_back({"posterior.parameters", quoteText(key) + " is not a soil field"});
    }
    if (p.mean.size() != n) {
        issues.push_back({"posterior.mean", std::to_string(p.mean.size()) + " values for " +
                                                std::to_string(n) + " parameters"});
    }
    bool square = p.covariance.size() == n;
    for (const auto& row : p.covariance) square = square && row.size() == n;
    if (!square) {
        issues.push_back(
            {"posterior.covariance", "must be " + std::to_string(n) + " x " + std::to_string(n)});
    } else if (n > 0) {
        Eigen::MatrixXd c(n, n);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j) c(i, j) = p.covariance[i][j];
        const Eigen::LLT<Eigen::MatrixXd> llt(c);
        if (!c.isApprox(c.transpose(), 1e-9) || llt.info() != Eigen::Success) {
            issues.push_back({"posterior.covariance", "is not symmetric positive definite"});
        }
    }
}
double quantileOf(std::vector<double> values, double q) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    const double at = q * static_cast<double>(values.size() - 1);  // Hyndman & Fan type 7
    const auto lo = static_cast<std::size_t>(std::floor(at));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (at - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

// The largest of f on [a, b] around a scan's best point (Brent's method, Boost.Math), never
// below the scan's own value.
template <typename F>
std::pair<double, double> refine(F f, double a, double b, double x_best, double f_best) {
    std::uintmax_t iterations = 60;
    const auto [x, minus] = boost::math::tools::brent_find_minima(
        [&](double s) {
            const double v = f(s);
            return std::isfinite(v) ? -v : std::numeric_limits<double>::max();
        },
        a, b, 30, iterations);
    return -minus > f_best ? std::pair{x, -minus} : std::pair{x_best, f_best};
}

// Standard normal draws from the fully specified mt19937_64 (Box–Muller), so that a seed gives the
// same soils on every platform (std::normal_distribution is implementation-defined).
class NormalDraws {
public:
    explicit NormalDraws(std::uint64_t seed) : engine_(seed) {}
    double next() {
        if (spare_) {
            spare_ = false;
            return stored_;
        }
        const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * 0x1.0p-53;
        const double u2 = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
        const double radius = std::sqrt(-2.0 * std::log(u1));
        stored_ = radius * std::sin(2.0 * std::numbers::pi * u2);
        spare_ = true;
        return radius * std::cos(2.0 * std::numbers::pi * u2);
    }

private:
    std::mt19937_64 engine_;
    bool spare_ = false;
    double stored_ = 0.0;
};

// The posterior's band by the second-order transform along the Cholesky directions
// (docs/traction.md §8, "Cost"): with x = μ + L z, z ~ N(0, I), the objective f is interpolated
// along each direction i by the parabola through z_i = −h_i, 0, h_i (h_i = √3, the
// divided-difference filter's choice for a normal, Nørgaard, Poulsen & Ravn 2000, Automatica
// 36: 1627–1638; shortened where μ ± h_i L e_i would leave a field's range): slope
// g_i = (f₊ − f₋)/(2h_i), curvature c_i = (f₊ + f₋ − 2f₀)/h_i². For f ≈ f₀ + Σ g_i z_i +
// ½ Σ c_i z_i², E f = f₀ + ½ Σ c_i and Var f = Σ g_i² + ½ Σ c_i² (Var z² = 2), and the quantile q
// is taken as a normal's, E f + Φ⁻¹(q) √Var f. 2d + 1 soils instead of `posterior_samples`.
struct SecondOrder {
    double mean = 0.0, variance = 0.0;
};
SecondOrder secondOrder(double f0, const std::vector<double>& plus,
                        const std::vector<double>& minus, const std::vector<double>& step) {
    SecondOrder out{f0, 0.0};
    for (std::size_t i = 0; i < step.size(); ++i) {
        const double g = (plus[i] - minus[i]) / (2.0 * step[i]);
        const double c = (plus[i] + minus[i] - 2.0 * f0) / (step[i] * step[i]);
        out.mean += 0.5 * c;
        out.variance += g * g + 0.5 * c * c;
    }
    return out;
}

// Appends the band at the next slip of the curve, keeping the indices of the largest quantile
// and the largest mean.
void addBand(TractionResult& out, const TractionBand& band, std::size_t& best_q,
             std::size_t& best_mean) {
    const std::size_t j = out.band.size();
    out.band.push_back(band);
    if (band.quantile > out.band[best_q].quantile) best_q = j;
    if (band.mean > out.band[best_mean].mean) best_mean = j;
}

template <typename Objective>
void sigmaPointBand(TractionResult& out, const std::vector<double>& slips,
                    const soil::SoilParameters& nominal, const wheel::WheelParameters& wheel,
                    const contact::ContactParameters<double>& centre, Objective objective,
                    const TractionSettings& s, const Control& control) {
    const SoilPosterior& post = *s.posterior;
    const std::size_t d = post.parameters.size();
    Eigen::MatrixXd covariance(d, d);
    for (std::size_t i = 0; i < d; ++i)
        for (std::size_t j = 0; j < d; ++j) covariance(i, j) = post.covariance[i][j];
    const Eigen::MatrixXd lower = covariance.llt().matrixL();
    std::vector<const soil::SoilField*> fields;
    for (const std::string& key : post.parameters) fields.push_back(soil::findSoilField(key));
    // The soil at μ + h L e_i (nullopt: outside a range or no contact parameters).
    auto soilAt = [&](std::size_t i,
                      double h) -> std::optional<contact::ContactParameters<double>> {
        soil::SoilParameters soil = nominal;
        for (std::size_t k = 0; k < d; ++k) {
            const double value = post.mean[k] + h * lower(static_cast<Eigen::Index>(k),
                                                          static_cast<Eigen::Index>(i));
            if (!fields[k]->range.contains(value)) return std::nullopt;
            soil::setUserValue(soil, *fields[k], value);
        }
        if (!soil::validate(soil).empty()) return std::nullopt;
        try {
            return contact::makeContactParameters(soil, wheel);
        } catch (const std::invalid_argument&) {
            return std::nullopt;
        }
    };
    constexpr double kStep = 1.7320508075688772;  // √3
    std::vector<contact::ContactParameters<double>> plus, minus;
    std::vector<double> step;
    int shortened = 0, dropped = 0;
    for (std::size_t i = 0; i < d; ++i) {
        // The largest h ≤ √3 (halving, 12 times at most) with both points in range.
        double h = kStep;
        std::optional<contact::ContactParameters<double>> a, b;
        for (int k = 0; k < 12; ++k, h *= 0.5) {
            a = soilAt(i, h);
            b = soilAt(i, -h);
            if (a && b) break;
        }
        if (!(a && b)) {
            ++dropped;  // μ on a bound in this direction: it adds nothing
            continue;
        }
        if (h < kStep) ++shortened;
        plus.push_back(*a);
        minus.push_back(*b);
        step.push_back(h);
    }
    if (shortened + dropped > 0) {
        out.notes.push_back(
            std::to_string(shortened + dropped) + " of " + std::to_string(d) +
            " sigma-point directions reach beyond a field's range: " + std::to_string(shortened) +
            " shortened, " + std::to_string(dropped) + " left out");
    }
    const std::size_t m = step.size();
    // The objective at a slip of the centre and every sigma point; false where one has none.
    std::vector<double> f_plus(m), f_minus(m);
    auto evaluate = [&](double slip, double& f0) {
        f0 = objective(centre, slip);
        bool ok = std::isfinite(f0);
        for (std::size_t i = 0; i < m; ++i) {
            f_plus[i] = objective(plus[i], slip);
            f_minus[i] = objective(minus[i], slip);
            ok = ok && std::isfinite(f_plus[i]) && std::isfinite(f_minus[i]);
        }
        return ok;
    };
    const double z = boost::math::quantile(boost::math::normal(), s.quantile);
    const double z5 = boost::math::quantile(boost::math::normal(), 0.05);
    // Each point's own s* on the curve's slips (for the spread of s*).
    double best0 = kMinusInfinity, slip0 = 0.0;
    std::vector<double> best_plus(m, kMinusInfinity), best_minus(m, kMinusInfinity);
    std::vector<double> slip_plus(m, 0.0), slip_minus(m, 0.0);
    std::size_t best_q = 0, best_mean = 0;
    for (std::size_t j = 0; j < slips.size(); ++j) {
        if (control.cancelled()) break;
        double f0 = 0.0;
        const bool ok = evaluate(slips[j], f0);
        if (f0 > best0) best0 = f0, slip0 = slips[j];
        for (std::size_t i = 0; i < m; ++i) {
            if (f_plus[i] > best_plus[i]) best_plus[i] = f_plus[i], slip_plus[i] = slips[j];
            if (f_minus[i] > best_minus[i]) best_minus[i] = f_minus[i], slip_minus[i] = slips[j];
        }
        TractionBand band;
        band.slip = slips[j];
        if (ok) {
            const SecondOrder moments = secondOrder(f0, f_plus, f_minus, step);
            const double sd = std::sqrt(moments.variance);
            band.samples = static_cast<int>(2 * m + 1);
            band.mean = band.p50 = moments.mean;
            band.p5 = moments.mean + z5 * sd;
            band.p95 = moments.mean - z5 * sd;
            band.quantile = moments.mean + z * sd;
        } else {
            band.mean = band.p5 = band.p50 = band.p95 = band.quantile = kMinusInfinity;
        }
        addBand(out, band, best_q, best_mean);
        control.report(0.1 + 0.8 * static_cast<double>(j + 1) / slips.size());
    }
    if (out.band.size() != slips.size()) {
        out.notes.push_back("cancelled: the posterior's band is partial");
        out.cancelled = true;
        return;
    }
    // The spread of s*: the same transform of each point's own s* on the curve's slips.
    bool spread_ok = std::isfinite(best0);
    for (std::size_t i = 0; i < m; ++i)
        spread_ok = spread_ok && std::isfinite(best_plus[i]) && std::isfinite(best_minus[i]);
    if (spread_ok) {
        out.optimal_slip_std =
            std::sqrt(std::max(0.0, secondOrder(slip0, slip_plus, slip_minus, step).variance));
    }
    if (!std::isfinite(out.band[best_q].quantile)) return;
    const auto [robust, q] = refine(
        [&](double slip) {
            double f0 = 0.0;
            if (!evaluate(slip, f0)) return kMinusInfinity;  // a point without equilibrium
            const SecondOrder moments = secondOrder(f0, f_plus, f_minus, step);
            return moments.mean + z * std::sqrt(moments.variance);
        },
        slips[best_q == 0 ? 0 : best_q - 1], slips[std::min(best_q + 1, slips.size() - 1)],
        slips[best_q], out.band[best_q].quantile);
    out.robust_slip = robust;
    out.robust_value = q;
    out.expected_slip = slips[best_mean];
}

}  // namespace

const char* objectiveName(TractionObjective objective) {
    return objective == TractionObjective::kDrawbar ? "drawbar" : "efficiency";
}

void readPosteriorObject(io::ObjectReader& r, const char* key, std::optional<SoilPosterior>& out) {
    const nlohmann::json* posterior = r.value(key);
    if (posterior == nullptr || posterior->is_string()) return;  // a file: readTractionSettings
    if (!posterior->is_object()) {
        r.report(key, "expected an object or a file, got " + io::describeJson(*posterior));
        return;
    }
    SoilPosterior p;
    io::ObjectReader pr = r.object(key);
    readPosterior(pr, p);
    pr.finish();
    out = p;
}

nlohmann::json posteriorJson(const std::optional<SoilPosterior>& p) {
    if (!p) return nullptr;
    return {{"parameters", p->parameters}, {"mean", p->mean}, {"covariance", p->covariance}};
}

std::vector<Issue> tractionRuleIssues(const TractionSettings& s) {
    std::vector<Issue> issues;
    if (!(s.slip_min < s.slip_max)) {
        issues.push_back({"slip_max", formatNumber(s.slip_max) +
                                          " must be above slip_min = " + formatNumber(s.slip_min)});
    }
    if (s.posterior) addPosteriorIssues(*s.posterior, issues);
    return issues;
}

void readTractionSettings(io::ObjectReader& r, TractionSettings& out,
                          const std::filesystem::path& base_dir) {
    io::readFields(r, out);
    // A soil file with its posterior (`identify --save-soil`): only "posterior" is read.
    if (const nlohmann::json* posterior = r.value("posterior");
        posterior != nullptr && posterior->is_string()) {
        std::filesystem::path path = posterior->get<std::string>();
        if (path.is_relative() && !base_dir.empty()) path = base_dir / path;
        Result<SoilPosterior> file = readPosteriorFile(path);
        if (!file) {
            for (const Issue& issue : file.issues()) r.report("posterior", formatIssue(issue));
        } else {
            out.posterior = file.value();
        }
    }
    for (Issue& issue : tractionRuleIssues(out)) r.report(issue.where, std::move(issue.message));
}

nlohmann::json toJson(const TractionSettings& s) { return io::fieldsToJson(s); }

double objectiveValue(TractionObjective objective, const TractionPoint& p) {
    if (!p.ok) return kMinusInfinity;
    return objective == TractionObjective::kDrawbar ? p.fx_n : p.efficiency;
}

TractionPoint tractionPoint(const contact::ContactParameters<double>& params, double load_n,
                            double slip, const TractionSettings& s, contact::ContactModel model,
                            std::string* failure) {
    PointSpec spec;
    spec.slip = slip;
    spec.slip_angle_deg = s.slip_angle_deg;
    spec.load_n = load_n;
    spec.model = s.model;
    spec.contact_model = model;
    const PointResult r = evaluatePoint(params, spec);
    TractionPoint p;
    p.slip = slip;
    if (failure) *failure = r.failure;
    if (!r.failure.empty()) return p;
    p.fx_n = r.forces.fx;
    p.my_nm = r.forces.my;
    p.sinkage_m = r.sinkage_m;
    // η = output power / input power = F_x v / (M_y ω), v = r ω (1 − s) when driving.
    p.efficiency = p.my_nm > 0.0 ? p.fx_n * params.radius_m * (1.0 - slip) / p.my_nm : 0.0;
    p.ok = !s.max_sinkage_m || p.sinkage_m <= *s.max_sinkage_m;
    return p;
}

TractionResult computeTraction(const Inputs& in, const TractionSettings& s,
                               const Control& control) {
    // The reader's checks, in its words, for settings built in code (the planner's, a test's).
    std::vector<Issue> issues = io::fieldIssues(s);
    for (Issue& issue : tractionRuleIssues(s)) issues.push_back(std::move(issue));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    TractionResult out;
    out.objective = s.objective;
    if (s.posterior) out.notes = s.posterior->notes;  // an old parameter key, read as its new one
    // The nominal soil: the given one with the posterior's mean.
    soil::SoilParameters nominal = in.soil;
    if (s.posterior) {
        for (std::size_t k = 0; k < s.posterior->parameters.size(); ++k)
            soil::setUserValue(nominal, *soil::findSoilField(s.posterior->parameters[k]),
                               s.posterior->mean[k]);
        if (std::vector<Issue> issues = soil::validate(nominal, "posterior.mean."); !issues.empty())
            throw std::invalid_argument(formatIssues(issues));
    }
    const contact::ContactParameters<double> params =
        contact::makeContactParameters(nominal, in.wheel);
    const contact::ContactModel model = in.conditions.model();
    const double load = in.conditions.load_n;
    auto at = [&](const contact::ContactParameters<double>& p, double slip) {
        return tractionPoint(p, load, slip, s, model);
    };
    std::vector<double> slips;
    for (int i = 0; i < s.curve_points; ++i)
        slips.push_back(s.slip_min + (s.slip_max - s.slip_min) * i / (s.curve_points - 1));
    for (double slip : slips) {
        if (control.cancelled()) {
            out.cancelled = true;
            out.message = "cancelled";
            return out;
        }
        out.curve.push_back(at(params, slip));
    }
    std::size_t best = 0;
    for (std::size_t i = 1; i < out.curve.size(); ++i)
        if (objectiveValue(s.objective, out.curve[i]) >
            objectiveValue(s.objective, out.curve[best]))
            best = i;
    const double best_value = objectiveValue(s.objective, out.curve[best]);
    if (!std::isfinite(best_value)) {
        out.message =
            s.max_sinkage_m
                ? "no slip in [" + formatNumber(s.slip_min) + ", " + formatNumber(s.slip_max) +
                      "] keeps the sinkage below " + formatNumber(*s.max_sinkage_m) + " m"
                : [&] {
                      // Why, in the sinkage solver's words (how much the soil carries).
                      std::string why;
                      tractionPoint(params, load, slips.front(), s, model, &why);
                      return "no slip has an equilibrium at this load" +
                             (why.empty()
                                  ? std::string()
                                  : " (at s = " + formatNumber(slips.front()) + ": " + why + ")");
                  }();
        return out;
    }
    const double a = slips[best == 0 ? 0 : best - 1];
    const double b = slips[std::min(best + 1, slips.size() - 1)];
    const auto [slip_star, value] =
        refine([&](double slip) { return objectiveValue(s.objective, at(params, slip)); }, a, b,
               slips[best], best_value);
    (void)value;
    out.optimal_slip = slip_star;
    out.at_optimum = at(params, slip_star);
    if (best + 1 == slips.size() || best == 0) {
        out.notes.push_back("s* is at the search's " + std::string(best == 0 ? "lower" : "upper") +
                            " bound (" + formatNumber(slips[best]) + "): the " +
                            objectiveName(s.objective) + " still grows beyond it");
    }
    // The best there is may still not pull (a tight sinkage cap, a soil that barely carries the
    // load): η = F_x r (1 − s)/M_y is then negative, and the plan drives without traction.
    if (!(out.at_optimum.fx_n > 0.0)) {
        out.notes.push_back(
            "at s* the wheel does not pull (F_x = " + formatNumber(out.at_optimum.fx_n) +
            " N): no slip in [" + formatNumber(s.slip_min) + ", " + formatNumber(s.slip_max) + "]" +
            (s.max_sinkage_m ? " within the sinkage cap" : "") + " gives drawbar pull here");
    }
    control.report(s.posterior ? 0.1 : 1.0);

    if (s.posterior && !control.cancelled() &&
        s.posterior_method == scenario::PosteriorMethod::kSigmaPoints) {
        sigmaPointBand(
            out, slips, nominal, in.wheel, params,
            [&](const contact::ContactParameters<double>& p, double slip) {
                return objectiveValue(s.objective, at(p, slip));
            },
            s, control);
    } else if (s.posterior && !control.cancelled()) {
        const SoilPosterior& post = *s.posterior;
        const std::size_t d = post.parameters.size();
        Eigen::MatrixXd covariance(d, d);
        for (std::size_t i = 0; i < d; ++i)
            for (std::size_t j = 0; j < d; ++j) covariance(i, j) = post.covariance[i][j];
        const Eigen::MatrixXd lower = covariance.llt().matrixL();
        const Eigen::Map<const Eigen::VectorXd> mean(post.mean.data(),
                                                     static_cast<Eigen::Index>(d));
        NormalDraws draws(s.seed);
        std::vector<contact::ContactParameters<double>> soils;
        for (int k = 0; k < s.posterior_samples; ++k) {
            Eigen::VectorXd z(d);
            for (std::size_t i = 0; i < d; ++i) z(static_cast<Eigen::Index>(i)) = draws.next();
            const Eigen::VectorXd x = mean + lower * z;
            soil::SoilParameters soil = nominal;
            for (std::size_t i = 0; i < d; ++i)
                soil::setUserValue(soil, *soil::findSoilField(post.parameters[i]),
                                   x(static_cast<Eigen::Index>(i)));
            if (!soil::validate(soil).empty()) {
                ++out.invalid_samples;
                continue;
            }
            try {
                soils.push_back(contact::makeContactParameters(soil, in.wheel));
            } catch (const std::invalid_argument&) {
                ++out.invalid_samples;
            }
        }
        if (out.invalid_samples > 0) {
            out.notes.push_back(std::to_string(out.invalid_samples) + " of " +
                                std::to_string(s.posterior_samples) +
                                " posterior draws fall outside a field's range and are left out");
        }
        // The objective of every drawn soil at a slip (−∞ where it has no equilibrium).
        auto objectivesAt = [&](double slip) {
            std::vector<double> v;
            v.reserve(soils.size());
            for (const auto& p : soils) v.push_back(objectiveValue(s.objective, at(p, slip)));
            return v;
        };
        auto valuesAt = [&](double slip) {
            std::vector<double> v;
            for (double f : objectivesAt(slip))
                if (std::isfinite(f)) v.push_back(f);
            return v;
        };
        // Each drawn soil's own s* on the curve's slips (its largest objective there).
        std::vector<double> best_value(soils.size(), kMinusInfinity);
        std::vector<double> best_slip(soils.size(), 0.0);
        std::size_t best_q = 0, best_mean = 0;
        for (std::size_t i = 0; i < slips.size(); ++i) {
            if (control.cancelled()) break;
            const std::vector<double> all = objectivesAt(slips[i]);
            std::vector<double> v;
            for (std::size_t k = 0; k < all.size(); ++k) {
                if (!std::isfinite(all[k])) continue;
                v.push_back(all[k]);
                if (all[k] > best_value[k]) {
                    best_value[k] = all[k];
                    best_slip[k] = slips[i];
                }
            }
            TractionBand band;
            band.slip = slips[i];
            band.samples = static_cast<int>(v.size());
            if (!v.empty()) {
                double sum = 0.0;
                for (double x : v) sum += x;
                band.mean = sum / static_cast<double>(v.size());
                band.p5 = quantileOf(v, 0.05);
                band.p50 = quantileOf(v, 0.5);
                band.p95 = quantileOf(v, 0.95);
                band.quantile = quantileOf(v, s.quantile);
            } else {
                band.mean = band.p5 = band.p50 = band.p95 = band.quantile = kMinusInfinity;
            }
            addBand(out, band, best_q, best_mean);
            control.report(0.1 + 0.8 * static_cast<double>(i + 1) / slips.size());
        }
        if (out.band.size() == slips.size()) {
            // The spread of s* over the posterior: the standard deviation of the drawn soils' own
            // s* (on the curve's slips: a spacing Δ adds at most Δ²/12 of variance).
            double sum = 0.0, sum_sq = 0.0;
            int count = 0;
            for (std::size_t k = 0; k < soils.size(); ++k) {
                if (!std::isfinite(best_value[k])) continue;
                sum += best_slip[k];
                sum_sq += best_slip[k] * best_slip[k];
                ++count;
            }
            if (count > 1) {
                const double mean = sum / count;
                out.optimal_slip_std =
                    std::sqrt(std::max(0.0, (sum_sq - count * mean * mean) / (count - 1)));
            }
        }
        if (out.band.size() == slips.size() && std::isfinite(out.band[best_q].quantile)) {
            // Robust s*: the largest lower quantile; refined between the neighbouring slips
            // (each evaluation is every posterior soil at that slip).
            const auto [robust, q] = refine(
                [&](double slip) {
                    const std::vector<double> v = valuesAt(slip);
                    // Lose no draw: a slip where some soils have no equilibrium is not robust.
                    if (v.size() < soils.size()) return kMinusInfinity;
                    return quantileOf(v, s.quantile);
                },
                slips[best_q == 0 ? 0 : best_q - 1], slips[std::min(best_q + 1, slips.size() - 1)],
                slips[best_q], out.band[best_q].quantile);
            out.robust_slip = robust;
            out.robust_value = q;
            out.expected_slip = slips[best_mean];
        } else if (control.cancelled()) {
            out.notes.push_back("cancelled: the posterior's band is partial");
            out.cancelled = true;
        }
    }
    control.report(1.0);
    return out;
}

nlohmann::json toJson(const TractionResult& r) {
    using nlohmann::json;
    json out{{"objective", objectiveName(r.objective)}};
    if (r.optimal_slip) {
        out["optimal_slip"] = *r.optimal_slip;
        out["Fx_N"] = r.at_optimum.fx_n;
        out["My_Nm"] = r.at_optimum.my_nm;
        out["efficiency"] = r.at_optimum.efficiency;
        out["sinkage_m"] = r.at_optimum.sinkage_m;
    }
    json curve = json::array();
    for (const TractionPoint& p : r.curve) {
        json row{{"slip", p.slip}, {"ok", p.ok}};
        if (p.ok || p.my_nm != 0.0) {
            row["Fx_N"] = p.fx_n;
            row["My_Nm"] = p.my_nm;
            row["efficiency"] = p.efficiency;
            row["sinkage_m"] = p.sinkage_m;
        }
        curve.push_back(row);
    }
    out["curve"] = curve;
    if (!r.band.empty()) {
        json band = json::array();
        for (const TractionBand& b : r.band) {
            json row{{"slip", b.slip}, {"samples", b.samples}};
            if (b.samples > 0) {
                row["mean"] = b.mean;
                row["p5"] = b.p5;
                row["p50"] = b.p50;
                row["p95"] = b.p95;
                row["quantile"] = b.quantile;
            }
            band.push_back(row);
        }
        out["band"] = band;
        if (r.robust_slip) {
            out["robust_slip"] = *r.robust_slip;
            out["robust_value"] = r.robust_value;
        }
        if (r.expected_slip) out["expected_slip"] = *r.expected_slip;
        if (r.optimal_slip_std) out["optimal_slip_std"] = *r.optimal_slip_std;
        out["invalid_samples"] = r.invalid_samples;
    }
    out["status"] = statusName(r.status());
    if (!r.message.empty()) out["message"] = r.message;
    out["notes"] = r.notes;
    return out;
}

Summary tractionSummary(const Inputs& in, const TractionSettings& s, const TractionResult& r) {
    using Emphasis = SummaryRow::Emphasis;
    Summary out;
    const std::string objective = objectiveName(s.objective);
    out.push_back(
        {"traction",
         in.soil.name + ", " + in.wheel.name + ", W = " + formatNumber(in.conditions.load_n) +
             " N, beta = " + formatNumber(s.slip_angle_deg) + " deg, objective " + objective +
             (s.max_sinkage_m ? ", sinkage <= " + formatNumber(*s.max_sinkage_m) + " m" : ""),
         "", "", Emphasis::kHeading, ""});
    if (!r.ok()) {
        out.push_back({statusName(r.status()), r.message, "", "", Emphasis::kWarning,
                       r.message.empty() ? "" : "/message"});
    } else {
        const TractionPoint& p = r.at_optimum;
        out.push_back({"s*", formatFixed(*r.optimal_slip, 4), "", "", Emphasis::kNormal,
                       "/optimal_slip", *r.optimal_slip});
        out.push_back({"Fx", formatFixed(p.fx_n, 3), "N", "", Emphasis::kNormal, "/Fx_N", p.fx_n});
        out.push_back(
            {"My", formatFixed(p.my_nm, 4), "Nm", "", Emphasis::kNormal, "/My_Nm", p.my_nm});
        out.push_back({"efficiency", formatFixed(p.efficiency, 4), "", "", Emphasis::kNormal,
                       "/efficiency", p.efficiency});
        out.push_back({"sinkage", formatFixed(p.sinkage_m * 1e3, 3), "mm", "", Emphasis::kNormal,
                       "/sinkage_m", p.sinkage_m});
    }
    if (r.robust_slip) {
        const std::string quantile = formatNumber(s.quantile * 100) + " %";
        const bool drawbar = s.objective == TractionObjective::kDrawbar;
        out.push_back({"posterior",
                       s.posterior_method == scenario::PosteriorMethod::kSigmaPoints
                           ? std::string("sigma points")
                           : std::to_string(s.posterior_samples) + " soils",
                       "", "", Emphasis::kHeading, ""});
        out.push_back({"robust s*", formatFixed(*r.robust_slip, 4), "",
                       "maximises the " + quantile + " quantile of the " + objective,
                       Emphasis::kNormal, "/robust_slip", *r.robust_slip});
        out.push_back({quantile + " quantile of the " + objective + " there",
                       formatFixed(r.robust_value, drawbar ? 3 : 4), drawbar ? "N" : "", "",
                       Emphasis::kNormal, "/robust_value", r.robust_value});
        if (r.expected_slip) {
            out.push_back({"largest mean at s", formatFixed(*r.expected_slip, 4), "", "",
                           Emphasis::kNormal, "/expected_slip", *r.expected_slip});
        }
        if (r.optimal_slip_std) {
            out.push_back({"spread of s*", formatFixed(*r.optimal_slip_std, 4), "",
                           "std over the posterior", Emphasis::kNormal, "/optimal_slip_std",
                           *r.optimal_slip_std});
        }
    }
    for (std::size_t n = 0; n < r.notes.size(); ++n) {
        out.push_back(
            {"note", r.notes[n], "", "", Emphasis::kWarning, "/notes/" + std::to_string(n)});
    }
    return out;
}

Outcome tractionOutcome(TractionResult result) {
    Outcome out;
    Table curve{{"slip", "Fx_N", "My_Nm", "efficiency", "sinkage_m", "ok"}, {}};
    const bool band = result.band.size() == result.curve.size() && !result.band.empty();
    if (band) {
        for (const char* c : {"objective_mean", "objective_p5", "objective_p50", "objective_p95",
                              "objective_quantile"})
            curve.columns.emplace_back(c);
    }
    for (std::size_t i = 0; i < result.curve.size(); ++i) {
        const TractionPoint& p = result.curve[i];
        std::vector<double> row{p.slip,       p.fx_n,      p.my_nm,
                                p.efficiency, p.sinkage_m, p.ok ? 1.0 : 0.0};
        if (band) {
            const TractionBand& b = result.band[i];
            // A slip where no posterior soil has an equilibrium has no band: 0 with samples = 0
            // would read as a value, so those rows keep the nominal objective (noted).
            const double fallback = objectiveValue(result.objective, p);
            for (double v : {b.mean, b.p5, b.p50, b.p95, b.quantile})
                row.push_back(std::isfinite(v) ? v : (std::isfinite(fallback) ? fallback : 0.0));
        }
        curve.rows.push_back(std::move(row));
    }
    Table optimum{{"optimal_slip", "Fx_N", "My_Nm", "efficiency", "sinkage_m"}, {}};
    if (result.optimal_slip) {
        optimum.rows.push_back({*result.optimal_slip, result.at_optimum.fx_n,
                                result.at_optimum.my_nm, result.at_optimum.efficiency,
                                result.at_optimum.sinkage_m});
        if (result.robust_slip) {
            optimum.columns.emplace_back("robust_slip");
            optimum.rows.back().push_back(*result.robust_slip);
        }
    }
    out.tables.push_back({"curve", "", std::move(curve)});
    out.tables.push_back({"optimum", "-optimum", std::move(optimum)});
    out.notes = result.notes;
    if (result.cancelled) {
        out.status = Outcome::Status::kCancelled;
        if (!result.ok()) out.message = result.message;
    } else if (!result.ok()) {
        out.status = Outcome::Status::kFailed;
        out.message = result.message;
    }
    out.documents.push_back({".json", toJson(result)});
    out.result = std::move(result);
    return out;
}

AnalysisType tractionType() {
    return makeAnalysisType<TractionSettings>(
        "traction",
        "the slip that maximises drawbar pull or tractive efficiency, with the posterior's band "
        "and a robust slip (docs/traction.md)",
        {"curve", "optimum"}, {{"efficiency", ""}},
        [](io::ObjectReader& r, const ReadContext& context, TractionSettings& s) {
            readTractionSettings(r, s, context.base_dir);
        },
        [](const Inputs& in, const TractionSettings& s, const Control& c) {
            return computeTraction(in, s, c);
        },
        tractionOutcome);
}

}  // namespace terra::analysis
