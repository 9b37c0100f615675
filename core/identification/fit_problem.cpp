#include "core/identification/fit_problem.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <set>

#include "core/common/range.h"
#include "core/common/worker_pool.h"

namespace terra::identification::detail {
namespace {

constexpr int kP = kFullParameterCount;

// Each sample's first residual row among `samples` (the rows of sample t start at first[t]), and
// the rows in all.
std::vector<int> firstRows(const ObservationModel& model, const std::vector<std::size_t>& samples,
                           int& rows) {
    std::vector<int> first;
    rows = 0;
    for (std::size_t i : samples) {
        first.push_back(rows);
        rows += model.residualCount(i);
    }
    return first;
}

// Sample t's weighted residuals at u into r + first[t], and their Jacobian (rows of kP,
// row-major) into j + first[t]·kP when j is given; whether each sample's model evaluation
// succeeded. On the pool when there is one: each sample is one thread's, written to its own
// rows, so the numbers are the same whatever the thread count. Without a pool and with
// `stop_at_failure`, the samples after the first that fails are not evaluated (false), as one
// thread always did (from the load, each evaluation moves that sample's warm start for θ_f).
std::vector<char> evaluateSamples(const ObservationModel& model,
                                  const std::vector<std::size_t>& samples,
                                  const std::vector<int>& first, const double* u,
                                  const ChannelValues& sigma, WorkerPool* pool, double* r,
                                  double* j, bool stop_at_failure) {
    std::vector<char> ok(samples.size(), 0);
    const auto one = [&](std::size_t t) {
        const auto row = static_cast<std::size_t>(first[t]);
        ok[t] = model.residuals(samples[t], u, sigma, r + row, j ? j + row * kP : nullptr);
    };
    if (pool) {
        pool->forEachIndex(samples.size(), one);
    } else {
        for (std::size_t t = 0; t < samples.size(); ++t) {
            one(t);
            if (stop_at_failure && !ok[t]) break;
        }
    }
    return ok;
}

// The data residuals of some samples in one cost function of the 7 solver coordinates.
class DataCost final : public ceres::CostFunction {
public:
    DataCost(const ObservationModel& model, std::vector<std::size_t> samples,
             const ChannelValues& sigma, WorkerPool* pool)
        : model_(model), samples_(std::move(samples)), sigma_(sigma), pool_(pool) {
        int rows = 0;
        first_ = firstRows(model_, samples_, rows);
        set_num_residuals(rows);
        mutable_parameter_block_sizes()->push_back(kP);
    }

    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
        const std::vector<char> ok =
            evaluateSamples(model_, samples_, first_, parameters[0], sigma_, pool_, residuals,
                            jacobians ? jacobians[0] : nullptr, true);
        return std::all_of(ok.begin(), ok.end(), [](char v) { return v != 0; });
    }

private:
    const ObservationModel& model_;
    std::vector<std::size_t> samples_;
    ChannelValues sigma_;
    WorkerPool* pool_;
    std::vector<int> first_;
};

// (θ_k(u) − mean)/std for each active prior of a free parameter.
class PriorCost final : public ceres::CostFunction {
public:
    PriorCost(const Priors& priors, const std::array<bool, kP>& fixed) {
        for (int k = 0; k < kP; ++k) {
            if (priors[k] && !fixed[k]) terms_.push_back({k, *priors[k]});
        }
        set_num_residuals(static_cast<int>(terms_.size()));
        mutable_parameter_block_sizes()->push_back(kP);
    }
    bool empty() const { return terms_.empty(); }

