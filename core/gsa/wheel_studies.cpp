#include "core/gsa/wheel_studies.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/units.h"

namespace terra::gsa {
namespace {

constexpr auto kNotEvaluated = static_cast<std::uint8_t>(SampleStatus::kNotEvaluated);
constexpr auto kOk = static_cast<std::uint8_t>(SampleStatus::kOk);

std::string pointLabel(const OperatingGrid& grid, std::size_t p) {
    return "s = " + formatNumber(grid.slip(p)) +
           ", β = " + formatNumber(roundSignificant(units::radToDeg(grid.slipAngle(p)))) + "°";
}

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g %%", 100.0 * fraction);
    return text;
}

std::string reasons(const FailureCounts& f) {
    std::string out;
    auto add = [&](std::size_t n, const char* what) {
        if (n == 0) return;
        out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + what;
    };
    add(f.no_equilibrium, "without equilibrium");
    add(f.load_not_matched, "with F_z jumping over W");
    add(f.invalid_soil, "with a soil outside its allowed range");
    add(f.non_finite, "non-finite");
    return out.empty() ? "none" : out;
}

// Per grid point, over groups of `per` consecutive rows (a base sample or a trajectory): groups
// fully evaluated, and those among them with a failed row.
struct GroupCounts {
    std::vector<std::size_t> evaluated, dropped;
    std::size_t evaluations = 0;
    bool cancelled = false;
};

GroupCounts countGroups(const TargetValues& values, std::size_t groups, std::size_t per) {
    const auto points = static_cast<std::size_t>(values.status.cols());
    GroupCounts c{std::vector<std::size_t>(points), std::vector<std::size_t>(points), 0, false};
    for (std::size_t p = 0; p < points; ++p) {
        for (std::size_t g = 0; g < groups; ++g) {
            bool evaluated = true, failed = false;
            for (std::size_t k = 0; k < per; ++k) {
                const std::uint8_t s = values.status(static_cast<Eigen::Index>(g * per + k),
                                                     static_cast<Eigen::Index>(p));
                evaluated = evaluated && s != kNotEvaluated;
                failed = failed || (s != kNotEvaluated && s != kOk);
                if (s != kNotEvaluated) ++c.evaluations;
            }
            if (!evaluated) c.cancelled = true;
            if (evaluated) ++c.evaluated[p];
            if (evaluated && failed) ++c.dropped[p];
        }
    }
    return c;
}

// The refusal message when some point lost more than the allowed share, or empty.
std::string refusal(const GroupCounts& c, const std::vector<FailureCounts>& failures,
                    const OperatingGrid& grid, double max_fraction, const char* groups) {
    std::string message;
    for (std::size_t p = 0; p < c.evaluated.size(); ++p) {
        if (c.evaluated[p] == 0) continue;
        const double fraction = static_cast<double>(c.dropped[p]) / c.evaluated[p];
        if (fraction <= max_fraction) continue;
        message += (message.empty() ? "" : "; ") + pointLabel(grid, p) + ": " +
                   std::to_string(c.dropped[p]) + " of " + std::to_string(c.evaluated[p]) + " " +
                   groups + " (" + percent(fraction) + ") have a failed evaluation (" +
                   reasons(failures[p]) + ")";
    }
    if (!message.empty()) {
        message += "; above max_failed_fraction = " + percent(max_fraction) +
                   ": narrow the parameter ranges or raise the threshold";
    }
    return message;
}

void checkShape(const WheelTarget& target, std::size_t rows, const TargetValues& values) {
    if (static_cast<std::size_t>(values.values.rows()) != rows ||
        static_cast<std::size_t>(values.values.cols()) != target.columns() ||
        values.status.rows() != values.values.rows() ||
        static_cast<std::size_t>(values.status.cols()) != target.points()) {
        throw std::invalid_argument(
            "study outputs are " + std::to_string(values.values.rows()) + "×" +
            std::to_string(values.values.cols()) + " (status " +
            std::to_string(values.status.rows()) + "×" + std::to_string(values.status.cols()) +
            "); the design needs " + std::to_string(rows) + "×" + std::to_string(target.columns()) +
            " (status " + std::to_string(rows) + "×" + std::to_string(target.points()) + ")");
    }
}

Eigen::MatrixXd block(const Eigen::MatrixXd& m, std::size_t output, std::size_t points) {
    if (m.size() == 0) return {};
    return m.middleCols(static_cast<Eigen::Index>(output * points),
                        static_cast<Eigen::Index>(points));
}

void checkFraction(std::vector<Issue>& issues, double fraction) {
    checkRange(issues, "max_failed_fraction", fraction, {0.0, 1.0});
}

}  // namespace

