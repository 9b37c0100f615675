#include "core/identification/streaming_estimator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"
#include "core/identification/observation_model.h"

namespace terra::identification {
namespace {

constexpr int kP = kFullParameterCount;
using Vector = Eigen::Matrix<double, kP, 1>;
using Matrix = Eigen::Matrix<double, kP, kP>;

// One sample of the horizon: its model (which keeps the sample's last θ_f as a warm start) and
// its residuals and Jacobian at the last linearisation.
struct Member {
    std::unique_ptr<ObservationModel> model;
    Eigen::VectorXd r;
    Eigen::Matrix<double, Eigen::Dynamic, kP> j;
    Vector at;  // where r and j were evaluated
    // A sample with an uncertain slip comes whitened from ObservationModel::residuals.
};

}  // namespace

struct StreamingEstimator::State {
    wheel::WheelParameters wheel;
    StreamingEstimatorOptions options;
    std::size_t count = 0;
    bool tracking = false;
    DataSource source = DataSource::kAuto;
    ChannelValues sigma{};
    std::array<bool, kP> fixed{};
    Vector lower, upper;
    Vector u = Vector::Zero();           // the estimate (solver coordinates)
    Matrix covariance = Matrix::Zero();  // its posterior covariance (solver coordinates)
    Vector arrival_mean = Vector::Zero();  // the arrival cost ‖u − mean‖² of `arrival_information`
    Matrix arrival_information = Matrix::Zero();
    std::deque<Member> window;
    std::vector<Sample> buffer;  // samples of the next initialisation
    struct Suspect {
        Sample sample;
        std::size_t index;
        bool usable;  // within the gate
    };
    std::vector<Suspect> segment;  // samples since the CUSUM was last zero
    std::deque<Sample> recent;     // accepted samples, for the confirmation of a change
    double cusum = 0.0;
    std::size_t anchor_size = 0;   // samples of the batch fit the arrival cost was built from
    std::size_t since_anchor = 0;  // samples used since

    std::vector<int> freeIndices() const {
        std::vector<int> f;
        for (int k = 0; k < kP; ++k) {
            if (!fixed[k]) f.push_back(k);
        }
        return f;
    }

    std::unique_ptr<ObservationModel> modelOf(const Sample& s) const {
        const DataSet one({s}, options.columns);
        const Result<ModelSetup> setup =
            setupModel(one, source, options.fit.load_n, options.fit.max_shear_deformation_m, 0.0,
                       0.0, options.fit.model);
        if (!setup) return nullptr;
        return std::make_unique<ObservationModel>(one, wheel, setup.value());
    }

    bool linearise(Member& m) const {
        const int rows = m.model->residualCount(0);
        m.r.resize(rows);
        m.j.resize(rows, kP);
        Eigen::Matrix<double, Eigen::Dynamic, kP, Eigen::RowMajor> jr(rows, kP);
        if (!m.model->residuals(0, u.data(), sigma, m.r.data(), jr.data())) return false;
        m.j = jr;
        for (int k = 0; k < kP; ++k) {
            if (fixed[k]) m.j.col(k).setZero();
        }
        m.at = u;
        return true;
    }

    // The inverse of an information matrix on some parameters (zero elsewhere).
    Matrix inverse(const Matrix& information) const { return inverse(information, freeIndices()); }
    Matrix inverse(const Matrix& information, const std::vector<int>& f) const {
        const int n = static_cast<int>(f.size());
        Eigen::MatrixXd h(n, n);
        for (int a = 0; a < n; ++a) {
            for (int b = 0; b < n; ++b) h(a, b) = information(f[a], f[b]);
        }
        const Eigen::MatrixXd inv = h.ldlt().solve(Eigen::MatrixXd::Identity(n, n));
        Matrix out = Matrix::Zero();
        for (int a = 0; a < n; ++a) {
            for (int b = 0; b < n; ++b) out(f[a], f[b]) = inv(a, b);
        }
        return out;
    }

    // A weak prior that keeps the information invertible where the initialisation's samples see
    // nothing: the width of the parameter's bounds (solver coordinates) as a standard deviation,
    // wider than any valley the data leave open (one load: c–φ, ±30°).
    Matrix regulariser() const {
        Matrix m = Matrix::Zero();
        for (int k = 0; k < kP; ++k) {
            if (!fixed[k]) m(k, k) = 1.0 / std::pow(upper(k) - lower(k), 2);
        }
        return m;
    }

