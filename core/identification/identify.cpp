#include "core/identification/identify.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/random/mersenne_twister.hpp>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <thread>

#include "core/common/range.h"
#include "core/common/worker_pool.h"
#include "core/identification/fit_problem.h"
#include "core/identification/screening.h"

namespace terra::identification {
namespace {

using detail::BoxSummary;
using detail::FitProblem;
using detail::Objective;
using Clock = std::chrono::steady_clock;
constexpr int kP = kFullParameterCount;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

ParameterVector physicalOf(const std::vector<double>& u) {
    const std::array<double, kP> p = toPhysical(u.data());
    ParameterVector out;
    std::copy(p.begin(), p.end(), out.begin());
    return out;
}

std::vector<double> solverOf(const ParameterVector& p) {
    const ParameterVector u = toSolver(p);
    return {u.begin(), u.end()};
}

// `count` indices spread evenly over 0..n−1 (all of them when n ≤ count).
std::vector<std::size_t> spreadSubset(std::size_t n, int count) {
    if (count <= 0 || n <= static_cast<std::size_t>(count)) return detail::allSamples(n);
    std::vector<std::size_t> subset;
    for (int k = 0; k < count; ++k)
        subset.push_back(static_cast<std::size_t>(std::llround((n - 1.0) * k / (count - 1.0))));
    subset.erase(std::unique(subset.begin(), subset.end()), subset.end());
    return subset;
}

// A provisional noise level per channel before any fit: the given one, else 1 % of the channel's
// largest |value| (only the ratios between channels matter until the levels are estimated).
ChannelValues provisionalNoise(const ObservationModel& model, const ChannelValues& given) {
    ChannelValues sigma{};
    for (int c = 0; c < kChannelCount; ++c) {
        double largest = 0.0;
        for (std::size_t i = 0; i < model.size(); ++i) {
            if (model.channels(i)[c])
                largest = std::max(largest, std::abs(model.measured(i, static_cast<Channel>(c))));
        }
        sigma[c] = given[c] > 0 ? given[c] : std::max(0.01 * largest, 1e-12);
    }
    return sigma;
}

// Noise per channel from the residuals at p: RSS_c / (N_c − p N_c/N) (the free parameters' share
// of the degrees of freedom), or the robust 1.4826 median |r| for robust losses; floored at 1e-9
// of the channel's scale so that noise-free data keep finite weights.
ChannelValues estimatedNoise(const ObservationModel& model, const ParameterVector& p,
                             const std::vector<std::size_t>& samples, int free_parameters,
                             const ChannelValues& given, const ChannelValues& provisional,
                             bool robust) {
    const detail::ChannelResiduals res = detail::channelResiduals(model, p, samples);
    const int total = std::accumulate(res.count.begin(), res.count.end(), 0);
    ChannelValues sigma = provisional;
    for (int c = 0; c < kChannelCount; ++c) {
        if (given[c] > 0 || res.count[c] == 0) continue;
        const double share = static_cast<double>(free_parameters) * res.count[c] / total;
        const double dof = std::max(1.0, res.count[c] - share);
        const double level =
            robust ? res.robust_std[c] : res.rms[c] * std::sqrt(res.count[c] / dof);
        sigma[c] = std::max(level, 1e-7 * provisional[c]);
    }
    return sigma;
}

// Normalised distance of two estimates in solver coordinates (per design-box width).
double distance(const std::vector<double>& a, const std::vector<double>& b,
                const ParameterVector& width) {
    double d = 0.0;
    for (int k = 0; k < kP; ++k) d = std::max(d, std::abs(a[k] - b[k]) / width[k]);
    return d;
}

// The values parameters are held at: the options' `fixed`, and j_max at
// max_shear_deformation_m unless it is identified.
std::array<std::optional<double>, kP> heldValues(const IdentifyOptions& o) {
    std::array<std::optional<double>, kP> held = o.fixed;
    if (!o.fit_max_shear_deformation && !held[kJmax]) held[kJmax] = o.max_shear_deformation_m;
    return held;
}

struct Local {
    std::size_t start = 0;  // index into the report's starts
    std::vector<double> u;
    double subset_chi2 = 0.0;
    BoxSummary summary;
    bool coarse = false;  // its last refinement walked the Gauss rule alone
};

class Search {
public:
    Search(const DataSet& data, const wheel::WheelParameters& wheel, const IdentifyOptions& o,
           IdentificationReport& report)
        : data_(data), options_(o), report_(report), wheel_(wheel) {
        report_.setup = setupModel(data, o.source, o.load_n, o.max_shear_deformation_m,
                                   o.sinkage_exponent_slip, o.slip_sinkage_coefficient, o.model)
                            .value();
        fixed_ = heldValues(o);
        report_.setup.max_shear_deformation_free = !fixed_[kJmax].has_value();
        model_.emplace(data, wheel, report_.setup);
        objective_.model = &*model_;
        // The screening, the descents and (when the noise allows) the refinement's rounds walk
        // the Gauss rule alone (7 stresses per piece instead of 15, ≤ 3e-5 relative on these
        // data); the polish or a last solve on the default rule finishes every minimum
        // (docs/identification.md §9, "fourth pass").
        if (o.gauss_rule_search) {
            ModelSetup coarse = report_.setup;
            coarse.integration.gauss_only = true;
            coarse_model_.emplace(data, wheel, coarse);
        }
        // Threads for the projected problem (θ_f measured); from the load the observation model
        // warms its θ_f solves from the last one per sample, which threads would share.
        const int threads =
            o.threads > 0
                ? o.threads
                : static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
        if (threads > 1 && report_.setup.source == DataSource::kEntryAngle) {
            pool_.emplace(threads);
            objective_.pool = &*pool_;
        }
        provisional_ = provisionalNoise(*model_, o.noise);
        objective_.sigma = provisional_;
        objective_.priors = o.priors;
        objective_.loss = o.loss;
        objective_.loss_scale = o.loss_scale;
        objective_.bounds = o.bounds;
        for (int k = 0; k < kP; ++k) {
            objective_.fixed[k] = fixed_[k].has_value();
            if (!objective_.fixed[k]) ++free_;
        }
        all_ = detail::allSamples(model_->size());
        subset_ = spreadSubset(model_->size(), o.subset_samples);
        screening_ = spreadSubset(model_->size(), o.screening_samples);
        const ParameterVector lo = toSolver(o.design.lower), hi = toSolver(o.design.upper);
        for (int k = 0; k < kP; ++k) width_[k] = hi[k] - lo[k];
        threshold_ =
            o.ambiguity_delta_chi2 > 0
                ? o.ambiguity_delta_chi2
                : boost::math::quantile(boost::math::chi_squared(std::max(free_, 1)), 0.99);
        report_.ambiguity_delta_chi2 = threshold_;
        report_.free_parameters = free_;
    }