    bool Evaluate(double const* const* parameters, double* residuals,
                  double** jacobians) const override {
        const std::array<double, kP> p = toPhysical(parameters[0]);
        ParameterVector pv;
        std::copy(p.begin(), p.end(), pv.begin());
        const ParameterVector slope = physicalPerSolver(pv);
        for (std::size_t t = 0; t < terms_.size(); ++t) {
            const auto& [k, prior] = terms_[t];
            residuals[t] = (p[k] - prior.mean) / prior.std;
            if (jacobians && jacobians[0]) {
                double* row = jacobians[0] + t * kP;
                std::fill(row, row + kP, 0.0);
                row[k] = slope[k] / prior.std;
            }
        }
        return true;
    }

private:
    std::vector<std::pair<int, GaussianPrior>> terms_;
};

double defaultLossScale(int channels) {
    return std::sqrt(boost::math::quantile(boost::math::chi_squared(channels), 0.95));
}

ceres::LossFunction* makeLoss(Loss loss, double scale) {
    switch (loss) {
        case Loss::kHuber:
            return new ceres::HuberLoss(scale);
        case Loss::kCauchy:
            return new ceres::CauchyLoss(scale);
        default:
            return nullptr;
    }
}

// The advice on a pair of parameters the data do not separate, each named through the table
// (parameter_text.h): the two known valleys with what separates them, any other pair plainly.
ParameterText pairAdvice(int i, int j) {
    const std::set<int> pair{i, j};
    const std::string a = reference(static_cast<FullParameter>(i)),
                      b = reference(static_cast<FullParameter>(j));
    if (pair == std::set<int>{kC, kPhi}) {
        return a + " and " + b +
               " trade off (one load shows only the shear strength they make together, "
               "Eq. 2.21): add data at several loads";
    }
    if (pair == std::set<int>{kKs, kN}) {
        return a + " and " + b +
               " trade off along a flat valley: add data over a wider range of sinkage (several "
               "loads)";
    }
    return a + " and " + b + " are not separable by these data";
}

}  // namespace

std::vector<std::size_t> allSamples(std::size_t n) {
    std::vector<std::size_t> all(n);
    for (std::size_t i = 0; i < n; ++i) all[i] = i;
    return all;
}

namespace {

// Every sample's weighted residuals and their Jacobian at u (evaluateSamples), for the callers
// to add up in sample order: the sums are then the same whatever the thread count.
struct SampleRows {
    std::vector<int> first;  // first residual of each sample
    std::vector<double> r, j;
    std::vector<char> ok;

    SampleRows(const Objective& objective, const std::vector<std::size_t>& samples, const double* u,
               bool stop_at_failure) {
        int rows = 0;
        first = firstRows(*objective.model, samples, rows);
        r.assign(static_cast<std::size_t>(rows), 0.0);
        j.assign(static_cast<std::size_t>(rows) * kP, 0.0);
        ok = evaluateSamples(*objective.model, samples, first, u, objective.sigma, objective.pool,
                             r.data(), j.data(), stop_at_failure);
    }
};

}  // namespace

FitProblem::FitProblem(const Objective& objective, const std::vector<std::size_t>& samples) {
    const ObservationModel& model = *objective.model;
    for (std::size_t i : samples) data_residuals_ += model.residualCount(i);
    if (objective.loss == Loss::kSquared) {
        costs_.push_back(
            std::make_unique<DataCost>(model, samples, objective.sigma, objective.pool));
        losses_.push_back(nullptr);
    } else {
        for (std::size_t i : samples) {
            const int channels = model.residualCount(i);
            const double scale =
                objective.loss_scale > 0 ? objective.loss_scale : defaultLossScale(channels);
            costs_.push_back(std::make_unique<DataCost>(model, std::vector<std::size_t>{i},
                                                        objective.sigma, nullptr));
            losses_.emplace_back(makeLoss(objective.loss, scale));
        }
    }
    auto prior = std::make_unique<PriorCost>(objective.priors, objective.fixed);
    if (!prior->empty()) {
        costs_.push_back(std::move(prior));
        losses_.push_back(nullptr);
    }
    for (std::size_t b = 0; b < costs_.size(); ++b) {
        box_.costs.push_back(costs_[b].get());
        box_.losses.push_back(losses_[b].get());
    }
    const ParameterVector lower = toSolver(objective.bounds.lower),
                          upper = toSolver(objective.bounds.upper);
    box_.lower.assign(lower.begin(), lower.end());
    box_.upper.assign(upper.begin(), upper.end());
    box_.fixed.assign(objective.fixed.begin(), objective.fixed.end());
}