    // The objective at v: the arrival cost plus the horizon's Σ r² (+inf when the model fails).
    double objective(const Vector& v) const {
        const Vector d = v - arrival_mean;
        double value = d.dot(arrival_information * d);
        std::vector<double> r(kChannelCount);
        for (const Member& m : window) {
            if (!m.model->residuals(0, v.data(), sigma, r.data(), nullptr)) return INFINITY;
            for (int c = 0; c < m.model->residualCount(0); ++c) value += r[c] * r[c];
        }
        return value;
    }

    // Gauss–Newton steps on the arrival cost plus the horizon, each step halved until the
    // objective decreases (a wide prior otherwise lets one sample throw the estimate along an
    // undetermined direction onto a bound); the covariance is the inverse of the information at
    // the last linearisation.
    void update() {
        const std::vector<int> f = freeIndices();
        Matrix information = arrival_information;
        double current = INFINITY;
        for (int it = 0; it < options.iterations; ++it) {
            information = arrival_information;
            Vector gradient = arrival_information * (u - arrival_mean);
            double value = (u - arrival_mean).dot(gradient);
            bool ok = true;
            for (Member& m : window) {
                ok = ok && (m.at == u || linearise(m));
                if (!ok) break;
                information += m.j.transpose() * m.j;
                gradient += m.j.transpose() * m.r;
                value += m.r.squaredNorm();
            }
            if (!ok) break;
            current = value;
            // Parameters on a bound that the step would push out are held for this step.
            std::vector<int> moving = f;
            Vector step = Vector::Zero();
            for (bool again = true; again && !moving.empty();) {
                step = -(inverse(information, moving) * gradient);
                again = false;
                for (std::size_t a = 0; a < moving.size(); ++a) {
                    const int k = moving[a];
                    if ((u(k) <= lower(k) && step(k) < 0) || (u(k) >= upper(k) && step(k) > 0)) {
                        moving.erase(moving.begin() + static_cast<long>(a));
                        again = true;
                        break;
                    }
                }
            }
            bool improved = false;
            for (double t = 1.0; t > 1e-3 && !improved; t *= 0.5) {
                Vector next = u;
                for (int k : moving) next(k) = std::clamp(u(k) + t * step(k), lower(k), upper(k));
                const double value_next = objective(next);
                if (value_next < current) {
                    u = next;
                    current = value_next;
                    improved = true;
                }
            }
            if (!improved) break;
        }
        covariance = inverse(information);
    }

    // Folds the oldest horizon member into the arrival cost, linearised where it was last.
    void foldOldest() {
        Member& m = window.front();
        const Matrix added = m.j.transpose() * m.j;
        const Vector rhs =
            arrival_information * arrival_mean + m.j.transpose() * (m.j * m.at - m.r);
        arrival_information += added;
        const Vector mean = inverse(arrival_information) * rhs;
        for (int k : freeIndices()) arrival_mean(k) = mean(k);
        window.pop_front();
    }

    bool initialise(StreamEstimate& out) {
        const DataSet data(buffer, options.columns);
        const IdentificationReport fit = identify(data, wheel, options.fit);
        if (!fit.usable()) {
            // Keep the newest samples and try again when more have come.
            buffer.erase(buffer.begin(), buffer.begin() + static_cast<long>(buffer.size() / 2));
            return false;
        }
        adopt(data, fit);
        out.initialised = true;
        return true;
    }

    // The information of a batch fit's samples at its estimate, its priors and the weak
    // regulariser (solver coordinates; zero rows and columns for held parameters).
    Matrix informationOf(const DataSet& data, const IdentificationReport& fit) const {
        const ParameterVector at = toSolver(fit.parameters);
        const ObservationModel model(data, wheel, fit.setup);
        Matrix information = regulariser();
        std::vector<double> r(kChannelCount), j(kChannelCount * kP);
        for (std::size_t i = 0; i < model.size(); ++i) {
            if (!model.residuals(i, at.data(), fit.noise, r.data(), j.data())) continue;
            const int rows = model.residualCount(i);
            const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, kP, Eigen::RowMajor>> jm(
                j.data(), rows, kP);
            information += jm.transpose() * jm;
        }
        const ParameterVector slope = physicalPerSolver(fit.parameters);
        for (int k = 0; k < kP; ++k) {
            if (options.fit.priors[k] && !fixed[k])
                information(k, k) += std::pow(slope[k] / options.fit.priors[k]->std, 2);
            if (fixed[k]) information.row(k).setZero(), information.col(k).setZero();
        }
        return information;
    }