    void run() {
        const auto begin = Clock::now();
        screen();
        report_.timing.screening_ms = millisecondsSince(begin);
        if (cancelled_) return finish();
        const auto descent = Clock::now();
        descend();
        report_.timing.descent_ms = millisecondsSince(descent);
        if (cancelled_ || locals_.empty()) return finish();
        const auto refinement = Clock::now();
        refine();
        report_.timing.refinement_ms = millisecondsSince(refinement);
        finish();
    }

private:
    bool progress(double fraction) {
        if (options_.progress && !options_.progress(fraction)) cancelled_ = true;
        return !cancelled_;
    }

    // Applies held values and the bounds to a start.
    ParameterVector admissible(ParameterVector p) const {
        for (int k = 0; k < kP; ++k) {
            p[k] = fixed_[k] ? *fixed_[k]
                             : std::clamp(p[k], options_.bounds.lower[k], options_.bounds.upper[k]);
        }
        return p;
    }

    void screen() {
        const bool projected = report_.setup.source == DataSource::kEntryAngle;
        std::array<bool, kP> vary{};
        for (int k = 0; k < kP; ++k) {
            const bool linear = k == kKs || k == kC || k == kPhi;
            vary[k] = !objective_.fixed[k] && !(projected && linear);
        }
        ParameterVector middle{};
        const ParameterVector lo = toSolver(options_.design.lower),
                              hi = toSolver(options_.design.upper);
        for (int k = 0; k < kP; ++k) middle[k] = 0.5 * (lo[k] + hi[k]);
        const ParameterVector base = admissible(physicalOf({middle.begin(), middle.end()}));
        std::vector<Start> starts = options_.starts;
        const std::vector<ParameterVector> design = detail::haltonDesign(
            options_.design_points, vary, options_.design, base, options_.seed);
        for (std::size_t d = 0; d < design.size(); ++d)
            starts.push_back({"design " + std::to_string(d + 1), design[d]});
        // The starts are shared among the pool's threads (each projection on its 12 samples in
        // one thread), 8 at a time between progress reports (as before there were threads).
        const Objective coarse = coarseObjective();
        Objective serial = coarse;
        serial.pool = nullptr;
        const detail::LinearProjection projection(serial, screening_, wheel_);
        const FitProblem screening_problem(coarse, screening_);
        std::vector<StartReport> screened(starts.size());
        const auto screenPart = [&](std::size_t begin, std::size_t end) {
            for (std::size_t s = begin; s < end; ++s) {
                StartReport& r = screened[s];
                r.label = starts[s].label;
                r.start = admissible(starts[s].parameters);
                ParameterVector p = r.start;
                r.screening_cost = projected ? projection.project(p)
                                             : detail::chiSquare(screening_problem, solverOf(p));
                r.end = p;
            }
        };
        constexpr std::size_t kBlock = 8;
        for (std::size_t first = 0; first < starts.size(); first += kBlock) {
            const std::size_t count = std::min(kBlock, starts.size() - first);
            const auto block = [&](std::size_t begin, std::size_t end) {
                screenPart(first + begin, first + end);
            };
            if (projected && objective_.pool) {
                objective_.pool->forEach(count, block);
            } else {
                block(0, count);
            }
            for (std::size_t s = first; s < first + count; ++s)
                report_.starts.push_back(screened[s]);
            if (!progress(0.3 * static_cast<double>(first + count) / starts.size())) return;
        }
    }

    void descend() {
        std::vector<std::size_t> order(report_.starts.size());
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
            return report_.starts[a].screening_cost < report_.starts[b].screening_cost;
        });
        // The best screened starts, skipping near-duplicates of one already taken.
        std::vector<std::size_t> chosen;
        for (std::size_t s : order) {
            if (static_cast<int>(chosen.size()) >= options_.descents) break;
            if (!std::isfinite(report_.starts[s].screening_cost)) break;
            const std::vector<double> u = solverOf(report_.starts[s].end);
            bool near = false;
            for (std::size_t c : chosen)
                near |= distance(u, solverOf(report_.starts[c].end), width_) < 0.05;
            if (!near) chosen.push_back(s);
        }
        // With θ_f measured the descent walks (a₀, a₁, n, K) of the projected problem (the linear
        // parameters follow in closed form); from the load it walks all seven.
        const Objective coarse = coarseObjective();
        const FitProblem subset_problem(coarse, subset_);
        const detail::LinearProjection projection(coarse, subset_, wheel_);
        const std::unique_ptr<ceres::CostFunction> projected_cost(projection.costFunction());
        detail::BoxProblem projected_box = subset_problem.box();
        projected_box.costs = {projected_cost.get()};
        projected_box.losses = {nullptr};
        for (int k : {kKs, kC, kPhi}) projected_box.fixed[k] = true;
        // A descent that comes within 0.01 of the design box (the distinct-minimum distance
        // below) of a minimum an earlier descent found has entered its basin: it ends there and
        // adds no minimum (the distinct filter would merge it). At one load every descent tends to
        // meet one minimum, after 20 iterations each. Compared on the walked coordinates (with θ_f
        // measured, K_s, c and φ stand still during the projected descent).
        detail::BoxOptions descent_options = detail::descentOptions();
        descent_options.bound_shortcuts = projectable();
        descent_options.stop = [this](const std::vector<double>& u, double,
                                      const detail::BoxProblem&) {
            return inBasinOfOne(u, locals_, locals_.size());
        };
        for (std::size_t c = 0; c < chosen.size(); ++c) {
            StartReport& r = report_.starts[chosen[c]];
            Local local;
            local.start = chosen[c];
            local.u = solverOf(r.end);
            local.summary = detail::solveInBox(projectable() ? projected_box : subset_problem.box(),
                                               local.u, descent_options);
            if (local.summary.stopped) {
                local.summary.termination = "STOPPED: in the basin of a minimum found before";
            }
            if (projectable()) {
                ParameterVector p = physicalOf(local.u);
                projection.project(p);
                local.u = solverOf(p);
                local.summary.cost = 0.5 * detail::chiSquare(subset_problem, local.u);
            }
            r.descended = true;
            r.end = physicalOf(local.u);
            r.iterations = local.summary.iterations;
            r.termination = local.summary.termination;
            local.subset_chi2 = 2.0 * local.summary.cost;
            r.chi2 = local.subset_chi2;
            // A descent stopped in a found minimum's basin adds no minimum.
            if (local.summary.usable && !local.summary.stopped) locals_.push_back(local);
            if (!progress(0.3 + 0.3 * (c + 1.0) / chosen.size())) return;
        }
        std::sort(locals_.begin(), locals_.end(),
                  [](const Local& a, const Local& b) { return a.subset_chi2 < b.subset_chi2; });
        // One per distinct minimum.
        std::vector<Local> distinct;
        for (const Local& l : locals_) {
            bool same = false;
            for (const Local& d : distinct) same |= distance(l.u, d.u, width_) < 0.01;
            if (!same) distinct.push_back(l);
        }
        locals_ = std::move(distinct);
    }

