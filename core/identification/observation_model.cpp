#include "core/identification/observation_model.h"

#include <ceres/jet.h>

#include <cmath>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/scalar.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"

namespace terra::identification {
namespace {

constexpr double kRightAngle = 1.5707963267948966;
// F_z = W to this fraction of W: θ_f to ~1e-12 relative, far below any residual's noise.
constexpr double kLoadTolerance = 1e-12;
constexpr int kNewtonSteps = 8;

template <typename T>
contact::ContactParameters<T> contactParameters(const std::array<T, kFullParameterCount>& p,
                                                const wheel::WheelParameters& wheel,
                                                const ModelSetup& setup) {
    return {T(wheel.radius_m),
            T(wheel.width_m),
            p[kN],
            T(setup.sinkage_exponent_slip),
            p[kKs],
            p[kC],
            p[kPhi],
            p[kK],
            T(0.0),
            p[kA0],
            p[kA1],
            scalarValue(p[kJmax]),
            wheel.lugShearOffset()};
}

// The sample's operating point at θ_f (θ_r = 0, θ_m from a₀, a₁), at `slip`.
template <typename T>
contact::OperatingPoint<T> operatingPointAt(const Sample& s, const T& entry_angle_rad,
                                            const T& slip) {
    return {slip, T(s.slip_angle_rad.value_or(0.0)), entry_angle_rad, T(0.0), std::nullopt};
}

template <typename T>
contact::WheelForces<T> forcesAt(const contact::ContactParameters<T>& p, const Sample& s,
                                 const T& entry_angle_rad, const ModelSetup& setup, const T& slip) {
    return modelForces(p, operatingPointAt(s, entry_angle_rad, slip), setup);
}

template <typename T>
contact::WheelForces<T> forcesAt(const contact::ContactParameters<T>& p, const Sample& s,
                                 const T& entry_angle_rad, const ModelSetup& setup) {
    return forcesAt(p, s, entry_angle_rad, setup, T(s.slip));
}

bool uncertainSlip(const Sample& s) { return s.slip_std && *s.slip_std > 0.0; }

// θ_f with F_z(θ_f) = W: Newton from the last root of this sample (F_z and dF_z/dθ_f from one
// Jet evaluation), which converges in 2–3 steps as the parameters move; the bracketing solver of
// sinkage.h when Newton leaves (0, 90°] or stalls. nullopt: no equilibrium. When Newton ends
// it, the Jet was evaluated at the root returned: `by_angle` (if given) gets ∂(F_x, F_z, M_y)/∂θ_f
// there; else it is left empty.
std::optional<double> solveEntryAngle(const contact::ContactParameters<double>& p, const Sample& s,
                                      double load_n, double start, const ModelSetup& setup,
                                      std::optional<std::array<double, 3>>* by_angle = nullptr) {
    using J = ceres::Jet<double, 1>;
    if (start > 0.0 && start < kRightAngle) {
        const contact::ContactParameters<J> pj = p.cast<J>();
        double theta = start;
        for (int step = 0; step < kNewtonSteps; ++step) {
            const contact::WheelForces<J> f = forcesAt(pj, s, J(theta, 0), setup);
            const J& fz = f.fz;
            const double error = fz.a - load_n;
            if (std::abs(error) <= kLoadTolerance * load_n) {
                if (by_angle) *by_angle = std::array<double, 3>{f.fx.v[0], fz.v[0], f.my.v[0]};
                return theta;
            }
            if (!(fz.v[0] > 0.0)) break;
            const double next = theta - error / fz.v[0];
            if (!(next > 0.0 && next < kRightAngle)) break;
            theta = next;
        }
    }
    contact::EntryAngleProblem problem;
    problem.load_n = load_n;
    problem.slip = s.slip;
    problem.slip_angle_rad = s.slip_angle_rad.value_or(0.0);
    problem.model = setup.model;
    problem.integration = setup.integration;
    if (start > 0.0 && start < kRightAngle) problem.initial_guess_rad = start;
    const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
    if (!solution.ok()) return std::nullopt;
    return solution.entry_angle_rad;
}

}  // namespace

const std::array<const char*, kChannelCount>& channelNames() {
    static const std::array<const char*, kChannelCount> names{"Fx_N", "Fz_N", "My_Nm", "sinkage_m"};
    return names;
}

Result<ModelSetup> setupModel(const DataSet& data, DataSource source, std::optional<double> load_n,
                              double max_shear_deformation_m, double sinkage_exponent_slip,
                              double slip_sinkage_coefficient, contact::ContactModel model) {
    std::vector<Issue> issues;
    if (data.samples.empty()) return std::vector<Issue>{{"data", "no samples"}};
    if (load_n) checkRange(issues, "load_N", *load_n, {0.0, 1e7, true, false}, "N");
    const DataColumns& columns = data.columns;
    if (source == DataSource::kEntryAngle && !columns.entry_angle) {
        issues.push_back({"data",
                          "no entry angle column ('entry_angle_deg' or 'entry_angle_rad'): "
                          "identify from the load (W_N) instead"});
    }
    if (!issues.empty()) return issues;
    ModelSetup setup;
    setup.max_shear_deformation_m = max_shear_deformation_m;
    setup.sinkage_exponent_slip = sinkage_exponent_slip;
    setup.slip_sinkage_coefficient = slip_sinkage_coefficient;
    setup.model = model;
    setup.source = source == DataSource::kAuto
                       ? (columns.entry_angle ? DataSource::kEntryAngle : DataSource::kLoad)
                       : source;
    const bool by_angle = setup.source == DataSource::kEntryAngle;
    // W per sample: the row's W_N, else the one value given, else (from the load) the measured F_z.
    // With θ_f measured, the F_z channel is the measured F_z when there is one.
    bool every_load = true;
    std::size_t without_load = 0, first_without = 0;
    for (std::size_t i = 0; i < data.samples.size(); ++i) {
        const Sample& s = data.samples[i];
        std::optional<double> w = s.load_n ? s.load_n : load_n;
        if (columns.fz && (by_angle || !w)) w = s.fz_n;
        if (!w) {
            every_load = false;
            if (without_load++ == 0) first_without = i;
            setup.loads_n.push_back(0.0);
            continue;
        }
        if (!by_angle) {
            checkRange(issues, "data: sample " + std::to_string(i) + ": W_N", *w,
                       {0.0, 1e7, true, false}, "N");
        }
        setup.loads_n.push_back(*w);
    }
    if (!by_angle && without_load > 0) {
        issues.push_back({"data", std::to_string(without_load) + " samples (the first: sample " +
                                      std::to_string(first_without) +
                                      ") have no load: without an entry angle θ_f is solved from "
                                      "the load; give a W_N column, one load value, or Fz_N"});
    }
    bool any_sinkage = false;
    for (const Sample& s : data.samples) any_sinkage |= s.sinkage_m.has_value();
    setup.channels[kFxChannel] = columns.fx;
    setup.channels[kMyChannel] = columns.my;
    setup.channels[kFzChannel] = by_angle && (columns.fz || every_load);
    // With θ_f measured the sinkage r (1 − cos θ_f) is known and carries nothing more.
    setup.channels[kSinkageChannel] = !by_angle && any_sinkage;
    bool any = false;
    for (bool c : setup.channels) any |= c;
    if (!any) {
        issues.push_back({"data", by_angle ? "no measured channel (Fx_N, Fz_N or My_Nm)"
                                           : "no measured channel besides the load (Fx_N, My_Nm "
                                             "or sinkage_m)"});
    }
    if (!issues.empty()) return issues;
    setup.description = by_angle ? "entry angle measured" : "entry angle solved from the load";
    setup.description += "; channels";
    for (int c = 0; c < kChannelCount; ++c) {
        if (setup.channels[c]) setup.description += std::string(" ") + channelNames()[c];
    }
    return setup;
}

ObservationModel::ObservationModel(const DataSet& data, const wheel::WheelParameters& wheel,
                                   ModelSetup setup)
    : samples_(data.samples),
      wheel_(wheel),
      setup_(std::move(setup)),
      last_entry_angle_(data.samples.size(), 0.0) {
    wheel::requireValid(wheel_);
    if (setup_.loads_n.size() != samples_.size()) {
        throw std::invalid_argument("model setup: " + std::to_string(setup_.loads_n.size()) +
                                    " loads for " + std::to_string(samples_.size()) + " samples");
    }
}

std::array<bool, kChannelCount> ObservationModel::channels(std::size_t i) const {
    std::array<bool, kChannelCount> c = setup_.channels;
    c[kSinkageChannel] = c[kSinkageChannel] && samples_[i].sinkage_m.has_value();
    return c;
}

int ObservationModel::residualCount(std::size_t i) const {
    int n = 0;
    for (bool c : channels(i)) n += c;
    return n;
}

double ObservationModel::measured(std::size_t i, Channel c) const {
    const Sample& s = samples_[i];
    switch (c) {
        case kFxChannel:
            return s.fx_n;
        case kFzChannel:
            return setup_.loads_n[i];
        case kMyChannel:
            return s.my_nm;
        default:
            return s.sinkage_m.value_or(0.0);
    }
}

Prediction ObservationModel::predict(std::size_t i, const ParameterVector& p) const {
    return predictAt(i, p, nullptr);
}

Prediction ObservationModel::predictAt(std::size_t i, const ParameterVector& p,
                                       std::optional<std::array<double, 3>>* by_angle) const {
    Prediction out;
    const Sample& s = samples_[i];
    const contact::ContactParameters<double> cp = contactParameters(p, wheel_, setup_);
    double theta = s.entry_angle_rad;
    if (setup_.source == DataSource::kLoad) {
        const std::optional<double> root =
            solveEntryAngle(cp, s, setup_.loads_n[i], last_entry_angle_[i], setup_, by_angle);
        if (!root) return out;
        theta = last_entry_angle_[i] = *root;
    }
    const contact::WheelForces<double> f = forcesAt(cp, s, theta, setup_);
    out.ok = true;
    out.entry_angle_rad = theta;
    out.values = {
        f.fx, f.fz, f.my,
        contact::slipSinkage(wheel_.radius_m, theta, s.slip, setup_.slip_sinkage_coefficient)};
    return out;
}

// ∂(F_x, F_z, M_y)/∂ln j_max at θ_f by a central difference: the forces are continuously
// differentiable in j_max (the integrand is continuous across the limit's kink, and the
// quadrature is split there, kinks.h), so a step of 1e-4 in ln j_max is accurate to ~1e-8.
std::array<double, 3> ObservationModel::shearLimitDerivative(std::size_t i,
                                                             const ParameterVector& p,
                                                             double entry_angle_rad) const {
    constexpr double kStep = 1e-4;
    std::array<double, 3> out{};
    if (!std::isfinite(p[kJmax])) return out;
    ParameterVector up = p, down = p;
    up[kJmax] = p[kJmax] * std::exp(kStep);
    down[kJmax] = p[kJmax] * std::exp(-kStep);
    const Sample& s = samples_[i];
    // Where the shear never reaches j_max (a driven wheel at low slip) the two evaluations are
    // the same to the bit, pieces included: 0, without them.
    if (setup_.model == contact::ContactModel::kFull &&
        contact::shearLimitUnreached(contactParameters(p, wheel_, setup_),
                                     operatingPointAt(s, entry_angle_rad, s.slip), down[kJmax]))
        return out;
    const contact::WheelForces<double> a =
        forcesAt(contactParameters(up, wheel_, setup_), s, entry_angle_rad, setup_);
    const contact::WheelForces<double> b =
        forcesAt(contactParameters(down, wheel_, setup_), s, entry_angle_rad, setup_);
    out = {(a.fx - b.fx) / (2 * kStep), (a.fz - b.fz) / (2 * kStep), (a.my - b.my) / (2 * kStep)};
    return out;
}

std::optional<ChannelValues> ObservationModel::slipSlope(std::size_t i,
                                                         const ParameterVector& p) const {
    std::optional<std::array<double, 3>> by_angle;
    const Prediction prediction = predictAt(i, p, &by_angle);
    if (!prediction.ok) return std::nullopt;
    return slipSlopeAt(i, p, prediction.entry_angle_rad, by_angle ? &*by_angle : nullptr);
}

std::optional<ChannelValues> ObservationModel::slipSlopeAt(
    std::size_t i, const ParameterVector& p, double entry_angle_rad,
    const std::array<double, 3>* by_angle) const {
    using J = ceres::Jet<double, 1>;
    const Sample& s = samples_[i];
    const contact::ContactParameters<J> pj = contactParameters(p, wheel_, setup_).cast<J>();
    const contact::WheelForces<J> f = forcesAt(pj, s, J(entry_angle_rad), setup_, J(s.slip, 0));
    ChannelValues g{f.fx.v[0], f.fz.v[0], f.my.v[0], 0.0};
    if (setup_.source != DataSource::kLoad) return g;
    // θ_f moves with s so that F_z stays W.
    std::array<double, 3> partial{};
    if (by_angle) {
        partial = *by_angle;
    } else {
        const contact::WheelForces<J> t = forcesAt(pj, s, J(entry_angle_rad, 0), setup_);
        partial = {t.fx.v[0], t.fz.v[0], t.my.v[0]};
    }
    if (!(partial[1] > 0.0)) return std::nullopt;
    const double dtheta_ds = -g[kFzChannel] / partial[1];
    g[kFxChannel] += partial[0] * dtheta_ds;
    g[kMyChannel] += partial[2] * dtheta_ds;
    g[kFzChannel] = 0.0;  // F_z = W at every slip
    // h = r (1 − cos θ_f)(1 + S s), the factor's S only for s > 0 (Eq. S.1, slipSinkageFactor).
    const double r_m = wheel_.radius_m, S = setup_.slip_sinkage_coefficient;
    g[kSinkageChannel] =
        contact::slipSinkageFactor(s.slip, S) * r_m * std::sin(entry_angle_rad) * dtheta_ds +
        (S != 0.0 && s.slip > 0.0 ? r_m * (1.0 - std::cos(entry_angle_rad)) * S : 0.0);
    return g;
}

bool ObservationModel::residuals(std::size_t i, const double* u, const ChannelValues& sigma,
                                 double* r, double* jacobian) const {
    constexpr int n = kFullParameterCount;
    constexpr int nj = kJetParameterCount;  // j_max's column: shearLimitDerivative
    const std::array<bool, kChannelCount> active = channels(i);
    const Sample& s = samples_[i];
    ChannelValues value{};
    std::array<std::array<double, n>, kChannelCount> derivative{};
    ParameterVector p{};
    {
        const auto physical = toPhysical(u);
        std::copy(physical.begin(), physical.end(), p.begin());
    }
    double entry_angle_rad = s.entry_angle_rad;
    std::optional<std::array<double, 3>> by_angle;  // ∂(F_x, F_z, M_y)/∂θ_f, from the load's Jet
    if (!jacobian) {
        const Prediction prediction = predictAt(i, p, uncertainSlip(s) ? &by_angle : nullptr);
        if (!prediction.ok) return false;
        value = prediction.values;
        entry_angle_rad = prediction.entry_angle_rad;
    } else if (setup_.source == DataSource::kEntryAngle) {
        using J = ceres::Jet<double, nj>;
        std::array<J, n> uj;
        for (int k = 0; k < n; ++k) uj[k] = k < nj ? J(u[k], k) : J(u[k]);
        const contact::WheelForces<J> f =
            forcesAt(contactParameters(toPhysical(uj.data()), wheel_, setup_), s,
                     J(s.entry_angle_rad), setup_);
        const J* channel[3] = {&f.fx, &f.fz, &f.my};
        const std::array<double, 3> limit = setup_.max_shear_deformation_free
                                                ? shearLimitDerivative(i, p, s.entry_angle_rad)
                                                : std::array<double, 3>{};
        for (int c = 0; c < 3; ++c) {
            value[c] = channel[c]->a;
            for (int k = 0; k < nj; ++k) derivative[c][k] = channel[c]->v[k];
            derivative[c][kJmax] = limit[c];
        }
    } else {
        // θ_f(u) from F_z(θ_f, u) = W, then one Jet over (u, θ_f): the total derivative of a
        // channel y is ∂y/∂u + ∂y/∂θ_f · dθ_f/du, dθ_f/du = −(∂F_z/∂u)/(∂F_z/∂θ_f).
        const std::optional<double> root =
            solveEntryAngle(contactParameters(p, wheel_, setup_), s, setup_.loads_n[i],
                            last_entry_angle_[i], setup_);
        if (!root) return false;
        last_entry_angle_[i] = *root;
        using J = ceres::Jet<double, nj + 1>;
        std::array<J, n> uj;
        for (int k = 0; k < n; ++k) uj[k] = k < nj ? J(u[k], k) : J(u[k]);
        const contact::WheelForces<J> f = forcesAt(
            contactParameters(toPhysical(uj.data()), wheel_, setup_), s, J(*root, nj), setup_);
        const double dfz_dtheta = f.fz.v[nj];
        if (!(dfz_dtheta > 0.0)) return false;
        entry_angle_rad = *root;
        by_angle = {f.fx.v[nj], dfz_dtheta, f.my.v[nj]};
        std::array<double, n> partial_fz{};
        std::array<std::array<double, n>, 3> partial{};
        const J* channel[3] = {&f.fx, &f.fz, &f.my};
        const std::array<double, 3> limit = setup_.max_shear_deformation_free
                                                ? shearLimitDerivative(i, p, *root)
                                                : std::array<double, 3>{};
        for (int c = 0; c < 3; ++c) {
            for (int k = 0; k < nj; ++k) partial[c][k] = channel[c]->v[k];
            partial[c][kJmax] = limit[c];
        }
        partial_fz = partial[1];
        std::array<double, n> dtheta{};
        for (int k = 0; k < n; ++k) dtheta[k] = -partial_fz[k] / dfz_dtheta;
        for (int c = 0; c < 3; ++c) {
            value[c] = channel[c]->a;
            for (int k = 0; k < n; ++k)
                derivative[c][k] = partial[c][k] + channel[c]->v[nj] * dtheta[k];
        }
        const double r_m = wheel_.radius_m;
        value[kSinkageChannel] =
            contact::slipSinkage(r_m, *root, s.slip, setup_.slip_sinkage_coefficient);
        // dh/dθ_f of Eq. S.1: the slip factor 1 + S s is a constant of the sample (exactly 1, and
        // so no change to the thesis model's derivative, when S = 0).
        const double factor = contact::slipSinkageFactor(s.slip, setup_.slip_sinkage_coefficient);
        for (int k = 0; k < n; ++k)
            derivative[kSinkageChannel][k] = factor * r_m * std::sin(*root) * dtheta[k];
    }
    int row = 0;
    for (int c = 0; c < kChannelCount; ++c) {
        if (!active[c]) continue;
        const double w = 1.0 / sigma[c];
        r[row] = (value[c] - measured(i, static_cast<Channel>(c))) * w;
        if (jacobian) {
            for (int k = 0; k < n; ++k) jacobian[row * n + k] = derivative[c][k] * w;
        }
        ++row;
    }
    if (uncertainSlip(s)) {
        const std::optional<ChannelValues> slope =
            slipSlopeAt(i, p, entry_angle_rad, by_angle ? &*by_angle : nullptr);
        if (!slope) return false;
        std::array<double, kChannelCount> g{};  // ∂r/∂s of the rows
        row = 0;
        for (int c = 0; c < kChannelCount; ++c) {
            if (active[c]) g[row++] = (*slope)[c] / sigma[c];
        }
        double norm = 0.0;
        for (int a = 0; a < row; ++a) norm += g[a] * g[a];
        norm = std::sqrt(norm);
        if (!std::isfinite(norm)) return false;
        if (norm > 0.0) {
            const double alpha = 1.0 - 1.0 / std::sqrt(1.0 + std::pow(*s.slip_std * norm, 2));
            for (int a = 0; a < row; ++a) g[a] /= norm;
            double along = 0.0;
            for (int a = 0; a < row; ++a) along += g[a] * r[a];
            for (int a = 0; a < row; ++a) r[a] -= alpha * g[a] * along;
            if (jacobian) {
                for (int k = 0; k < n; ++k) {
                    double column = 0.0;
                    for (int a = 0; a < row; ++a) column += g[a] * jacobian[a * n + k];
                    for (int a = 0; a < row; ++a) jacobian[a * n + k] -= alpha * g[a] * column;
                }
            }
        }
    }
    return true;
}

}  // namespace terra::identification