    // Starts tracking from a batch fit: its estimate, noise levels, and as the arrival cost the
    // information of its samples at the estimate, its priors and the weak regulariser.
    void adopt(const DataSet& data, const IdentificationReport& fit) {
        source = fit.setup.source;
        sigma = fit.noise;
        const ParameterVector u0 = toSolver(fit.parameters);
        for (int k = 0; k < kP; ++k) u(k) = u0[k];
        arrival_information = informationOf(data, fit);
        arrival_mean = u;
        covariance = inverse(arrival_information);
        window.clear();
        buffer.clear();
        segment.clear();
        recent.assign(data.samples.begin(), data.samples.end());
        while (recent.size() > options.history) recent.pop_front();
        cusum = 0.0;
        tracking = true;
        anchor_size = data.samples.size();
        since_anchor = 0;
    }

    // Rebuilds the arrival cost from a batch refinement of the history, started at the current
    // estimate: the folded linearisations of a wide early prior otherwise leave a bias of a few
    // std. Done when the samples used since the last batch fit equal that fit's samples (so the
    // refits double: 30, 60, 120, … up to `history`, then every `history` samples), with the
    // noise levels (when not given) estimated again from more samples until the history is full.
    void reanchor(StreamEstimate& out) {
        if (since_anchor < std::max<std::size_t>(anchor_size, 1) || !segment.empty()) return;
        out.refitted = true;
        IdentifyOptions o = options.fit;
        o.progress = nullptr;
        o.design_points = 0;
        o.descents = 1;
        Start start{"current estimate", {}};
        const std::array<double, kP> current = toPhysical(u.data());
        std::copy(current.begin(), current.end(), start.parameters.begin());
        o.starts = {start};
        // Once the history is full the levels are known from as many samples as will ever be
        // used: keep them (one refinement instead of two or three).
        if (anchor_size >= options.history) o.noise = sigma;
        const DataSet history(std::vector<Sample>(recent.begin(), recent.end()), options.columns);
        const IdentificationReport fit = identify(history, wheel, o);
        if (fit.usable()) {
            adopt(history, fit);
        } else {
            since_anchor = 0;
        }
    }

    // The log-likelihood ratio of the CUSUM, ℓ = ½ [ε (1 − 1/λ) − m ln λ], capped.
    double evidenceOf(double nis, int m) const {
        const double lambda = options.change_inflation;
        return std::min(0.5 * (nis * (1.0 - 1.0 / lambda) - m * std::log(lambda)),
                        options.max_step_evidence);
    }

    // Where a confirmed change began: the generalised likelihood-ratio estimate of the change
    // time (docs/identification.md §8). Before τ the innovations are N(0, S), from τ on
    // N(0, λS) with λ ≥ 1 unknown; with the suspect samples' ε taken against the batch fit of the
    // history (`before`, its covariance from the information of its samples: the running
    // estimate's linearisation can underrate how far a new slip or load lies from what its
    // samples determined), the log-likelihood ratio of a change at τ, maximised over λ, is
    // G(τ) = ½ [Σ ε − M − M ln(Σ ε / M)] over the samples from τ on (M their residuals,
    // λ̂ = Σ ε / M), and the change began at argmax_τ G. The CUSUM's fixed λ would count a
    // sample of the old soil with ε > m ln λ /(1 − 1/λ) (5.5 for m = 3, p = 2 %) as evidence of a
    // change and place it early; λ̂ of a real border is ~100. Returns an index into `segment`.
    std::size_t placeChange(const DataSet& history, const IdentificationReport& before) const {
        const Matrix p = inverse(informationOf(history, before));
        const ParameterVector at = toSolver(before.parameters);
        std::vector<double> nis(segment.size(), INFINITY);
        std::vector<int> rows(segment.size(), 1);
        Member m;
        for (std::size_t k = 0; k < segment.size(); ++k) {
            m.model = modelOf(segment[k].sample);
            if (!m.model) continue;  // cannot be predicted by the old soil
            rows[k] = m.model->residualCount(0);
            m.r.resize(rows[k]);
            Eigen::Matrix<double, Eigen::Dynamic, kP, Eigen::RowMajor> jr(rows[k], kP);
            if (!m.model->residuals(0, at.data(), sigma, m.r.data(), jr.data())) continue;
            m.j = jr;
            for (int c = 0; c < kP; ++c) {
                if (fixed[c]) m.j.col(c).setZero();
            }
            const Eigen::MatrixXd innovation =
                m.j * p * m.j.transpose() + Eigen::MatrixXd::Identity(rows[k], rows[k]);
            nis[k] = m.r.dot(innovation.ldlt().solve(m.r));
        }
        std::size_t best = segment.size() - 1;
        double best_ratio = -INFINITY, sum = 0.0, count = 0.0;
        for (std::size_t k = segment.size(); k-- > 0;) {
            // A sample the old soil cannot carry is a change at the latest there.
            if (!std::isfinite(nis[k])) return k;
            sum += nis[k];
            count += rows[k];
            const double lambda = std::max(1.0, sum / count);
            const double ratio = 0.5 * (sum * (1.0 - 1.0 / lambda) - count * std::log(lambda));
            if (ratio > best_ratio) best_ratio = ratio, best = k;
        }
        return best;
    }