    // Whether the solver walks parameter k: free, and not K_s, c or φ of a projected solve.
    bool walked(int k) const {
        return !objective_.fixed[k] && !(projectable() && (k == kKs || k == kC || k == kPhi));
    }

    // The distance of u from v on the walked coordinates: the largest |u − v| in units of the
    // design box.
    double walkedDistance(const std::vector<double>& u, const std::vector<double>& v) const {
        double d = 0.0;
        for (int k = 0; k < kP; ++k) {
            if (walked(k)) d = std::max(d, std::abs(u[k] - v[k]) / width_[k]);
        }
        return d;
    }

    // Whether u is within 0.01 of the design box (the distinct-minimum distance) of one of the
    // first `count` of `found`, on the coordinates the solver walks (with θ_f measured, K_s, c
    // and φ stand still during a projected solve): in its basin.
    bool inBasinOfOne(const std::vector<double>& u, const std::vector<Local>& found,
                      std::size_t count) const {
        for (std::size_t j = 0; j < count; ++j) {
            if (walkedDistance(u, found[j].u) < 0.01) return true;
        }
        return false;
    }

    // Whether one of the first `count` minima of `found` lies downhill of u (at `cost` on `box`;
    // detail::downhillTo): then the solve from u would end at that minimum, as inBasinOfOne says
    // only within 0.01 of the design box (sandy loam on A, one load, j_max identified, seed 5:
    // two refinements of 17 and 29 iterations ended there). Tried within kDownhillRadius of the
    // design box of a minimum (the max norm of inBasinOfOne), and again once the distance has
    // fallen below kDownhillShrink of the last tried (`tested`) or kRetest steps later (`since`),
    // both kept per minimum: three evaluations a try, a handful of tries a solve. The minima's
    // costs are those solveFrom gives them, on the full objective with these levels: on a
    // projected solve at least the box's at the same point (their K_s, c, φ projected with
    // earlier levels), erring toward fewer stops. Ridges below kRidge in cost do not count (0.05
    // of χ²: the height of a point 0.22 std from a minimum along one direction): minima they part
    // are one to the data, and a minimum refined under levels estimated since lies a little off
    // the new levels' minimum (0.007 of χ² measured).
    static constexpr double kDownhillRadius = 0.12;
    static constexpr double kDownhillShrink = 0.7;
    static constexpr double kRidge = 0.025;
    static constexpr int kRetest = 5;
    bool downhillToOne(const std::vector<double>& u, double cost, const detail::BoxProblem& box,
                       const std::vector<Local>& found, std::size_t count,
                       std::vector<double>& tested, std::vector<int>& since) const {
        if (count == 0) return false;
        tested.resize(count, kInfinity);
        since.resize(count, 0);
        std::vector<bool> walked_now(kP);
        for (int k = 0; k < kP; ++k) walked_now[k] = walked(k);
        for (std::size_t j = 0; j < count; ++j) {
            const Local& m = found[j];
            ++since[j];
            if (!m.summary.usable || !(m.summary.cost < cost)) continue;
            const double d = walkedDistance(u, m.u);
            if (!(d < kDownhillRadius && (d <= kDownhillShrink * tested[j] || since[j] >= kRetest)))
                continue;
            tested[j] = d;
            since[j] = 0;
            if (detail::downhillTo(box, u, cost, m.u, m.summary.cost, walked_now, kRidge))
                return true;
        }
        return false;
    }

    // The objective on the Gauss rule alone (coarse_model_; the objective itself without
    // IdentifyOptions::gauss_rule_search).
    Objective coarseObjective() const {
        Objective coarse = objective_;
        if (coarse_model_) coarse.model = &*coarse_model_;
        return coarse;
    }

    // The χ² that the polish must still remove to take a step: 1e-6, far below the noise; after
    // rounds on the Gauss rule, relative to χ² when it is below 1 (down to 1e-15): noise-free
    // data of the model end at χ² ~ 1e-20 on the default rule, from ~1e-8 on the Gauss rule.
    static double polishTolerance(bool coarse, const Local& l) {
        return coarse ? 1e-6 * std::clamp(2.0 * l.summary.cost, 1e-9, 1.0) : 1e-6;
    }

    // Whether a refinement round may walk the Gauss rule alone: at p its predictions differ from
    // the default rule's by at most a tenth of the noise levels on every sample of the subset and
    // every channel, so that its minimum is within about a tenth of a std of the objective's and
    // the default rule finishes it in a step or two. Not on noise-free data, whose levels fall
    // below the Gauss rule's ~1e-5 (relative) difference.
    bool gaussRuleSuffices(const ParameterVector& p, const ChannelValues& sigma) const {
        if (!coarse_model_) return false;
        for (std::size_t i : subset_) {
            const Prediction exact = model_->predict(i, p), gauss = coarse_model_->predict(i, p);
            if (!exact.ok || !gauss.ok) return false;
            const std::array<bool, kChannelCount> channels = model_->channels(i);
            for (int c = 0; c < kChannelCount; ++c) {
                if (channels[c] && !(std::abs(exact.values[c] - gauss.values[c]) <= 0.1 * sigma[c]))
                    return false;
            }
        }
        return true;
    }

