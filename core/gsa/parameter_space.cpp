#include "core/gsa/parameter_space.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"

namespace terra::gsa {
namespace {

using boost::math::complement;
using boost::math::normal;

const normal kStandardNormal(0.0, 1.0);

// A truncation is refused when it keeps less than this probability: Φ(b) − Φ(a) would lose all
// its digits.
constexpr double kMinimumMass = 1e-10;
// Covariance symmetry is checked to this fraction of the largest entry (a posterior written with
// 15 digits is symmetric to ~1e-15 relative).
constexpr double kSymmetryTolerance = 1e-9;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
    throw std::invalid_argument("parameters." + name + ": " + what);
}

bool upperTail(const Normal& n) { return (n.low - n.mean) / n.sd > 0.0; }

}  // namespace

void ParameterSpace::addName(const std::string& name) {
    if (name.empty()) throw std::invalid_argument("parameters: a parameter needs a name");
    if (find(name) != dimension()) fail(name, "given twice");
    names_.push_back(name);
}

void ParameterSpace::add(const std::string& name, const Marginal& marginal) {
    Entry entry{marginal};
    if (const auto* u = std::get_if<Uniform>(&marginal)) {
        if (!std::isfinite(u->low) || !std::isfinite(u->high)) {
            fail(name, "uniform range [" + formatNumber(u->low) + ", " + formatNumber(u->high) +
                           "] must be finite");
        }
        if (!(u->low < u->high)) {
            fail(name, "uniform range low = " + formatNumber(u->low) +
                           " must be below high = " + formatNumber(u->high));
        }
    } else {
        const Normal& n = std::get<Normal>(marginal);
        if (!std::isfinite(n.mean)) fail(name, "normal mean = " + formatNumber(n.mean));
        if (!(n.sd > 0.0) || !std::isfinite(n.sd)) {
            fail(name, "normal sd = " + formatNumber(n.sd) + " must be > 0 and finite");
        }
        if (std::isnan(n.low) || std::isnan(n.high) || !(n.low < n.high)) {
            fail(name, "truncation [" + formatNumber(n.low) + ", " + formatNumber(n.high) +
                           "] must have low < high");
        }
        // Upper-tail truncations work with the survival function Q = 1 − Φ, which keeps its
        // digits there.
        if (upperTail(n)) {
            entry.cdf_low = cdf(complement(kStandardNormal, (n.low - n.mean) / n.sd));
            entry.cdf_high = std::isinf(n.high)
                                 ? 0.0
                                 : cdf(complement(kStandardNormal, (n.high - n.mean) / n.sd));
        } else {
            entry.cdf_low = std::isinf(n.low) ? 0.0 : cdf(kStandardNormal, (n.low - n.mean) / n.sd);
            entry.cdf_high =
                std::isinf(n.high) ? 1.0 : cdf(kStandardNormal, (n.high - n.mean) / n.sd);
        }
        if (!(std::abs(entry.cdf_high - entry.cdf_low) >= kMinimumMass)) {
            fail(name, "the truncation [" + formatNumber(n.low) + ", " + formatNumber(n.high) +
                           "] keeps almost none of N(" + formatNumber(n.mean) + ", " +
                           formatNumber(n.sd) + "²)");
        }
    }
    addName(name);
    entries_.push_back(entry);
}

void ParameterSpace::addMultivariateNormal(const std::vector<std::string>& names,
                                           const Eigen::VectorXd& mean,
                                           const Eigen::MatrixXd& covariance) {
    const std::string label = names.empty() ? std::string("(group)") : names.front();
    const auto k = static_cast<Eigen::Index>(names.size());
    if (names.empty()) throw std::invalid_argument("parameters: an empty multivariate group");
    if (mean.size() != k || covariance.rows() != k || covariance.cols() != k) {
        fail(label, "multivariate normal of " + std::to_string(k) + " parameters needs a mean of " +
                        std::to_string(k) + " values and a " + std::to_string(k) + "×" +
                        std::to_string(k) + " covariance, got " + std::to_string(mean.size()) +
                        " and " + std::to_string(covariance.rows()) + "×" +
                        std::to_string(covariance.cols()));
    }
    if (!mean.allFinite() || !covariance.allFinite()) {
        fail(label, "multivariate normal mean and covariance must be finite");
    }
    const double scale = covariance.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < k; ++i) {
        for (Eigen::Index j = 0; j < i; ++j) {
            if (std::abs(covariance(i, j) - covariance(j, i)) > kSymmetryTolerance * scale) {
                fail(names[i], "covariance is not symmetric: (" + names[i] + ", " + names[j] +
                                   ") = " + formatNumber(covariance(i, j)) + " but (" + names[j] +
                                   ", " + names[i] + ") = " + formatNumber(covariance(j, i)));
            }
        }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
    if (llt.info() != Eigen::Success) {
        fail(label,
             "covariance is not positive definite (a fixed or perfectly correlated "
             "parameter: leave it out of the group)");
    }
    // Names first: a duplicate leaves the space unchanged.
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (find(names[i]) != dimension() ||
            std::find(names.begin(), names.begin() + i, names[i]) != names.begin() + i) {
            fail(names[i], "given twice");
        }
    }
    Group group{dimension(), mean, llt.matrixL()};
    for (const std::string& name : names) {
        addName(name);
        Entry entry{Normal{}};
        entry.group = static_cast<int>(groups_.size());
        entries_.push_back(entry);
    }
    groups_.push_back(std::move(group));
}

std::size_t ParameterSpace::find(const std::string& name) const {
    const auto it = std::find(names_.begin(), names_.end(), name);
    return static_cast<std::size_t>(it - names_.begin());
}

const Marginal* ParameterSpace::marginal(std::size_t i) const {
    return entries_.at(i).group < 0 ? &entries_[i].marginal : nullptr;
}

bool ParameterSpace::allUniform() const {
    return std::all_of(entries_.begin(), entries_.end(), [](const Entry& e) {
        return e.group < 0 && std::holds_alternative<Uniform>(e.marginal);
    });
}

void ParameterSpace::transform(std::span<const double> u, std::span<double> x) const {
    const std::size_t d = dimension();
    if (u.size() != d || x.size() != d) {
        throw std::invalid_argument("ParameterSpace::transform: " + std::to_string(d) +
                                    " parameters, got " + std::to_string(u.size()) + " → " +
                                    std::to_string(x.size()) + " values");
    }
    for (std::size_t i = 0; i < d; ++i) {
        const Entry& e = entries_[i];
        if (e.group >= 0) continue;
        if (const auto* uni = std::get_if<Uniform>(&e.marginal)) {
            x[i] = uni->low + u[i] * (uni->high - uni->low);
            continue;
        }
        const Normal& n = std::get<Normal>(e.marginal);
        const double p = e.cdf_low + u[i] * (e.cdf_high - e.cdf_low);
        const double z =
            upperTail(n) ? quantile(complement(kStandardNormal, p)) : quantile(kStandardNormal, p);
        x[i] = std::clamp(n.mean + n.sd * z, n.low, n.high);
    }
    for (const Group& g : groups_) {
        const auto k = g.mean.size();
        Eigen::VectorXd z(k);
        for (Eigen::Index j = 0; j < k; ++j) z[j] = quantile(kStandardNormal, u[g.first + j]);
        const Eigen::VectorXd value = g.mean + g.cholesky.triangularView<Eigen::Lower>() * z;
        for (Eigen::Index j = 0; j < k; ++j) x[g.first + j] = value[j];
    }
}

}  // namespace terra::gsa
