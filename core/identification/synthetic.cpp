#include "core/identification/synthetic.h"

#include <algorithm>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/contact/wheel_forces.h"

namespace terra::identification {
namespace {

void validate(const SyntheticSpec& spec) {
    std::vector<Issue> issues;
    if (spec.loads_n.empty()) issues.push_back({"loads", "no load given"});
    if (spec.slips.empty()) issues.push_back({"slips", "no slip given"});
    const FieldInfo& load = contact::loadField();
    for (double w : spec.loads_n) checkRange(issues, load.key, w, load.range, load.displayUnit());
    const FieldInfo& slip = contact::slipField();
    for (double s : spec.slips) checkRange(issues, slip.key, s, slip.range);
    for (const auto& [name, noise] : {std::pair{"noise.Fx", spec.noise.fx},
                                      {"noise.Fz", spec.noise.fz},
                                      {"noise.My", spec.noise.my},
                                      {"noise.entry_angle", spec.noise.entry_angle}}) {
        checkRange(issues, std::string(name) + ".absolute", noise.absolute, {0.0, 1e6});
        checkRange(issues, std::string(name) + ".relative", noise.relative, {0.0, 10.0});
    }
    checkRange(issues, "sample_period_s", spec.sample_period_s, {0.0, 1e6, true, false}, "s");
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace

SyntheticData synthesize(const contact::ContactParameters<double>& p, const SyntheticSpec& spec) {
    validate(spec);
    SyntheticData out;
    const bool several_loads = spec.loads_n.size() > 1;
    const double points = static_cast<double>(spec.loads_n.size() * spec.slips.size());
    std::size_t done = 0;
    for (double load : spec.loads_n) {
        std::optional<double> previous;
        for (double s : spec.slips) {
            if (spec.progress && done > 0) spec.progress(static_cast<double>(done) / points);
            ++done;
            if (spec.cancel && spec.cancel->load(std::memory_order_relaxed)) {
                out.cancelled = true;
                break;
            }
            contact::EntryAngleProblem problem;
            problem.load_n = load;
            problem.slip = s;
            problem.slip_angle_rad = spec.slip_angle_rad;
            problem.exit = spec.exit;
            problem.initial_guess_rad = previous;
            const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
            if (!solution.ok()) {
                out.warnings.push_back("W = " + formatNumber(load) + " N, s = " + formatNumber(s) +
                                       ": " + solution.message);
                previous.reset();
                continue;
            }
            previous = solution.entry_angle_rad;
            const contact::WheelForces<double> f = contact::computeForces(
                p, contact::operatingPoint(problem, solution.entry_angle_rad));
            Sample sample;
            sample.slip = s;
            sample.entry_angle_rad = solution.entry_angle_rad;
            sample.fx_n = f.fx;
            sample.fz_n = f.fz;
            sample.my_nm = f.my;
            sample.fy_n = f.fy;
            sample.slip_angle_rad = spec.slip_angle_rad;
            sample.time_s = spec.sample_period_s * static_cast<double>(out.data.samples.size());
            if (several_loads) sample.load_n = load;
            out.data.samples.push_back(sample);
        }
        if (out.cancelled) break;
    }
    if (spec.progress && !out.cancelled) spec.progress(1.0);
    // Eq. 5.1: ỹ = y + e, e ~ N(0, σ²) per channel, in a fixed order so a seed is reproducible.
    double max_fx = 0, max_fz = 0, max_my = 0, max_theta = 0;
    for (const Sample& s : out.data.samples) {
        max_fx = std::max(max_fx, std::abs(s.fx_n));
        max_fz = std::max(max_fz, std::abs(s.fz_n));
        max_my = std::max(max_my, std::abs(s.my_nm));
        max_theta = std::max(max_theta, std::abs(s.entry_angle_rad));
    }
    boost::random::mt19937_64 engine(spec.seed);
    boost::random::normal_distribution<double> normal(0.0, 1.0);
    const double sigma_fx = spec.noise.fx.sigma(max_fx), sigma_fz = spec.noise.fz.sigma(max_fz),
                 sigma_my = spec.noise.my.sigma(max_my),
                 sigma_theta = spec.noise.entry_angle.sigma(max_theta);
    for (Sample& s : out.data.samples) {
        s.fx_n += sigma_fx * normal(engine);
        s.fz_n += sigma_fz * normal(engine);
        s.my_nm += sigma_my * normal(engine);
        // Keep a noisy entry angle inside the model's domain (0, 90°).
        s.entry_angle_rad = std::clamp(s.entry_angle_rad + sigma_theta * normal(engine), 1e-6,
                                       std::nextafter(1.5707963267948966, 0.0));
    }
    return out;
}

}  // namespace terra::identification