    // Refines on all samples the subset minimum that fits all samples best, and the others
    // within three times the ambiguity threshold of it (they might be ambiguous on all data); χ²
    // in the noise levels that the best subset minimum's residuals show. All samples, not the
    // subset, rank them: a subset may hold few samples of a load that decides.
    void refine() {
        Objective scaled = objective_;
        scaled.sigma =
            estimatedNoise(*model_, physicalOf(locals_[0].u), subset_, free_, options_.noise,
                           provisional_, options_.loss != Loss::kSquared);
        const FitProblem all_problem(scaled, all_);
        std::vector<std::pair<double, std::size_t>> ranked;
        for (std::size_t j = 0; j < locals_.size(); ++j)
            ranked.push_back({detail::chiSquare(all_problem, locals_[j].u), j});
        std::sort(ranked.begin(), ranked.end());
        std::vector<Local> refined;
        for (const auto& [chi2, j] : ranked) {
            if (refined.size() >= 3 || !std::isfinite(chi2)) break;
            if (refined.empty() || chi2 - ranked[0].first <= 3.0 * threshold_)
                refined.push_back(locals_[j]);
        }
        if (refined.empty()) refined.push_back(locals_[0]);
        // With estimated noise: fit with the levels the subset's best minimum shows, estimate them
        // again from the best fit on all samples, and fit again while they still move by more
        // than 10 % (once or twice). The rounds walk the first minimum alone; the others are
        // refined once, with the levels the rounds settled on (refining them in every round
        // repeated their work: sandy loam on A, one load, j_max identified, seed 6: 9.5 of 41 ms;
        // docs/identification.md §9, "ninth pass"). When one of them fits better than the first,
        // the levels are estimated again at it and, if they moved by 10 % or more, every minimum
        // is refined once more.
        const bool estimate = std::any_of(options_.noise.begin(), options_.noise.end(),
                                          [](double s) { return !(s > 0); });
        if (estimate) objective_.sigma = scaled.sigma;
        // Solves refined[first..] with the current levels, on the Gauss rule alone when it
        // suffices at the best start (checked with these levels: they may shrink); a refinement
        // that enters the basin of a minimum refined before it ends there and is dropped: it would
        // meet that minimum (sandy loam on A, one load, j_max identified: three starts refined to
        // one minimum, 57 + 20 + 15 iterations). The minima before `first`, refined with earlier
        // levels, get their cost again with these (on the same rule), so that all compare. Then
        // sorted, best first, and starts that met merged: the polish would only repeat the same
        // work on them (they are merged below anyway).
        const auto solveFrom = [&](std::size_t first) {
            const bool coarse = gaussRuleSuffices(physicalOf(refined[0].u), objective_.sigma);
            const Objective objective = coarse ? coarseObjective() : objective_;
            if (first > 0) {
                const FitProblem problem(objective, all_);
                for (std::size_t j = 0; j < first; ++j) {
                    double cost = 0.0;
                    if (refined[j].summary.usable &&
                        detail::evaluateCost(problem.box(), refined[j].u, cost))
                        refined[j].summary.cost = cost;
                }
            }
            for (std::size_t j = first; j < refined.size(); ++j) {
                // Per earlier minimum: the distance of the last downhill test, the steps since.
                const auto stop = [this, &refined, j, tested = std::vector<double>(),
                                   since = std::vector<int>()](
                                      const std::vector<double>& u, double cost,
                                      const detail::BoxProblem& box) mutable {
                    return inBasinOfOne(u, refined, j) ||
                           downhillToOne(u, cost, box, refined, j, tested, since);
                };
                solveAll(refined[j], objective, stop);
                refined[j].coarse = coarse;
                if (cancelled_) return;
                if (refined[j].summary.stopped) refined.erase(refined.begin() + j--);
            }
            std::sort(refined.begin(), refined.end(), [](const Local& a, const Local& b) {
                return a.summary.usable && (!b.summary.usable || a.summary.cost < b.summary.cost);
            });
            mergeMet(refined);
        };
        // The levels at the best minimum, stored; returns how far they moved. With squares and
        // no prior, the minimum depends on the ratios of the levels only (a common factor scales
        // χ², not its minimiser): what counts is how far those ratios move. Otherwise (priors,
        // robust losses) the levels themselves.
        const auto estimateLevels = [&] {
            const ChannelValues sigma =
                estimatedNoise(*model_, physicalOf(refined[0].u), all_, free_, options_.noise,
                               provisional_, options_.loss != Loss::kSquared);
            double change = 0.0;
            if (scaleFree()) {
                double low = kInfinity, high = 0.0;
                for (int c = 0; c < kChannelCount; ++c) {
                    if (!report_.setup.channels[c]) continue;
                    low = std::min(low, sigma[c] / objective_.sigma[c]);
                    high = std::max(high, sigma[c] / objective_.sigma[c]);
                }
                change = high > 0.0 ? high / low - 1.0 : 0.0;
            } else {
                for (int c = 0; c < kChannelCount; ++c)
                    change = std::max(change, std::abs(sigma[c] / objective_.sigma[c] - 1.0));
            }
            objective_.sigma = sigma;
            return change;
        };
        constexpr int kRounds = 3;
        if (!estimate) {
            solveFrom(0);
        } else {
            // The rounds on the first minimum alone (the others wait in `waiting`).
            std::vector<Local> waiting(refined.begin() + 1, refined.end());
            refined.resize(1);
            for (int round = 0; round < kRounds; ++round) {
                solveFrom(0);
                if (cancelled_) return;
                if (!progress(0.6 + 0.35 * (round + 1.0) / (kRounds + 1)) || estimateLevels() < 0.1)
                    break;
            }
            if (cancelled_) return;
            // The others ranked again by the rule that chose them (within three times the
            // threshold), now with the settled levels: one chosen with the subset's levels may lie
            // far above with these (sandy loam on B, one load, j_max identified, seed 5: 24
            // iterations to a minimum 61 of χ² above the best). Against the refined best, which is
            // stricter than the first ranking against the unrefined one: a minimum that would
            // refine into the threshold from more than three times it above is lost (none in the
            // 144 matrix cells: the three dropped there were not ambiguous).
            if (!waiting.empty()) {
                const FitProblem problem(objective_, all_);
                const double best_chi2 = detail::chiSquare(problem, refined[0].u);
                std::erase_if(waiting, [&](const Local& w) {
                    return !(detail::chiSquare(problem, w.u) - best_chi2 <= 3.0 * threshold_);
                });
            }
            if (!waiting.empty()) {
                const std::size_t best = refined[0].start;
                refined.insert(refined.end(), waiting.begin(), waiting.end());
                solveFrom(1);
                if (cancelled_) return;
                if (refined[0].start != best && estimateLevels() >= 0.1) {
                    solveFrom(0);
                    if (cancelled_) return;
                    estimateLevels();
                }
            }
        }
        if (!progress(0.95)) return;
        // Rounds that walked the Gauss rule alone end within about a tenth of a std of the
        // objective's minimum: with squares, the Gauss–Newton polish below finishes each on the
        // default rule (one or two steps); with a robust loss, or where the rounds ended short of
        // a minimum (the iteration budget), the solver on the default rule.
        for (Local& l : refined) {
            if (l.coarse && (options_.loss != Loss::kSquared || !l.summary.converged))
                solveOnDefaultRule(l);
        }
        // χ² of the full seven-parameter objective at each minimum, with the final noise levels,
        // after Gauss–Newton polishing where the damped solver stopped short (the best one's
        // gradient comes with its covariance).
        const FitProblem problem(objective_, all_);
        for (Local& l : refined) {
            if (options_.loss == Loss::kSquared && l.summary.usable) {
                double remaining = 0.0;
                l.summary.iterations += detail::polish(objective_, all_, l.u, 4,
                                                       polishTolerance(l.coarse, l), &remaining);
                if (l.coarse && remaining > 0.01) {
                    // The polish left more than 0.01 of χ² (a tenth of a std along one
                    // direction) of what the Gauss rule left (a failed line search or row, or
                    // four steps): the solver on the default rule finishes, then the polish as
                    // without the Gauss rule. (In the flat one-load valleys four steps, some
                    // stretched, end ~2e-5 above the minimum, 3e-4 without the stretch: not
                    // worth the solver's ~10 ms.)
                    solveOnDefaultRule(l);
                    if (l.summary.usable)
                        l.summary.iterations +=
                            detail::polish(objective_, all_, l.u, 4, polishTolerance(false, l));
                }
            }
            double cost = 0.0;
            l.summary.usable = l.summary.usable && detail::evaluateCost(problem.box(), l.u, cost);
            l.summary.cost = cost;
        }
        std::sort(refined.begin(), refined.end(), [](const Local& a, const Local& b) {
            return a.summary.usable && (!b.summary.usable || a.summary.cost < b.summary.cost);
        });
        mergeMet(refined);
        report_.noise_estimated = estimate;
        for (Local& l : refined) {
            StartReport& r = report_.starts[l.start];
            r.refined = true;
            r.end = physicalOf(l.u);
            r.chi2 = 2.0 * l.summary.cost;
            r.iterations += l.summary.iterations;
            r.termination = l.summary.termination;
        }
        locals_ = std::move(refined);
    }