BoxOptions descentOptions() {
    BoxOptions o;
    o.max_iterations = 40;
    o.iterations_per_pass = 20;
    o.gradient = false;
    o.function_tolerance = 1e-8;
    o.parameter_tolerance = 1e-8;
    o.gradient_tolerance = 1e-12;
    return o;
}

BoxOptions refinementOptions() {
    BoxOptions o;
    o.max_iterations = 100;
    o.iterations_per_pass = 40;
    // 1e-10 of the cost is far below the noise; the Gauss–Newton polish (polish()) finishes
    // noise-free data to rounding (truth to 1e-13 on the thesis's data).
    o.function_tolerance = 1e-10;
    o.parameter_tolerance = 1e-12;
    o.gradient_tolerance = 1e-16;
    // The K_s–n and c–φ valleys are long and flat: let the trust region walk along them. (The
    // projected refinement, which has no such valleys, turns this off: identify.cpp, solveAll.)
    o.nonmonotonic_steps = true;
    return o;
}

double chiSquare(const FitProblem& problem, const std::vector<double>& u) {
    double cost = 0.0;
    if (!evaluateCost(problem.box(), u, cost)) return INFINITY;
    return 2.0 * cost;
}

ChannelResiduals channelResiduals(const ObservationModel& model, const ParameterVector& p,
                                  const std::vector<std::size_t>& samples) {
    ChannelResiduals out;
    std::array<std::vector<double>, kChannelCount> absolute;
    ChannelValues sum{};
    for (std::size_t i : samples) {
        const Prediction prediction = model.predict(i, p);
        if (!prediction.ok) continue;
        const auto active = model.channels(i);
        const Sample& s = model.sample(i);
        for (int c = 0; c < kChannelCount; ++c) {
            if (!active[c]) continue;
            const double measured = model.measured(i, static_cast<Channel>(c));
            const double r = prediction.values[c] - measured;
            sum[c] += r * r;
            ++out.count[c];
            absolute[c].push_back(std::abs(r));
            out.largest[c] = std::max(out.largest[c], std::abs(measured));
            out.residuals[c].push_back(
                {s.load_n.value_or(0.0), s.slip_angle_rad.value_or(0.0), s.slip, r});
        }
    }
    for (int c = 0; c < kChannelCount; ++c) {
        if (out.count[c] == 0) continue;
        out.rms[c] = std::sqrt(sum[c] / out.count[c]);
        auto middle = absolute[c].begin() + absolute[c].size() / 2;
        std::nth_element(absolute[c].begin(), middle, absolute[c].end());
        out.robust_std[c] = 1.4826 * *middle;
    }
    return out;
}

