#include "core/gsa/uncertainty_bands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/units.h"

namespace terra::gsa {
namespace {

std::size_t checkedDimension(const ParameterSpace& space) {
    if (space.dimension() == 0) throw std::invalid_argument("parameters: no parameter to vary");
    return space.dimension();
}

std::string percentName(double q) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", q);
    return text;
}

}  // namespace

BandSample::BandSample(ParameterSpace space, std::size_t samples, std::uint64_t seed)
    : space_(std::move(space)), samples_(samples), sequence_(checkedDimension(space_), seed) {
    if (samples < 2) {
        throw std::invalid_argument("samples = " + std::to_string(samples) +
                                    " is outside the allowed range [2, inf)");
    }
}

Eigen::MatrixXd BandSample::rows(std::size_t begin, std::size_t end) const {
    if (begin > end || end > samples_) {
        throw std::out_of_range("samples [" + std::to_string(begin) + ", " + std::to_string(end) +
                                ") outside [0, " + std::to_string(samples_) + ")");
    }
    const std::size_t d = space_.dimension();
    std::vector<double> u((end - begin) * d), x(d);
    sequence_.generate(begin, end - begin, u);
    Eigen::MatrixXd out(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(d));
    for (std::size_t r = 0; r < end - begin; ++r) {
        space_.transform(std::span<const double>(&u[r * d], d), x);
        for (std::size_t i = 0; i < d; ++i) {
            out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(i)) = x[i];
        }
    }
    return out;
}

void requireValid(const BandOptions& options) {
    std::vector<Issue> issues;
    checkRange(issues, "samples", static_cast<double>(options.samples), {2.0, 1e12});
    if (options.percentiles.empty()) issues.push_back({"percentiles", "no percentile asked"});
    for (double q : options.percentiles) checkRange(issues, "percentiles", q, {0.0, 100.0}, "%");
    checkRange(issues, "max_failed_fraction", options.max_failed_fraction, {0.0, 1.0});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

double percentile(std::span<const double> sorted, double q) {
    if (sorted.empty()) throw std::invalid_argument("percentile of no values");
    const double h = (static_cast<double>(sorted.size()) - 1.0) * q / 100.0;
    const auto lo = static_cast<std::size_t>(std::floor(h));
    if (lo + 1 >= sorted.size()) return sorted.back();
    return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[lo + 1] - sorted[lo]);
}

BandResult uncertaintyBands(const WheelStudy& study, const BandOptions& options,
                            const RunControl& control) {
    requireValid(options);
    const WheelTarget target(study);
    const BandSample sample(study.parameters, options.samples, options.seed);
    const TargetValues values = evaluateInChunks(
        target, sample.rows(), kChunkEvaluations / target.points(), 1,
        [&](std::size_t begin, std::size_t end) { return sample.rows(begin, end); }, control);
    return bandResult(target, sample, values, options);
}