    // Starts that met on all samples are one minimum: keeps the first (the best, `refined` being
    // sorted) of those within 1e-3 of the design box of each other, or, as distinctMinima, apart
    // in j_max only with one cost (to 1e-9 of it: j_max wanders on the plateau beyond the shear
    // deformations the data reach).
    void mergeMet(std::vector<Local>& refined) const {
        const auto same = [this](const Local& a, const Local& b) {
            if (distance(a.u, b.u, width_) < 1e-3) return true;
            std::vector<double> a_rest = a.u, b_rest = b.u;
            a_rest[kJmax] = b_rest[kJmax] = 0.0;
            return distance(a_rest, b_rest, width_) < 1e-3 &&
                   std::abs(a.summary.cost - b.summary.cost) <=
                       1e-9 * std::max({std::abs(a.summary.cost), std::abs(b.summary.cost), 1.0});
        };
        std::vector<Local> distinct;
        for (const Local& l : refined) {
            bool met = false;
            for (const Local& d : distinct) met |= same(l, d);
            if (!met) distinct.push_back(l);
        }
        refined = std::move(distinct);
    }

    // Whether the minimiser is unchanged by a common factor on the noise levels: squares and no
    // prior on a free parameter.
    bool scaleFree() const {
        if (options_.loss != Loss::kSquared) return false;
        for (int k = 0; k < kP; ++k) {
            if (objective_.priors[k] && !objective_.fixed[k]) return false;
        }
        return true;
    }

    // Whether the projected problem is the same objective as the full one: θ_f measured, squares,
    // no prior on φ (priors on K_s and c are rows of the projection).
    bool projectable() const {
        return report_.setup.source == DataSource::kEntryAngle && options_.loss == Loss::kSquared &&
               !(options_.priors[kPhi] && !objective_.fixed[kPhi]);
    }

    // The last solve of a minimum that rounds on the Gauss rule left: on the default rule, its
    // iterations added to theirs.
    void solveOnDefaultRule(Local& l) {
        const int before = l.summary.iterations;
        solveAll(l, objective_);
        l.summary.iterations += before;
    }

    // Refines one minimum on all samples: on the projected problem (four parameters walked, the
    // valleys of K_s–n and c–φ gone) when it is the same objective, else on all seven.
    void solveAll(Local& l, const Objective& objective,
                  decltype(detail::BoxOptions::stop) stop = {}) {
        // The gradient is computed afterwards, at the polished minimum.
        detail::BoxOptions options = detail::refinementOptions();
        options.gradient = false;
        options.stop = std::move(stop);
        // The box solver's shortcuts (box_solver.h) on the projected problem only: from the load
        // (seven parameters, θ_f solved in every residual) they cost more passes than they save
        // (three loads, 1 % noise: 101 → 182 ms measured).
        options.bound_shortcuts = projectable();
        // Gauss–Newton crawls along the one-load valleys, each step ~0.55 of the one before:
        // extrapolated to the limit (box_solver.h; docs/identification.md §9, "eleventh pass").
        options.extrapolate = projectable();
        if (!projectable()) {
            const FitProblem problem(objective, all_);
            l.summary = detail::solveInBox(problem.box(), l.u, options);
            return;
        }
        // Monotonic steps on the projected problem: non-monotonic ones let the trust region walk
        // the long K_s–n and c–φ valleys of the seven-parameter problem, which the projection
        // removes; on the four or five parameters walked here they can cycle, a step up accepted
        // and then the step back (docs/identification.md §9, "eighth pass").
        options.nonmonotonic_steps = false;
        const FitProblem problem(objective, all_);
        const detail::LinearProjection projection(objective, all_, wheel_);
        const std::unique_ptr<ceres::CostFunction> cost(projection.costFunction());
        detail::BoxProblem box = problem.box();
        box.costs = {cost.get()};
        box.losses = {nullptr};
        for (int k : {kKs, kC, kPhi}) box.fixed[k] = true;
        l.summary = detail::solveInBox(box, l.u, options);
        ParameterVector p = physicalOf(l.u);
        projection.project(p);
        l.u = solverOf(p);
    }