AtSolution analyseSolution(const Objective& objective, const std::vector<std::size_t>& samples,
                           const std::vector<double>& u, const std::vector<bool>& at_bound,
                           double covariance_scale, double correlation_flag,
                           double bound_correlation_flag) {
    AtSolution out;
    Uncertainty& unc = out.uncertainty;
    const ObservationModel& model = *objective.model;
    // JᵀJ of the data, each sample's rows weighted by the loss's ρ'(s), plus the priors.
    Eigen::Matrix<double, kP, kP> h = Eigen::Matrix<double, kP, kP>::Zero();
    Eigen::Matrix<double, kP, 1> g_all = Eigen::Matrix<double, kP, 1>::Zero();
    const SampleRows rows(objective, samples, u.data(), false);
    for (std::size_t t = 0; t < samples.size(); ++t) {
        const int m = model.residualCount(samples[t]);
        if (!rows.ok[t]) continue;
        const double* r = rows.r.data() + rows.first[t];
        const double* j = rows.j.data() + static_cast<std::size_t>(rows.first[t]) * kP;
        double weight = 1.0;
        if (objective.loss != Loss::kSquared) {
            double s = 0.0;
            for (int a = 0; a < m; ++a) s += r[a] * r[a];
            const double scale =
                objective.loss_scale > 0 ? objective.loss_scale : defaultLossScale(m);
            const std::unique_ptr<ceres::LossFunction> loss(makeLoss(objective.loss, scale));
            double rho[3];
            loss->Evaluate(s, rho);
            weight = rho[1];
        }
        const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, kP, Eigen::RowMajor>> jm(j, m,
                                                                                              kP);
        h += weight * jm.transpose() * jm;
        g_all += weight * jm.transpose() * Eigen::Map<const Eigen::VectorXd>(r, m);
    }
    const std::array<double, kP> physical = toPhysical(u.data());
    ParameterVector p;
    std::copy(physical.begin(), physical.end(), p.begin());
    const ParameterVector slope = physicalPerSolver(p);
    for (int k = 0; k < kP; ++k) {
        if (objective.priors[k] && !objective.fixed[k]) {
            const double d = slope[k] / objective.priors[k]->std;
            h(k, k) += d * d;
            g_all(k) += d * (p[k] - objective.priors[k]->mean) / objective.priors[k]->std;
        }
    }
    out.gradient.assign(g_all.data(), g_all.data() + kP);
    const std::vector<double>& gradient = out.gradient;
    std::vector<int> free;
    for (int k = 0; k < kP; ++k) {
        if (!objective.fixed[k]) free.push_back(k);
    }
    const int nf = static_cast<int>(free.size());
    unc.correlation = {};
    for (int k = 0; k < kP; ++k) unc.correlation[k][k] = 1.0;
    if (nf > 0) {
        Eigen::MatrixXd hf(nf, nf);
        for (int a = 0; a < nf; ++a) {
            for (int b = 0; b < nf; ++b) hf(a, b) = h(free[a], free[b]);
        }
        // Rank test on the scale-free (unit-diagonal) matrix.
        Eigen::VectorXd d = hf.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd normalised = d.asDiagonal() * hf * d.asDiagonal();
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(normalised);
        const double largest = eigen.eigenvalues().maxCoeff();
        if (eigen.eigenvalues().minCoeff() > 1e-12 * largest && largest > 0.0) {
            const Eigen::MatrixXd cov =
                d.asDiagonal() *
                (eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
                 eigen.eigenvectors().transpose()) *
                d.asDiagonal() * covariance_scale;
            unc.computed = true;
            for (int a = 0; a < nf; ++a) {
                unc.std[free[a]] = std::sqrt(std::max(0.0, cov(a, a))) * slope[free[a]];
                for (int b = 0; b < nf; ++b) {
                    const double denom = std::sqrt(cov(a, a) * cov(b, b));
                    unc.correlation[free[a]][free[b]] = denom > 0 ? cov(a, b) / denom : 0.0;
                }
            }
            // Newton decrement over the parameters not held on a bound.
            std::vector<int> moving;
            for (int a = 0; a < nf; ++a) {
                if (!at_bound[free[a]]) moving.push_back(free[a]);
            }
            if (!moving.empty()) {
                const int nm = static_cast<int>(moving.size());
                Eigen::MatrixXd hm(nm, nm);
                Eigen::VectorXd g(nm);
                for (int a = 0; a < nm; ++a) {
                    g(a) = gradient[moving[a]];
                    for (int b = 0; b < nm; ++b) hm(a, b) = h(moving[a], moving[b]);
                }
                out.newton_decrement = g.dot(hm.ldlt().solve(g));
            }
        }
    }
    if (!unc.computed && nf > 0) {
        unc.flags.push_back(
            "the data do not determine all free parameters (rank-deficient covariance): fix some, "
            "give priors, or add data at several loads");
    }
    if (unc.computed) {
        for (int a = 0; a < nf; ++a) {
            for (int b = a + 1; b < nf; ++b) {
                const double c = unc.correlation[free[a]][free[b]];
                if (std::abs(c) > correlation_flag) {
                    unc.flags.push_back(pairAdvice(free[a], free[b]).text + " (correlation " +
                                        formatNumber(roundSignificant(c, 4)) + ")");
                }
            }
        }
    }
    for (int k : free) {
        if (!at_bound[k]) continue;
        const std::string bounded = reference(static_cast<FullParameter>(k));
        unc.flags.push_back(bounded + " ended at its bound: not determined by the data");
        // The covariance is conditional on k held at its bound: a parameter that trades off with
        // k has compensated for it, and its standard deviation understates its error.
        if (!unc.computed) continue;
        for (int j2 : free) {
            if (j2 == k || std::abs(unc.correlation[k][j2]) < bound_correlation_flag) continue;
            unc.flags.push_back(reference(static_cast<FullParameter>(j2)) +
                                " is uncertain beyond its std: it trades off with " + bounded +
                                " (correlation " +
                                formatNumber(roundSignificant(unc.correlation[k][j2], 3)) +
                                "), which ended at its bound");
        }
    }
    return out;
}

