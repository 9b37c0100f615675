#include "core/gsa/sobol_indices.h"

#include <algorithm>
#include <atomic>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <thread>

#include "core/common/range.h"
#include "core/gsa/resample.h"

namespace terra::gsa {
namespace {

// An output whose standard deviation is below this fraction of its mean has no variance to
// apportion: F_z with the load given equals W to ~1e-12.
constexpr double kConstantOutput = 1e-9;

void requireShape(const SaltelliDesign& design, const Eigen::MatrixXd& values, const Mask& ok) {
    const auto rows = static_cast<Eigen::Index>(design.rows());
    if (values.rows() != rows) {
        throw std::invalid_argument("Sobol' estimator: " + std::to_string(values.rows()) +
                                    " output rows, the design has " + std::to_string(rows));
    }
    if (design.baseSamples() > (std::size_t{1} << 32)) {
        throw std::invalid_argument("Sobol' estimator: at most 2^32 base samples");
    }
    if (ok.size() != 0 && (ok.rows() != values.rows() || ok.cols() != values.cols())) {
        throw std::invalid_argument("Sobol' estimator: the success mask is " +
                                    std::to_string(ok.rows()) + "×" + std::to_string(ok.cols()) +
                                    ", the outputs " + std::to_string(values.rows()) + "×" +
                                    std::to_string(values.cols()));
    }
}

// Per-sample terms of the estimators for one column, centred on the mean of the A and B outputs
// (which leaves every estimator unchanged in expectation and removes the cancellation of a large
// mean): a = f_A − m, b = f_B − m, p_i = b (f_ABi − f_A), q_i = (f_A − f_ABi)². One contiguous row
// of w = 4 + 2d values per sample, [a, a², b, b², p_1…p_d, q_1…q_d], so that a bootstrap
// replicate is a sum of gathered rows.
struct Terms {
    std::size_t d = 0, w = 0;
    std::vector<double> rows;