    void finish() {
        if (cancelled_) {
            report_.status = IdentifyStatus::kCancelled;
            report_.message = "cancelled";
        }
        if (locals_.empty() || !locals_[0].summary.usable) {
            if (!cancelled_) {
                report_.status = IdentifyStatus::kFailed;
                report_.message = "no start gave a usable fit";
            }
            return;
        }
        const Local& best = locals_[0];
        const auto covariance = Clock::now();
        const FitProblem problem(objective_, all_);
        const BoxSummary& summary = best.summary;
        report_.parameters = physicalOf(best.u);
        report_.chi2 = 2.0 * summary.cost;
        report_.residuals = problem.dataResiduals();
        report_.noise = objective_.sigma;
        report_.iterations = summary.iterations;
        report_.termination = summary.termination;
        const ParameterVector lower = toSolver(options_.bounds.lower),
                              upper = toSolver(options_.bounds.upper);
        for (int k = 0; k < kP; ++k) {
            const double margin = 1e-9 * (upper[k] - lower[k]);
            report_.at_bound[k] = !objective_.fixed[k] && (best.u[k] <= lower[k] + margin ||
                                                           best.u[k] >= upper[k] - margin);
        }
        const int dof = std::max(1, report_.residuals - free_);
        double scale = report_.noise_estimated ? report_.chi2 / dof : 1.0;
        // Estimated levels come from the unwhitened residuals, which hold the scatter of
        // uncertain slips that the whitening carries again (docs/identification.md §8, "An
        // uncertain slip"): χ² then falls below its degrees of freedom for that reason alone, and
        // does not shrink the covariance.
        if (report_.noise_estimated && std::any_of(all_.begin(), all_.end(), [this](std::size_t i) {
                const std::optional<double> slip_std = model_->sample(i).slip_std;
                return slip_std && *slip_std > 0.0;
            }))
            scale = std::max(scale, 1.0);
        std::vector<bool> at_bound(report_.at_bound.begin(), report_.at_bound.end());
        const detail::AtSolution at = detail::analyseSolution(
            objective_, all_, best.u, at_bound, scale, options_.correlation_flag, 0.5);
        report_.gradient_norm = detail::projectedGradientNorm(problem.box(), best.u, at.gradient);
        report_.uncertainty = at.uncertainty;
        report_.newton_decrement = at.newton_decrement;
        const detail::ChannelResiduals residuals =
            detail::channelResiduals(*model_, report_.parameters, all_);
        report_.rms = residuals.rms;
        flagInterpolation();
        checkAdequacy(residuals);
        report_.timing.covariance_ms = millisecondsSince(covariance);
        // Every refined minimum, and the ambiguous ones: within the threshold and distinct (some
        // parameter more than three std away, or 1 % when the std is unknown).
        for (const Local& l : locals_) {
            Minimum m;
            m.parameters = physicalOf(l.u);
            m.chi2 = 2.0 * l.summary.cost;
            m.delta_chi2 = m.chi2 - report_.chi2;
            m.label = report_.starts[l.start].label;
            if (&l == &best) m.std = report_.uncertainty.std;
            report_.minima.push_back(m);
            if (&l == &best || !l.summary.usable || m.delta_chi2 > threshold_) continue;
            bool distinct = false;
            for (int k = 0; k < kP; ++k) {
                const double d = std::abs(m.parameters[k] - report_.parameters[k]);
                const double scale_k =
                    report_.uncertainty.computed && report_.uncertainty.std[k] > 0
                        ? 3.0 * report_.uncertainty.std[k]
                        : 0.01 * std::max(std::abs(report_.parameters[k]), 1e-9);
                distinct |= d > scale_k;
            }
            if (distinct) report_.ambiguity.push_back(m);
        }
        // Starts that met the same other minimum (refined apart, within rounding) are one.
        report_.ambiguity = distinctMinima(report_.ambiguity);
        for (int k = 0; k < kP; ++k) {
            if (!options_.priors[k] || objective_.fixed[k]) continue;
            PriorComparison& c = report_.prior[k];
            c.active = true;
            c.prior_mean = options_.priors[k]->mean;
            c.prior_std = options_.priors[k]->std;
            c.posterior_mean = report_.parameters[k];
            c.posterior_std = report_.uncertainty.computed ? report_.uncertainty.std[k] : 0.0;
            c.shift_in_prior_std = (c.posterior_mean - c.prior_mean) / c.prior_std;
            c.std_ratio = c.posterior_std / c.prior_std;
        }
        if (!cancelled_) {
            report_.status =
                summary.converged ? IdentifyStatus::kConverged : IdentifyStatus::kNotConverged;
            report_.message = summary.termination;
        }
    }

    // A channel whose noise is estimated from no more values than free parameters can be fitted
    // exactly: the estimate then follows the residuals down and the weight up, round after round.
    // Whether it happened is seen in the residuals: below 0.1 % of the channel's largest value
    // (a tenth of the provisional level), finer than any wheel test measures (the shared sheet's
    // readings are good to a few %, a load cell to 0.1 % of its range); a channel that the others
    // keep from its points (six drawbar pulls beside two sinkages, 3 N RMS) is not flagged.
    void flagInterpolation() {
        report_.channel_values = measuredValueCounts(data_, report_.setup);
        for (int c = 0; c < kChannelCount; ++c) {
            const int count = report_.channel_values[c];
            if (count == 0 || options_.noise[c] > 0 || count > free_) continue;
            if (!(report_.rms[c] <= 0.1 * provisional_[c])) continue;
            report_.interpolated[c] = true;
            report_.uncertainty.flags.push_back(
                std::string(channelNames()[c]) + ": " + std::to_string(count) +
                " measured values for " + std::to_string(free_) +
                " free parameters with its noise estimated: the fit passes through every one "
                "(RMS residual " +
                formatNumber(roundSignificant(report_.rms[c], 3)) +
                "), so its estimated noise and its residuals mean nothing; give its noise level "
                "or measure it at more points");
        }
    }

    // The trend test per channel; residuals at rounding level (noise-free data of the model
    // itself: below 1e-9 of the channel's largest value) are no misfit and are not tested.
    void checkAdequacy(const detail::ChannelResiduals& residuals) {
        AdequacyReport& a = report_.adequacy;
        for (int c = 0; c < kChannelCount; ++c) {
            if (residuals.count[c] == 0 || residuals.rms[c] <= 1e-9 * residuals.largest[c])
                continue;
            const TrendTest t = trendTest(residuals.residuals[c]);
            a.trend[c] = t;
            if (!t.tested()) continue;
            a.p = std::min(a.p, t.p);
            if (t.p >= options_.adequacy_p) continue;
            a.flag = true;
            report_.uncertainty.flags.push_back(
                std::string("the ") + channelNames()[c] +
                " residuals follow slip: a cubic trend per sweep holds " +
                formatNumber(roundSignificant(100.0 * t.trend_share, 2)) +
                " % of them (F = " + formatNumber(roundSignificant(t.f, 3)) +
                ", p = " + formatNumber(roundSignificant(t.p, 2)) +
                "): the misfit is systematic, the model misses something the data have (a shear "
                "limit j_max?), so the estimate is biased and its std understate its error");
        }
    }

    const DataSet& data_;
    const IdentifyOptions& options_;
    std::array<std::optional<double>, kP> fixed_{};
    IdentificationReport& report_;
    wheel::WheelParameters wheel_;
    std::optional<ObservationModel> model_;
    std::optional<ObservationModel> coarse_model_;  // the Gauss rule alone (IntegrationOptions)
    std::optional<WorkerPool> pool_;                // IdentifyOptions::threads > 1, θ_f measured
    Objective objective_;
    ChannelValues provisional_{};
    int free_ = 0;
    std::vector<std::size_t> all_, subset_, screening_;
    ParameterVector width_{};
    double threshold_ = 0.0;
    std::vector<Local> locals_;
    bool cancelled_ = false;
};

DataSet pick(const DataSet& data, const std::vector<std::size_t>& indices) {
    DataSet out;
    out.columns = data.columns;
    for (std::size_t i : indices) out.samples.push_back(data.samples[i]);
    return out;
}