namespace {

// The scaled Gauss–Newton step (pseudo-inverse below 1e-14 of the largest eigenvalue) of the
// parameters in `moving`, on the normal equations h, g; a parameter on its bound (side −1 lower,
// +1 upper) whose step leaves the box is dropped from `moving` and the step solved again without
// it. Returns the χ² the step removes by the Gauss–Newton model (0 when nothing moves).
double gaussNewtonStep(const Eigen::Matrix<double, kP, kP>& h,
                       const Eigen::Matrix<double, kP, 1>& g, const std::array<int, kP>& side,
                       std::vector<int>& moving, Eigen::VectorXd& step) {
    for (;;) {
        const int n = static_cast<int>(moving.size());
        if (n == 0) return 0.0;
        Eigen::MatrixXd hm(n, n);
        Eigen::VectorXd gm(n);
        for (int a = 0; a < n; ++a) {
            gm(a) = g(moving[a]);
            for (int b = 0; b < n; ++b) hm(a, b) = h(moving[a], moving[b]);
        }
        const Eigen::VectorXd d = hm.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(d.asDiagonal() * hm *
                                                                   d.asDiagonal());
        const Eigen::VectorXd values = eigen.eigenvalues();
        const double cutoff = 1e-14 * values.maxCoeff();
        Eigen::VectorXd inverse = values;
        for (int a = 0; a < n; ++a) inverse(a) = values(a) > cutoff ? 1.0 / values(a) : 0.0;
        step = -(d.asDiagonal() *
                 (eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose()) *
                 d.asDiagonal() * gm);
        std::vector<int> inside;
        for (int a = 0; a < n; ++a) {
            if (!(side[moving[a]] * step(a) > 0.0)) inside.push_back(moving[a]);
        }
        if (inside.size() == moving.size()) return -gm.dot(step);
        moving = std::move(inside);
    }
}

}  // namespace