    // The generalised likelihood-ratio test of an alarm (see the header). True: a change of
    // soil, beginning at segment[first]; false: the joint fit explains everything and has become
    // the estimate.
    bool confirm(StreamEstimate& out, std::size_t& first) {
        // Without a history to test against: the first suspect sample beyond the gate (the CUSUM
        // may have left zero on a few noisy samples of the old soil before it).
        first = 0;
        while (first + 1 < segment.size() && segment[first].usable) ++first;
        if (recent.size() < 2 * static_cast<std::size_t>(kP)) return true;
        IdentifyOptions o = options.fit;
        o.noise = sigma;
        o.progress = nullptr;
        const std::array<double, kP> current = toPhysical(u.data());
        Start start{"current estimate", {}};
        std::copy(current.begin(), current.end(), start.parameters.begin());
        IdentifyOptions local = o;
        local.design_points = 8;
        local.descents = 2;
        local.starts = {start};
        const DataSet history(std::vector<Sample>(recent.begin(), recent.end()), options.columns);
        const IdentificationReport before = identify(history, wheel, local);
        DataSet joint = history;
        for (const Suspect& k : segment) joint.samples.push_back(k.sample);
        o.design_points = IdentifyOptions{}.design_points;
        o.descents = IdentifyOptions{}.descents;
        o.starts = {start};
        if (before.usable()) o.starts.push_back({"history", before.parameters});
        const IdentificationReport together = identify(joint, wheel, o);
        if (!before.usable()) return true;
        if (!together.usable()) {
            first = placeChange(history, before);
            return true;
        }
        const int added = together.residuals - before.residuals;

        out.change_statistic = together.chi2 - before.chi2;
        const double limit = boost::math::quantile(boost::math::chi_squared(std::max(added, 1)),
                                                   1.0 - options.confirm_probability);
        if (out.change_statistic > limit) {
            first = placeChange(history, before);
            return true;
        }
        adopt(joint, together);
        return false;
    }