    const double* row(std::size_t k) const { return &rows[k * w]; }
};

void accumulate(const double* row, std::size_t w, double* sums) {
    for (std::size_t x = 0; x < w; ++x) sums[x] += row[x];
}

// S_i and S_Ti from the sums over M samples; the variance is that of the 2M A and B outputs.
void indices(const double* sums, std::size_t d, double m, double* first, double* total) {
    const double n = 2.0 * m;
    const double mean = (sums[0] + sums[2]) / n;
    const double variance = (sums[1] + sums[3]) / n - mean * mean;
    for (std::size_t i = 0; i < d; ++i) {
        first[i] = variance > 0.0 ? sums[4 + i] / m / variance : 0.0;
        total[i] = variance > 0.0 ? sums[4 + d + i] / (2.0 * m) / variance : 0.0;
    }
}

// Everything for output column c; writes only column c of `out` (and `constant`).
void estimateColumn(const SaltelliDesign& design, const Eigen::MatrixXd& values, const Mask& ok,
                    const BootstrapOptions& options, double z, Eigen::Index c, SobolIndices& out,
                    bool& constant) {
    const std::size_t d = design.parameters(), n = design.baseSamples();
    const std::size_t per = design.rowsPerSample();
    Terms t{d, 4 + 2 * d, {}};
    std::vector<double> first(d), total(d), boot_first, boot_total;
    auto y = [&](std::size_t j, std::size_t kind) {
        return values(static_cast<Eigen::Index>(j * per + kind), c);
    };
    std::vector<std::size_t> kept;
    for (std::size_t j = 0; j < n; ++j) {
        bool usable = true;
        for (std::size_t k = 0; k < per && usable; ++k) {
            usable = ok.size() == 0 || ok(static_cast<Eigen::Index>(j * per + k), c);
        }
        if (!usable) continue;
        for (std::size_t k = 0; k < per; ++k) {
            if (!std::isfinite(y(j, k))) {
                throw std::invalid_argument("Sobol' estimator: output column " + std::to_string(c) +
                                            ", row " + std::to_string(j * per + k) + " = " +
                                            formatNumber(y(j, k)) +
                                            " is not finite (mark failed evaluations in the mask)");
            }
        }
        kept.push_back(j);
    }
    const std::size_t m = kept.size();
    out.samples_used[static_cast<std::size_t>(c)] = m;
    if (m < 2) return;
    double mean = 0.0;
    for (std::size_t j : kept) mean += y(j, 0) + y(j, 1);
    mean /= 2.0 * m;
    t.rows.resize(m * t.w);
    for (std::size_t k = 0; k < m; ++k) {
        const std::size_t j = kept[k];
        double* row = &t.rows[k * t.w];
        const double a = y(j, 0) - mean, b = y(j, 1) - mean;
        row[0] = a, row[1] = a * a, row[2] = b, row[3] = b * b;
        for (std::size_t i = 0; i < d; ++i) {
            const double step = y(j, 2 + i) - y(j, 0);
            row[4 + i] = b * step;
            row[4 + d + i] = step * step;
        }
    }
    std::vector<double> all(t.w, 0.0), sums(t.w);
    for (std::size_t k = 0; k < m; ++k) accumulate(t.row(k), t.w, all.data());
    const double variance =
        (all[1] + all[3]) / (2.0 * m) - std::pow((all[0] + all[2]) / (2.0 * m), 2);
    out.mean[c] = mean + (all[0] + all[2]) / (2.0 * m);
    out.variance[c] = variance;
    if (!(std::sqrt(std::max(variance, 0.0)) > kConstantOutput * std::abs(out.mean[c]))) {
        constant = true;
        return;
    }
    indices(all.data(), d, static_cast<double>(m), first.data(), total.data());
    for (std::size_t i = 0; i < d; ++i) {
        out.first_order(static_cast<Eigen::Index>(i), c) = first[i];
        out.total(static_cast<Eigen::Index>(i), c) = total[i];
    }
    if (options.resamples == 0) return;
    // Every column draws the same resamples (the same seed): columns with the same usable
    // samples are bootstrapped consistently.
    Resampler resampler(options.seed);
    const auto b_count = static_cast<std::size_t>(options.resamples);
    boot_first.assign(b_count * d, 0.0), boot_total.assign(b_count * d, 0.0);
    for (std::size_t b = 0; b < b_count; ++b) {
        std::fill(sums.begin(), sums.end(), 0.0);
        for (std::size_t k = 0; k < m; ++k) {
            accumulate(t.row(resampler.index(m)), t.w, sums.data());
        }
        indices(sums.data(), d, static_cast<double>(m), &boot_first[b * d], &boot_total[b * d]);
    }
    for (std::size_t i = 0; i < d; ++i) {
        out.first_order_conf(static_cast<Eigen::Index>(i), c) =
            z * standardDeviation(boot_first, i, d);
        out.total_conf(static_cast<Eigen::Index>(i), c) = z * standardDeviation(boot_total, i, d);
    }
}

}  // namespace

void requireValid(const BootstrapOptions& options) {
    std::vector<Issue> issues;
    checkRange(issues, "bootstrap.resamples", options.resamples, {0.0, 1e6});
    checkRange(issues, "bootstrap.confidence_level", options.confidence_level,
               {0.0, 1.0, true, true});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

SobolIndices estimateSobol(const SaltelliDesign& design, const Eigen::MatrixXd& values,
                           const Mask& ok, const BootstrapOptions& options) {
    requireValid(options);
    requireShape(design, values, ok);
    const auto columns = values.cols();
    const auto pd = static_cast<Eigen::Index>(design.parameters());
    SobolIndices out;
    out.first_order = out.total = out.first_order_conf = out.total_conf =
        Eigen::MatrixXd::Zero(pd, columns);
    out.mean = out.variance = Eigen::VectorXd::Zero(columns);
    out.samples_used.assign(static_cast<std::size_t>(columns), 0);
    const double z = options.resamples > 0 ? quantile(boost::math::normal(0.0, 1.0),
                                                      0.5 + 0.5 * options.confidence_level)
                                           : 0.0;
    // Columns are independent: threads take them from a counter and write only their own column
    // (std::vector<bool> packs bits, so the flags go through a byte per column).
    const auto count = static_cast<std::size_t>(columns);
    std::vector<char> constant(count, 0);
    std::vector<std::exception_ptr> failures(count);
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t c = next++; c < count; c = next++) {
            try {
                bool flag = false;
                estimateColumn(design, values, ok, options, z, static_cast<Eigen::Index>(c), out,
                               flag);
                constant[c] = flag;
            } catch (...) {
                failures[c] = std::current_exception();
            }
        }
    };
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers = std::max<std::size_t>(
        1, std::min<std::size_t>(count, options.threads > 0 ? options.threads : hardware));
    {
        std::vector<std::jthread> pool;
        for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
        work();
    }
    // The first failing column's error, whatever the thread that met it.
    for (const std::exception_ptr& failure : failures) {
        if (failure) std::rethrow_exception(failure);
    }
    out.constant.assign(constant.begin(), constant.end());
    return out;
}

}  // namespace terra::gsa