int polish(const Objective& objective, const std::vector<std::size_t>& samples,
           std::vector<double>& u, int max_steps, double tolerance, double* remaining) {
    if (remaining) *remaining = INFINITY;
    const ObservationModel& model = *objective.model;
    const FitProblem problem(objective, samples);
    const ParameterVector lower = toSolver(objective.bounds.lower),
                          upper = toSolver(objective.bounds.upper);
    double chi2 = chiSquare(problem, u);
    int steps = 0;
    bool kinked = false;  // a step off a bound failed: parameters on a bound are held from then on
    for (; steps < max_steps && std::isfinite(chi2); ++steps) {
        Eigen::Matrix<double, kP, kP> h = Eigen::Matrix<double, kP, kP>::Zero();
        Eigen::Matrix<double, kP, 1> g = Eigen::Matrix<double, kP, 1>::Zero();
        const SampleRows rows(objective, samples, u.data(), true);
        for (std::size_t t = 0; t < samples.size(); ++t) {
            const int m = model.residualCount(samples[t]);
            if (!rows.ok[t]) return steps;
            const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, kP, Eigen::RowMajor>> jm(
                rows.j.data() + static_cast<std::size_t>(rows.first[t]) * kP, m, kP);
            const Eigen::Map<const Eigen::VectorXd> rm(rows.r.data() + rows.first[t], m);
            h += jm.transpose() * jm;
            g += jm.transpose() * rm;
        }
        const std::array<double, kP> physical = toPhysical(u.data());
        ParameterVector p;
        std::copy(physical.begin(), physical.end(), p.begin());
        const ParameterVector slope = physicalPerSolver(p);
        for (int k = 0; k < kP; ++k) {
            if (objective.priors[k] && !objective.fixed[k]) {
                const double w = slope[k] / objective.priors[k]->std;
                h(k, k) += w * w;
                g(k) += w * (p[k] - objective.priors[k]->mean) / objective.priors[k]->std;
            }
        }
        std::array<int, kP> side{};  // -1 on the lower bound, +1 on the upper, else 0
        for (int k = 0; k < kP; ++k) {
            const double margin = 1e-9 * (upper[k] - lower[k]);
            side[k] = u[k] <= lower[k] + margin ? -1 : (u[k] >= upper[k] - margin ? 1 : 0);
        }
        // First with the parameters on a bound that the gradient pulls inside; where the model
        // has a kink at that bound (a₀ = 0 at one load), its slope inside is not the gradient's
        // and the step fails: two trials (the full step and a thousandth of it, which a smooth
        // model would accept), then the step again with them held, for the rest of the call.
        bool improved = false, ended = false;
        for (const bool hold : {false, true}) {
            if (!hold && kinked) continue;
            std::vector<int> moving;
            for (int k = 0; k < kP; ++k) {
                const bool pushed_out = (side[k] < 0 && g(k) > 0) || (side[k] > 0 && g(k) < 0);
                if (!objective.fixed[k] && !pushed_out && !(hold && side[k] != 0))
                    moving.push_back(k);
            }
            Eigen::VectorXd step;
            const double predicted = gaussNewtonStep(h, g, side, moving, step);
            if (moving.empty() || !(predicted > tolerance)) {
                if (remaining) *remaining = 0.0;
                ended = true;
                break;
            }
            if (remaining) *remaining = predicted;
            bool off_bound = false;  // the step moves a parameter off its bound
            for (int k : moving) off_bound |= side[k] != 0;
            // u + t·step, clamped into the box.
            const auto along = [&](double t) {
                std::vector<double> at = u;
                for (std::size_t a = 0; a < moving.size(); ++a) {
                    const int k = moving[a];
                    at[k] = std::clamp(u[k] + t * step(static_cast<Eigen::Index>(a)), lower[k],
                                       upper[k]);
                }
                return at;
            };
            for (double t = 1.0; t > 1e-4 && !improved; t *= off_bound ? 1e-3 : 0.5) {
                std::vector<double> next = along(t);
                const double value = chiSquare(problem, next);
                if (value < chi2) {
                    // A full step that gained ρ = 1.2–1.9 times what the model predicted (the
                    // cost curves less along it than Gauss–Newton's model: the one-load valleys,
                    // where the steps otherwise shrink by ~0.6 each) is stretched to the minimum
                    // of the parabola through both ends and the slope, 1/(2 − ρ) of it, kept
                    // where that is lower (docs/identification.md §9, "seventh pass").
                    double best = value;
                    const double rho = (chi2 - value) / predicted;
                    if (t == 1.0 && rho >= 1.2 && rho <= 1.9) {
                        std::vector<double> far = along(1.0 / (2.0 - rho));
                        const double stretched = chiSquare(problem, far);
                        if (stretched < value) {
                            next = std::move(far);
                            best = stretched;
                        }
                    }
                    u = std::move(next);
                    chi2 = best;
                    improved = true;
                }
            }
            if (improved || !off_bound) break;
            kinked = true;
        }
        if (ended || !improved) break;
    }
    return steps;
}

}  // namespace terra::identification::detail