void holdout(const DataSet& data, const wheel::WheelParameters& wheel,
             const IdentifyOptions& options, IdentificationReport& report) {
    const std::size_t n = data.samples.size();
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    boost::random::mt19937_64 engine(options.seed);
    for (std::size_t i = n - 1; i > 0; --i) std::swap(order[i], order[engine() % (i + 1)]);
    const int folds = options.folds >= 2 ? options.folds : 1;
    const std::size_t held_count =
        folds == 1
            ? std::clamp<std::size_t>(
                  static_cast<std::size_t>(std::llround(options.holdout_fraction * n)), 1, n - 1)
            : 0;
    IdentifyOptions inner = options;
    inner.holdout_fraction = 0.0;
    inner.folds = 0;
    inner.progress = nullptr;
    HoldoutReport& h = report.holdout;
    h.folds = folds;
    h.channels = report.setup.channels;
    ChannelValues sum{};
    std::array<int, kChannelCount> count{};
    for (int f = 0; f < folds; ++f) {
        std::vector<std::size_t> train, test;
        for (std::size_t r = 0; r < n; ++r) {
            const bool held = folds == 1 ? r < held_count : static_cast<int>(r % folds) == f;
            (held ? test : train).push_back(order[r]);
        }
        std::sort(train.begin(), train.end());
        std::sort(test.begin(), test.end());
        const IdentificationReport fit = identify(pick(data, train), wheel, inner);
        if (!fit.usable()) {
            h.failed += test.size();
            continue;
        }
        const DataSet held = pick(data, test);
        const std::vector<Prediction> predictions = predictAll(held, wheel, fit.parameters, inner);
        const ObservationModel model(
            held, wheel,
            setupModel(held, report.setup.source, options.load_n, options.max_shear_deformation_m,
                       options.sinkage_exponent_slip, options.slip_sinkage_coefficient,
                       options.model)
                .value());
        for (std::size_t i = 0; i < held.samples.size(); ++i) {
            if (!predictions[i].ok) {
                ++h.failed;
                continue;
            }
            ++h.samples;
            const auto active = model.channels(i);
            for (int c = 0; c < kChannelCount; ++c) {
                if (!active[c] || !h.channels[c]) continue;
                const double e =
                    predictions[i].values[c] - model.measured(i, static_cast<Channel>(c));
                sum[c] += e * e;
                ++count[c];
            }
        }
        if (options.progress && !options.progress(0.95 + 0.05 * (f + 1.0) / folds)) break;
    }
    for (int c = 0; c < kChannelCount; ++c) {
        if (count[c] == 0) continue;
        h.rms[c] = std::sqrt(sum[c] / count[c]);
        h.rms_in_fit[c] = report.rms[c];
        h.rms_over_noise[c] = h.rms[c] / report.noise[c];
    }
    h.computed = h.samples > 0;
}

// Whether a fit with j_max free determined it: a covariance, j_max inside its bounds, and its
// std below half its value (a limit the data reach; beyond the largest shear deformation they
// reach, the fit is flat in j_max and its std grows without bound).
bool shearLimitSeen(const IdentificationReport& r) {
    return r.uncertainty.computed && !r.at_bound[kJmax] && std::isfinite(r.parameters[kJmax]) &&
           r.uncertainty.std[kJmax] < 0.5 * r.parameters[kJmax];
}

}  // namespace

std::vector<Issue> validate(const DataSet& data, const wheel::WheelParameters& wheel,
                            const IdentifyOptions& o) {
    std::vector<Issue> issues = wheel::validate(wheel);
    const auto& info = parameterInfo();
    for (int c = 0; c < kChannelCount; ++c) {
        checkRange(issues, std::string("noise.") + channelNames()[c], o.noise[c], {0.0, 1e9});
    }
    for (int k = 0; k < kP; ++k) {
        const std::string name = info[k].name;
        const double to_user = info[k].to_user;
        if (!(o.bounds.lower[k] < o.bounds.upper[k])) {
            issues.push_back({"bounds." + name, "lower " +
                                                    formatNumber(o.bounds.lower[k] * to_user) +
                                                    " must be below upper " +
                                                    formatNumber(o.bounds.upper[k] * to_user)});
        }
        if (o.fixed[k] && k == kJmax) {
            if (!(*o.fixed[k] > 0.0)) {  // +inf: no limit
                issues.push_back({"fix.jmax_m", "= " + formatNumber(*o.fixed[k]) +
                                                    " m is not a length > 0 (+inf: no limit)"});
            }
        } else if (o.fixed[k]) {
            checkRange(issues, "fix." + name, *o.fixed[k] * to_user,
                       {o.bounds.lower[k] * to_user, o.bounds.upper[k] * to_user}, info[k].unit);
        }
        if (o.priors[k]) {
            checkRange(issues, "prior." + name + ".mean", o.priors[k]->mean * to_user,
                       {-1e12, 1e12}, info[k].unit);
            checkRange(issues, "prior." + name + ".std", o.priors[k]->std * to_user,
                       {0.0, 1e12, true, false}, info[k].unit);
        }
    }
    if (o.fit_max_shear_deformation && o.fixed[kJmax]) {
        issues.push_back({"fix.jmax_m", "j_max is both held (fixed) and identified: choose one"});
    }
    if (!o.fit_max_shear_deformation && !(o.max_shear_deformation_m > 0.0)) {
        issues.push_back(
            {"max_shear_deformation_m", "= " + formatNumber(o.max_shear_deformation_m) +
                                            " m is not a length > 0 (+inf: no limit)"});
    }
    for (int k : {kKs, kK, kJmax}) {
        if (!(o.bounds.lower[k] > 0)) {
            issues.push_back(
                {std::string("bounds.") + info[k].name, "the lower bound must be > 0"});
        }
        if (!(o.design.lower[k] > 0)) {
            issues.push_back(
                {std::string("design.") + info[k].name, "the lower bound must be > 0"});
        }
    }
    for (const Start& start : o.starts) {
        for (int k = 0; k < kP; ++k) {
            // j_max = +inf is a start without a limit (a soil without one).
            if (!std::isfinite(start.parameters[k]) &&
                !(k == kJmax && start.parameters[k] == kInfinity)) {
                issues.push_back({"starts." + start.label + "." + info[k].name,
                                  "= " + formatNumber(start.parameters[k]) + " is not finite"});
            }
        }
    }
    checkRange(issues, "design_points", o.design_points, {0, 100000});
    checkRange(issues, "descents", o.descents, {1, 1000});
    checkRange(issues, "threads", o.threads, {0, IdentifyOptions::kMaxThreads});
    checkRange(issues, "subset_samples", o.subset_samples, {0, 1e9});
    checkRange(issues, "screening_samples", o.screening_samples, {0, 1e9});
    checkRange(issues, "loss_scale", o.loss_scale, {0.0, 1e6});
    checkRange(issues, "ambiguity_delta_chi2", o.ambiguity_delta_chi2, {0.0, 1e12});
    checkRange(issues, "holdout_fraction", o.holdout_fraction, {0.0, 1.0, false, true});
    if (o.folds != 0) {
        checkRange(issues, "folds", o.folds, {2, std::max(2.0, data.samples.size() / 2.0)});
    }
    if (o.folds != 0 && o.holdout_fraction > 0) {
        issues.push_back({"holdout", "give a holdout fraction or a number of folds, not both"});
    }
    const Result<ModelSetup> setup =
        setupModel(data, o.source, o.load_n, o.max_shear_deformation_m, o.sinkage_exponent_slip,
                   o.slip_sinkage_coefficient, o.model);
    if (!setup) {
        const std::vector<Issue>& more = setup.issues();
        issues.insert(issues.end(), more.begin(), more.end());
    } else {
        // Fewer residuals than free parameters leave a family of exact fits: any "estimate" is
        // one of them, picked by the start, and its covariance does not exist. A prior on a free
        // parameter is one residual more.
        const std::array<int, kChannelCount> counts = measuredValueCounts(data, setup.value());
        const int residuals = std::accumulate(counts.begin(), counts.end(), 0);
        int free = 0, priors = 0;
        const std::array<std::optional<double>, kP> held = heldValues(o);
        for (int k = 0; k < kP; ++k) {
            if (held[k]) continue;
            ++free;
            priors += o.priors[k] ? 1 : 0;
        }
        if (residuals + priors < free) {
            issues.push_back(
                {"data", std::to_string(residuals) + " measured values (" +
                             std::to_string(data.samples.size()) +
                             (data.samples.size() == 1 ? " sample) " : " samples) ") +
                             (priors > 0 ? "and " + std::to_string(priors) + " priors " : "") +
                             "for " + std::to_string(free) +
                             " free parameters: the data cannot determine them; add samples, "
                             "hold parameters fixed or give priors"});
        }
    }
    return issues;
}