BandResult bandResult(const WheelTarget& target, const BandSample& sample,
                      const TargetValues& values, const BandOptions& options) {
    requireValid(options);
    const auto rows = static_cast<Eigen::Index>(sample.rows());
    const auto points = static_cast<Eigen::Index>(target.points());
    if (values.values.rows() != rows || values.status.rows() != rows ||
        values.values.cols() != static_cast<Eigen::Index>(target.columns()) ||
        values.status.cols() != points) {
        throw std::invalid_argument("band outputs do not match the sample (" +
                                    std::to_string(values.values.rows()) + " rows for " +
                                    std::to_string(rows) + " samples)");
    }
    const WheelStudy& study = target.study();
    BandResult out;
    out.outputs = study.outputs;
    out.grid = study.grid;
    out.percentiles = options.percentiles;
    out.failures = target.failures(values);
    out.used.assign(static_cast<std::size_t>(points), 0);
    const auto ok = static_cast<std::uint8_t>(SampleStatus::kOk);
    const auto skipped = static_cast<std::uint8_t>(SampleStatus::kNotEvaluated);
    std::vector<std::size_t> evaluated(static_cast<std::size_t>(points), 0);
    bool cancelled = false;
    for (Eigen::Index p = 0; p < points; ++p) {
        for (Eigen::Index r = 0; r < rows; ++r) {
            const std::uint8_t s = values.status(r, p);
            if (s == skipped) {
                cancelled = true;
                continue;
            }
            ++evaluated[p];
            if (s == ok) ++out.used[p];
        }
    }
    for (Eigen::Index p = 0; p < points; ++p) {
        const std::size_t failed = evaluated[p] - out.used[p];
        if (evaluated[p] == 0 ||
            static_cast<double>(failed) <= options.max_failed_fraction * evaluated[p]) {
            continue;
        }
        char share[32];
        std::snprintf(share, sizeof share, "%.3g %%", 100.0 * failed / evaluated[p]);
        out.message +=
            (out.message.empty() ? "" : "; ") + std::string("s = ") +
            formatNumber(out.grid.slip(p)) +
            ", β = " + formatNumber(roundSignificant(units::radToDeg(out.grid.slipAngle(p)))) +
            "°: " + std::to_string(failed) + " of " + std::to_string(evaluated[p]) + " samples (" +
            share + ") failed";
    }
    if (!out.message.empty()) {
        out.status = StudyStatus::kTooManyFailures;
        char limit[32];
        std::snprintf(limit, sizeof limit, "%.3g %%", 100.0 * options.max_failed_fraction);
        out.message += "; above max_failed_fraction = " + std::string(limit);
        return out;
    }
    const auto q_count = static_cast<Eigen::Index>(options.percentiles.size());
    const auto o_count = static_cast<Eigen::Index>(study.outputs.size());
    out.mean = Eigen::MatrixXd::Zero(o_count, points);
    std::vector<double> column;
    for (Eigen::Index o = 0; o < o_count; ++o) {
        Eigen::MatrixXd band = Eigen::MatrixXd::Zero(q_count, points);
        for (Eigen::Index p = 0; p < points; ++p) {
            column.clear();
            for (Eigen::Index r = 0; r < rows; ++r) {
                if (values.status(r, p) == ok) column.push_back(values.values(r, o * points + p));
            }
            if (column.empty()) continue;
            std::sort(column.begin(), column.end());
            double sum = 0.0;
            for (double v : column) sum += v;
            out.mean(o, p) = sum / static_cast<double>(column.size());
            for (Eigen::Index k = 0; k < q_count; ++k) {
                band(k, p) = percentile(column, options.percentiles[k]);
            }
        }
        out.bands.push_back(std::move(band));
    }
    if (cancelled) {
        out.status = StudyStatus::kCancelled;
        out.message = "cancelled: bands from the samples evaluated before the cancel";
    }
    return out;
}

Table BandResult::table() const {
    Table t;
    t.columns = {"slip_angle_deg", "slip", "samples"};
    for (Output o : outputs) {
        t.columns.push_back(std::string(outputName(o)) + "_mean");
        for (double q : percentiles) {
            t.columns.push_back(std::string(outputName(o)) + "_p" + percentName(q));
        }
    }
    if (bands.empty()) return t;
    for (std::size_t p = 0; p < grid.size(); ++p) {
        std::vector<double> row{roundSignificant(units::radToDeg(grid.slipAngle(p))), grid.slip(p),
                                static_cast<double>(used[p])};
        for (std::size_t o = 0; o < outputs.size(); ++o) {
            row.push_back(mean(static_cast<Eigen::Index>(o), static_cast<Eigen::Index>(p)));
            for (std::size_t k = 0; k < percentiles.size(); ++k) {
                row.push_back(bands[o](static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(p)));
            }
        }
        t.rows.push_back(std::move(row));
    }
    return t;
}

}  // namespace terra::gsa