    void fill(StreamEstimate& out) const {
        out.estimated = tracking;
        out.cusum = cusum;
        if (!tracking) return;
        const std::array<double, kP> p = toPhysical(u.data());
        std::copy(p.begin(), p.end(), out.parameters.begin());
        const ParameterVector slope = physicalPerSolver(out.parameters);
        for (int k = 0; k < kP; ++k)
            out.std[k] = std::sqrt(std::max(0.0, covariance(k, k))) * slope[k];
    }
};

StreamingEstimator::StreamingEstimator(const wheel::WheelParameters& wheel,
                                       StreamingEstimatorOptions options)
    : state_(std::make_unique<State>()) {
    wheel::requireValid(wheel);
    std::vector<Issue> issues;
    checkRange(issues, "init_samples", static_cast<double>(options.init_samples), {2, 1e9});
    checkRange(issues, "window", static_cast<double>(options.window), {1, 1e6});
    checkRange(issues, "iterations", options.iterations, {1, 100});
    checkRange(issues, "memory_samples", options.memory_samples, {1.0, 1e12, true, false});
    checkRange(issues, "change_inflation", options.change_inflation, {1.0, 1e6, true, false});
    checkRange(issues, "change_threshold", options.change_threshold, {0.0, 1e6, true, false});
    checkRange(issues, "max_step_evidence", options.max_step_evidence, {0.0, 1e6, true, false});
    checkRange(issues, "gate_probability", options.gate_probability, {0.0, 1.0, true, true});
    checkRange(issues, "confirm_probability", options.confirm_probability, {0.0, 1.0, true, true});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    State& s = *state_;
    s.wheel = wheel;
    s.options = std::move(options);
    s.options.fit.holdout_fraction = 0.0;
    s.options.fit.folds = 0;
    // The streaming estimate holds j_max at the options' value (its recursive update has no
    // shear-limit column).
    if (!s.options.fit.fixed[kJmax])
        s.options.fit.fixed[kJmax] = s.options.fit.max_shear_deformation_m;
    s.options.fit.fit_max_shear_deformation = false;
    s.source = s.options.fit.source;
    s.sigma = s.options.fit.noise;
    const ParameterVector lo = toSolver(s.options.fit.bounds.lower),
                          hi = toSolver(s.options.fit.bounds.upper);
    for (int k = 0; k < kP; ++k) {
        s.fixed[k] = s.options.fit.fixed[k].has_value();
        s.lower(k) = lo[k];
        s.upper(k) = hi[k];
    }
}

StreamingEstimator::~StreamingEstimator() = default;
StreamingEstimator::StreamingEstimator(StreamingEstimator&&) noexcept = default;
StreamingEstimator& StreamingEstimator::operator=(StreamingEstimator&&) noexcept = default;

StreamEstimate StreamingEstimator::push(const Sample& sample) {
    const auto begin = std::chrono::steady_clock::now();
    State& s = *state_;
    StreamEstimate out;
    out.index = s.count++;
    auto finish = [&]() {
        s.fill(out);
        out.update_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
                .count();
        return out;
    };
    if (!s.tracking) {
        s.buffer.push_back(sample);
        if (s.buffer.size() >= s.options.init_samples) s.initialise(out);
        return finish();
    }
    Member member;
    member.model = s.modelOf(sample);
    if (!member.model || !s.linearise(member)) return finish();  // cannot be predicted: skipped
    // An uncertain slip comes whitened by I + σ_s² g gᵀ (ObservationModel::residuals), so the
    // innovation below is ε = rᵀ (H P Hᵀ + I + σ_s² g gᵀ)⁻¹ r in the whitened coordinates.
    // The information fades; the covariance before this sample grows with it.
    const double keep = 1.0 - 1.0 / s.options.memory_samples;
    s.arrival_information *= keep;
    const Matrix prior = s.covariance / keep;
    // Normalised innovation squared and the CUSUM of the log-likelihood ratio.
    const int m = static_cast<int>(member.r.size());
    const Eigen::MatrixXd innovation =
        member.j * prior * member.j.transpose() + Eigen::MatrixXd::Identity(m, m);
    out.nis = member.r.dot(innovation.ldlt().solve(member.r));
    out.channels = m;
    const double evidence = s.evidenceOf(out.nis, m);
    const double gate =
        boost::math::quantile(boost::math::chi_squared(m), 1.0 - s.options.gate_probability);
    const bool usable = out.nis <= gate;
    const double previous = s.cusum;
    s.cusum = std::max(0.0, s.cusum + evidence);
    if (s.cusum > 0.0) {
        if (previous == 0.0) s.segment.clear();
        s.segment.push_back({sample, out.index, usable});
    }
    if (s.cusum > s.options.change_threshold) {
        std::size_t first = 0;
        if (!s.confirm(out, first)) {
            out.change_rejected = true;
            return finish();
        }
        out.change_detected = true;
        out.change_at = s.segment[first].index;
        s.tracking = false;
        s.buffer.clear();
        for (std::size_t k = first; k < s.segment.size(); ++k)
            s.buffer.push_back(s.segment[k].sample);
        s.segment.clear();
        s.window.clear();
        s.recent.clear();
        s.cusum = 0.0;
        return finish();
    }
    if (usable) {
        s.window.push_back(std::move(member));
        s.update();
        while (s.window.size() > s.options.window) s.foldOldest();
        out.used = true;
        ++s.since_anchor;
    }
    // Back to zero: the suspect samples belonged to the soil after all.
    if (s.cusum == 0.0) {
        for (const State::Suspect& k : s.segment) {
            if (k.usable) s.recent.push_back(k.sample);
        }
        s.segment.clear();
        if (usable) s.recent.push_back(sample);
        while (s.recent.size() > s.options.history) s.recent.pop_front();
        s.reanchor(out);
    }
    return finish();
}

std::array<std::array<double, kFullParameterCount>, kFullParameterCount>
StreamingEstimator::covariance() const {
    const State& s = *state_;
    std::array<std::array<double, kP>, kP> out{};
    if (!s.tracking) return out;
    const std::array<double, kP> p = toPhysical(s.u.data());
    ParameterVector pv;
    std::copy(p.begin(), p.end(), pv.begin());
    const ParameterVector slope = physicalPerSolver(pv);
    for (int a = 0; a < kP; ++a) {
        for (int b = 0; b < kP; ++b) out[a][b] = s.covariance(a, b) * slope[a] * slope[b];
    }
    return out;
}

const ChannelValues& StreamingEstimator::noise() const { return state_->sigma; }

}  // namespace terra::identification