std::array<int, kChannelCount> measuredValueCounts(const DataSet& data, const ModelSetup& setup) {
    // As ObservationModel::channels: the setup's channels, less a sinkage the row does not have.
    std::array<int, kChannelCount> counts{};
    for (const Sample& s : data.samples) {
        for (int c = 0; c < kChannelCount; ++c) {
            if (setup.channels[c] && (c != kSinkageChannel || s.sinkage_m.has_value())) ++counts[c];
        }
    }
    return counts;
}

IdentificationReport identify(const DataSet& data, const wheel::WheelParameters& wheel,
                              const IdentifyOptions& options) {
    const auto begin = Clock::now();
    wheel::requireValid(wheel);
    IdentificationReport report;
    report.issues = validate(data, wheel, options);
    if (!report.issues.empty()) {
        report.status = IdentifyStatus::kInvalidInput;
        report.message = formatIssues(report.issues);
        return report;
    }
    Search(data, wheel, options, report).run();
    IdentifyOptions with_prior = options;
    if (report.usable() && options.fit_max_shear_deformation && !options.priors[kJmax] &&
        !shearLimitSeen(report)) {
        // The data do not determine j_max (a limit beyond every shear deformation they reach
        // changes nothing, and near it the fit is flat): the estimate is then the prior's.
        const ParameterVector unseen = report.parameters;
        with_prior.priors[kJmax] = kDefaultShearLimitPrior;
        const IdentifyTiming first = report.timing;
        report = IdentificationReport{};
        Search(data, wheel, with_prior, report).run();
        report.timing.screening_ms += first.screening_ms;
        report.timing.descent_ms += first.descent_ms;
        report.timing.refinement_ms += first.refinement_ms;
        report.timing.covariance_ms += first.covariance_ms;
        report.shear_limit_prior = true;
        const std::string jmax = reference(kJmax);
        report.uncertainty.flags.push_back(
            "the data do not determine " + jmax + " (without a prior it ended at " +
            formatNumber(roundSignificant(unseen[kJmax] * 1e3, 3)) +
            " mm, unresolved): estimated with the prior " +
            formatNumber(kDefaultShearLimitPrior.mean * 1e3) + " ± " +
            formatNumber(kDefaultShearLimitPrior.std * 1e3) + " mm (give a prior of your own on " +
            jmax + ", or hold it at a value)");
    }
    if (report.usable() && (options.holdout_fraction > 0 || options.folds >= 2)) {
        const auto start = Clock::now();
        holdout(data, wheel, with_prior, report);
        report.timing.holdout_ms = millisecondsSince(start);
    }
    report.timing.total_ms = millisecondsSince(begin);
    return report;
}

double relativeDistance(const ParameterVector& a, const ParameterVector& b) {
    const DesignBox box;
    double d = 0.0;
    for (int k = 0; k < kP; ++k) {
        if (a[k] == b[k]) continue;
        const double floor = (k == kA0 || k == kA1 || k == kC) ? box.upper[k] - box.lower[k] : 0.0;
        const double scale = std::max({std::abs(a[k]), std::abs(b[k]), floor});
        d = std::max(d,
                     std::isfinite(scale) && scale > 0 ? std::abs(a[k] - b[k]) / scale : kInfinity);
    }
    return d;
}

std::vector<Minimum> distinctMinima(const std::vector<Minimum>& minima, double tolerance) {
    // Two minima that differ only in j_max and have one χ² (to 1e-9 of it) are one: a limit beyond
    // every shear deformation the data reach changes nothing, so j_max wanders on that plateau.
    const auto same = [tolerance](const Minimum& a, const Minimum& b) {
        if (relativeDistance(a.parameters, b.parameters) <= tolerance) return true;
        ParameterVector a_rest = a.parameters, b_rest = b.parameters;
        a_rest[kJmax] = b_rest[kJmax] = 0.0;
        return relativeDistance(a_rest, b_rest) <= tolerance &&
               std::abs(a.chi2 - b.chi2) <=
                   1e-9 * std::max({std::abs(a.chi2), std::abs(b.chi2), 1.0});
    };
    std::vector<Minimum> out;
    for (const Minimum& m : minima) {
        bool seen = false;
        for (const Minimum& kept : out) seen |= same(m, kept);
        if (!seen) out.push_back(m);
    }
    return out;
}

std::vector<Prediction> predictAll(const DataSet& data, const wheel::WheelParameters& wheel,
                                   const ParameterVector& p, const IdentifyOptions& options) {
    const Result<ModelSetup> setup =
        setupModel(data, options.source, options.load_n, options.max_shear_deformation_m,
                   options.sinkage_exponent_slip, options.slip_sinkage_coefficient, options.model);
    if (!setup) throw std::invalid_argument(setup.message());
    const ObservationModel model(data, wheel, setup.value());
    std::vector<Prediction> out;
    for (std::size_t i = 0; i < model.size(); ++i) out.push_back(model.predict(i, p));
    return out;
}

std::vector<Start> startsFromSoils(const std::vector<soil::SoilParameters>& soils,
                                   const wheel::WheelParameters& wheel) {
    std::vector<Start> starts;
    for (const soil::SoilParameters& s : soils) starts.push_back({s.name, fromSoil(s, wheel)});
    return starts;
}

}  // namespace terra::identification