Eigen::MatrixXd SobolStudyResult::firstOrder(std::size_t output) const {
    return block(indices.first_order, output, grid.size());
}
Eigen::MatrixXd SobolStudyResult::total(std::size_t output) const {
    return block(indices.total, output, grid.size());
}
Eigen::MatrixXd SobolStudyResult::firstOrderConf(std::size_t output) const {
    return block(indices.first_order_conf, output, grid.size());
}
Eigen::MatrixXd SobolStudyResult::totalConf(std::size_t output) const {
    return block(indices.total_conf, output, grid.size());
}

void requireValid(const SobolOptions& options) {
    std::vector<Issue> issues;
    checkRange(issues, "samples", static_cast<double>(options.base_samples), {2.0, 1e12});
    checkFraction(issues, options.max_failed_fraction);
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    requireValid(options.bootstrap);
}

SobolStudyResult sobolStudy(const WheelStudy& study, const SobolOptions& options,
                            const RunControl& control) {
    requireValid(options);
    const WheelTarget target(study);
    const SaltelliDesign design(study.parameters, options.base_samples, options.seed);
    const std::size_t chunk =
        options.chunk_rows > 0 ? options.chunk_rows : kChunkEvaluations / target.points();
    const TargetValues values = evaluateInChunks(
        target, design.rows(), chunk, design.rowsPerSample(),
        [&](std::size_t begin, std::size_t end) { return design.rows(begin, end); }, control);
    SobolOptions estimation = options;
    if (estimation.bootstrap.threads == 0) estimation.bootstrap.threads = control.threads;
    return sobolResult(target, design, values, estimation);
}

SobolStudyResult sobolResult(const WheelTarget& target, const SaltelliDesign& design,
                             const TargetValues& values, const SobolOptions& options) {
    requireValid(options);
    checkShape(target, design.rows(), values);
    const WheelStudy& study = target.study();
    SobolStudyResult out;
    out.parameters = study.parameters.names();
    out.outputs = study.outputs;
    out.grid = study.grid;
    out.base_samples = design.baseSamples();
    out.failures = target.failures(values);
    const GroupCounts counts = countGroups(values, design.baseSamples(), design.rowsPerSample());
    out.dropped_samples = counts.dropped;
    out.evaluations = counts.evaluations;
    out.message =
        refusal(counts, out.failures, study.grid, options.max_failed_fraction, "base samples");
    if (!out.message.empty()) {
        out.status = StudyStatus::kTooManyFailures;
        return out;
    }
    out.indices =
        estimateSobol(design, values.values, target.successMask(values), options.bootstrap);
    if (counts.cancelled) {
        out.status = StudyStatus::kCancelled;
        const std::size_t complete =
            *std::min_element(counts.evaluated.begin(), counts.evaluated.end());
        out.message = "cancelled: indices from the " + std::to_string(complete) + " of " +
                      std::to_string(design.baseSamples()) + " base samples evaluated";
    }
    return out;
}

void requireValid(const MorrisOptions& options) {
    std::vector<Issue> issues;
    checkRange(issues, "trajectories", static_cast<double>(options.trajectories), {2.0, 1e9});
    if (options.levels < 2 || options.levels % 2 != 0) {
        issues.push_back({"levels", std::to_string(options.levels) +
                                        " must be an even number of grid levels, at least 2"});
    }
    checkFraction(issues, options.max_failed_fraction);
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    requireValid(options.bootstrap);
}

MorrisStudyResult morrisStudy(const WheelStudy& study, const MorrisOptions& options,
                              const RunControl& control) {
    requireValid(options);
    const WheelTarget target(study);
    const MorrisDesign design(study.parameters, options.trajectories, options.levels, options.seed);
    const TargetValues values = evaluateInChunks(
        target, design.rows(), kChunkEvaluations / target.points(), design.rowsPerTrajectory(),
        [&](std::size_t begin, std::size_t end) { return design.rows(begin, end); }, control);
    return morrisResult(target, design, values, options);
}

MorrisStudyResult morrisResult(const WheelTarget& target, const MorrisDesign& design,
                               const TargetValues& values, const MorrisOptions& options) {
    requireValid(options);
    checkShape(target, design.rows(), values);
    const WheelStudy& study = target.study();
    MorrisStudyResult out;
    out.parameters = study.parameters.names();
    out.outputs = study.outputs;
    out.grid = study.grid;
    out.failures = target.failures(values);
    const GroupCounts counts =
        countGroups(values, design.trajectories(), design.rowsPerTrajectory());
    out.dropped_trajectories = counts.dropped;
    out.evaluations = counts.evaluations;
    out.message =
        refusal(counts, out.failures, study.grid, options.max_failed_fraction, "trajectories");
    if (!out.message.empty()) {
        out.status = StudyStatus::kTooManyFailures;
        return out;
    }
    out.indices =
        estimateMorris(design, values.values, target.successMask(values), options.bootstrap);
    if (counts.cancelled) {
        out.status = StudyStatus::kCancelled;
        out.message = "cancelled: statistics from the trajectories evaluated before the cancel";
    }
    return out;
}

}  // namespace terra::gsa
