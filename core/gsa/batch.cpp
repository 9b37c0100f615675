#include "core/gsa/batch.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/wheel_forces.h"

namespace terra::gsa {
namespace {

using contact::ContactParameters;
using soil::SoilField;
using soil::SoilParameters;

// Samples a worker claims at a time: small enough to balance 2…64 threads on a few thousand
// samples, large enough that the shared counter is not contended (one sample is ≥ 2 µs).
constexpr std::size_t kBlock = 16;
// At most this many bad inputs are listed in one error message; the rest are counted.
constexpr std::size_t kMaxListed = 10;

// One input array: `count` values or one broadcast value.
struct Column {
    const double* data = nullptr;
    std::size_t stride = 0;

    double at(std::size_t i) const { return data[i * stride]; }
};

struct Override {
    const SoilField* field;
    Column values;
};

struct Prepared {
    SoilParameters base;  // without name and source: copied per sample without allocating
    double width_m = 0.0, radius_m = 0.0;
    double lug_shear_offset_m = 0.0;  // λ_s h_g (docs/model.md, "Lugs")
    std::vector<Override> overrides;
    bool exponent_varied = false;  // n or n1 overridden: N = n + n1 s is re-checked per sample
    Column slip, slip_angle, load, entry;
    bool has_slip_angle = false, has_load = false;
    std::size_t count = 0;
};

std::string indexed(const std::string& name, const Column& c, std::size_t i) {
    return c.stride == 0 ? name : name + "[" + std::to_string(i) + "]";
}

Column column(std::vector<Issue>& issues, const std::string& name, std::span<const double> a,
              std::size_t count) {
    if (a.size() == count || a.size() == 1) return {a.data(), a.size() == 1 ? 0u : 1u};
    issues.push_back({name, "has " + std::to_string(a.size()) + " values, expected " +
                                std::to_string(count) + " (one per sample) or 1"});
    return {};
}

// The sample's soil as contact parameters; false (and, with `issues`, the reasons) when invalid.
bool contactOf(const Prepared& prep, std::size_t i, ContactParameters<double>& p,
               std::vector<Issue>* issues) {
    SoilParameters s = prep.base;
    bool ok = true;
    for (const Override& o : prep.overrides) {
        const double v = o.values.at(i);
        if (!o.field->range.contains(v)) {
            ok = false;
            if (!issues) return false;
            const std::string unit = o.field->unit;
            checkRange(*issues, indexed(o.field->key, o.values, i), v, o.field->range,
                       unit == "-" ? "" : unit);
            continue;
        }
        s.*(o.field->member) = v * o.field->to_si;
    }
    if (!ok) return false;
    if (prep.exponent_varied && s.sinkage_exponent_slip != 0.0) {
        static const Range n_range = soil::findSoilField("n")->range;
        const double braking = roundSignificant(s.sinkage_exponent - s.sinkage_exponent_slip);
        const double driving = roundSignificant(s.sinkage_exponent + s.sinkage_exponent_slip);
        if (!n_range.contains(braking) || !n_range.contains(driving)) {
            if (issues) {
                issues->push_back({"n1[" + std::to_string(i) + "]",
                                   "N = n + n1·s must stay in " + n_range.describe() +
                                       " for every slip, but n - n1 = " + formatNumber(braking) +
                                       " and n + n1 = " + formatNumber(driving)});
            }
            return false;
        }
    }
    const double pressure_modulus = s.cohesive_modulus / prep.width_m + s.frictional_modulus;
    if (!(pressure_modulus > 0.0)) {
        if (issues) {
            issues->push_back({"kc[" + std::to_string(i) + "]",
                               "K_s = kc/b + kphi = " +
                                   formatNumber(roundSignificant(pressure_modulus / 1e3, 6)) +
                                   " kN/m^(n+2) must be > 0"});
        }
        return false;
    }
    p = {.radius_m = prep.radius_m,
         .width_m = prep.width_m,
         .sinkage_exponent = s.sinkage_exponent,
         .sinkage_exponent_slip = s.sinkage_exponent_slip,
         .pressure_modulus = pressure_modulus,
         .cohesion_pa = s.cohesion_pa,
         .friction_angle_rad = s.friction_angle_rad,
         .shear_modulus_m = s.shear_modulus_m,
         .unit_weight_n_m3 = s.unit_weight_n_m3,
         .max_stress_a0 = s.max_stress_a0,
         .max_stress_a1 = s.max_stress_a1,
         .max_shear_deformation_m = s.max_shear_deformation_m,
         .lug_shear_offset_m = prep.lug_shear_offset_m,
         .slip_sinkage_coefficient = s.slip_sinkage_coefficient};
    return true;
}

// The fast test accepts what is clearly inside; values near an end are checked as the user typed
// them (rounded degrees), exactly as contact::requireValid would.
void checkPoint(std::vector<Issue>& issues, const Prepared& prep, std::size_t i) {
    // A broadcast value is checked once, at sample 0.
    auto due = [i](const Column& c) { return c.stride != 0 || i == 0; };
    const double s = prep.slip.at(i);
    if (due(prep.slip) && !(std::abs(s) <= 1.0)) {
        checkRange(issues, indexed("slip", prep.slip, i), s, contact::slipField().range);
    }
    if (prep.has_slip_angle && due(prep.slip_angle)) {
        const double b = prep.slip_angle.at(i);
        if (!(std::abs(b) < 0.999999 * units::kPi / 2.0)) {
            checkRange(issues, indexed("slip_angle_deg", prep.slip_angle, i), roundedDegrees(b),
                       contact::slipAngleField().range, "deg");
        }
    }
    if (prep.has_load && due(prep.load)) {
        const double w = prep.load.at(i);
        checkRange(issues, indexed("load_N", prep.load, i), w, contact::loadField().range, "N");
    } else if (!prep.has_load && due(prep.entry)) {
        const double t = prep.entry.at(i);
        if (!(t > 1e-9 && t < 0.999999 * units::kPi / 2.0)) {
            checkRange(issues, indexed("entry_angle_deg", prep.entry, i), roundedDegrees(t),
                       {0.0, 90.0, true, false}, "deg");
        }
    }
}

Prepared prepare(const SoilParameters& soil, const wheel::WheelParameters& wheel,
                 const BatchInput& input, const ModelOptions& options, const BatchOutputView& out,
                 InvalidSoil invalid) {
    requireValid(options);
    // The base soil and wheel must be valid on their own (and give K_s > 0).
    (void)contact::makeContactParameters(soil, wheel);
    Prepared prep;
    prep.base = soil;
    prep.base.name.clear(), prep.base.source.clear();
    prep.base.name.shrink_to_fit(), prep.base.source.shrink_to_fit();
    prep.width_m = wheel.width_m, prep.radius_m = wheel.radius_m;
    prep.lug_shear_offset_m = wheel.lugShearOffset();
    prep.count = input.count;
    const std::size_t n = input.count;
    std::vector<Issue> issues;
    if (input.slip.empty() && n > 0) issues.push_back({"slip", "no slip values"});
    if (!input.slip.empty()) prep.slip = column(issues, "slip", input.slip, n);
    if (!input.slip_angle_rad.empty()) {
        prep.slip_angle = column(issues, "slip_angle", input.slip_angle_rad, n);
        prep.has_slip_angle = true;
    }
    if (!input.load_n.empty() && !input.entry_angle_rad.empty()) {
        issues.push_back({"load_N", "give either the load or the entry angle, not both"});
    } else if (input.load_n.empty() && input.entry_angle_rad.empty()) {
        issues.push_back({"load_N", "give the load (θ_f solved) or the entry angle"});
    } else if (!input.load_n.empty()) {
        prep.load = column(issues, "load_N", input.load_n, n);
        prep.has_load = true;
    } else {
        prep.entry = column(issues, "entry_angle", input.entry_angle_rad, n);
    }
    for (const SoilOverride& o : input.soil) {
        const SoilField* field = soil::findSoilField(o.key);
        if (!field) {
            std::string keys;
            for (const SoilField& f : soil::soilFields()) keys += std::string(" ") + f.key;
            issues.push_back({o.key, "is not a soil field (fields:" + keys + ")"});
            continue;
        }
        for (const Override& other : prep.overrides) {
            if (other.field == field) issues.push_back({o.key, "is overridden twice"});
        }
        prep.overrides.push_back({field, column(issues, o.key, o.values, n)});
        const std::string key = field->key;
        if (key == "n" || key == "n1") prep.exponent_varied = true;
    }
    auto checkOut = [&](const char* name, std::size_t size) {
        if (size != 0 && size != n) {
            issues.push_back({name, "output array has " + std::to_string(size) +
                                        " values, expected " + std::to_string(n)});
        }
    };
    checkOut("Fx_N", out.fx_n.size()), checkOut("Fy_N", out.fy_n.size());
    checkOut("Fz_N", out.fz_n.size()), checkOut("Mx_Nm", out.mx_nm.size());
    checkOut("My_Nm", out.my_nm.size()), checkOut("Mz_Nm", out.mz_nm.size());
    checkOut("Fb_N", out.fb_n.size()), checkOut("Fs_N", out.fs_n.size());
    checkOut("entry_angle", out.entry_angle_rad.size());
    checkOut("exit_angle", out.exit_angle_rad.size()), checkOut("sinkage_m", out.sinkage_m.size());
    checkOut("status", out.status.size());
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    // Every sample's inputs, listing the first few problems and counting the rest.
    std::size_t problems = 0;
    ContactParameters<double> scratch{};
    const bool soil_varies = std::any_of(prep.overrides.begin(), prep.overrides.end(),
                                         [](const Override& o) { return o.values.stride != 0; });
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<Issue> found;
        checkPoint(found, prep, i);
        if (invalid == InvalidSoil::kThrow && (i == 0 || soil_varies)) {
            contactOf(prep, i, scratch, &found);
        }
        problems += found.size();
        for (Issue& issue : found) {
            if (issues.size() < kMaxListed) issues.push_back(std::move(issue));
        }
    }
    if (problems > issues.size()) {
        issues.push_back(
            {"input", "and " + std::to_string(problems - issues.size()) + " more invalid values"});
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    return prep;
}

struct Sample {
    contact::WheelForces<double> forces;
    double entry = 0.0, exit = 0.0, sinkage = 0.0;
};

SampleStatus evaluateSample(const Prepared& prep, const ModelOptions& options, std::size_t i,
                            Sample& out) {
    ContactParameters<double> p;
    if (!contactOf(prep, i, p, nullptr)) return SampleStatus::kInvalidSoil;
    const double s = prep.slip.at(i);
    const double beta = prep.has_slip_angle ? prep.slip_angle.at(i) : 0.0;
    double theta_f = 0.0;
    if (prep.has_load) {
        const contact::EntryAngleProblem problem{prep.load.at(i),
                                                 s,
                                                 beta,
                                                 options.exit,
                                                 options.max_stress_angle_rad,
                                                 options.model,
                                                 options.integration,
                                                 std::nullopt};
        const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
        if (solution.status == contact::SinkageSolution::Status::kNoEquilibrium) {
            return SampleStatus::kNoEquilibrium;
        }
        if (solution.status == contact::SinkageSolution::Status::kLoadNotMatched) {
            return SampleStatus::kLoadNotMatched;
        }
        theta_f = solution.entry_angle_rad;
    } else {
        theta_f = prep.entry.at(i);
    }
    const double theta_r = std::max(options.exit.exitAngle(theta_f), -theta_f);
    const contact::OperatingPoint<double> op{s, beta, theta_f, theta_r,
                                             options.max_stress_angle_rad};
    out.forces = options.model == contact::ContactModel::kFull
                     ? contact::computeForces(p, op, options.bulldozing, options.integration)
                     : contact::computeQuadraticForces(p, op, options.bulldozing);
    out.entry = theta_f, out.exit = theta_r;
    out.sinkage = contact::slipSinkage(p.radius_m, theta_f, s, p.slip_sinkage_coefficient);
    const contact::WheelForces<double>& f = out.forces;
    for (double v : {f.fx, f.fy, f.fz, f.mx, f.my, f.mz, f.fb, f.fs, out.sinkage}) {
        if (!std::isfinite(v)) return SampleStatus::kNonFinite;
    }
    return SampleStatus::kOk;
}

void put(std::span<double> a, std::size_t i, double v) {
    if (!a.empty()) a[i] = v == 0.0 ? 0.0 : v;  // no negative zeros
}

void write(const BatchOutputView& out, std::size_t i, SampleStatus status, const Sample& s) {
    const bool ok = status == SampleStatus::kOk;
    const contact::WheelForces<double>& f = s.forces;
    put(out.fx_n, i, ok ? f.fx : 0.0), put(out.fy_n, i, ok ? f.fy : 0.0);
    put(out.fz_n, i, ok ? f.fz : 0.0), put(out.mx_nm, i, ok ? f.mx : 0.0);
    put(out.my_nm, i, ok ? f.my : 0.0), put(out.mz_nm, i, ok ? f.mz : 0.0);
    put(out.fb_n, i, ok ? f.fb : 0.0), put(out.fs_n, i, ok ? f.fs : 0.0);
    put(out.entry_angle_rad, i, ok ? s.entry : 0.0);
    put(out.exit_angle_rad, i, ok ? s.exit : 0.0);
    put(out.sinkage_m, i, ok ? s.sinkage : 0.0);
    if (!out.status.empty()) out.status[i] = status;
}

}  // namespace

void requireValid(const ModelOptions& options) {
    std::vector<Issue> issues;
    if (options.exit.kind == contact::ExitCondition::Kind::kRutRatio) {
        checkRange(issues, "rut_ratio", options.exit.value, contact::rutRatioField().range);
    } else {
        checkRange(issues, "exit_angle_deg", roundedDegrees(options.exit.value),
                   contact::exitAngleField().range, "deg");
    }
    if (options.max_stress_angle_rad) {
        checkRange(issues, "max_stress_angle_deg", roundedDegrees(*options.max_stress_angle_rad),
                   contact::maxStressAngleField().range, "deg");
    }
    checkRange(issues, "integration.tolerance", options.integration.tolerance,
               {0.0, 1.0, true, false});
    checkRange(issues, "integration.max_pieces", options.integration.max_pieces, {1.0, 96.0});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

const char* statusName(SampleStatus status) {
    switch (status) {
        case SampleStatus::kOk:
            return "ok";
        case SampleStatus::kNoEquilibrium:
            return "no equilibrium";
        case SampleStatus::kLoadNotMatched:
            return "load not matched";
        case SampleStatus::kInvalidSoil:
            return "soil outside its allowed range";
        case SampleStatus::kNonFinite:
            return "non-finite output";
        case SampleStatus::kNotEvaluated:
            return "not evaluated (cancelled)";
    }
    return "?";
}

BatchSummary evaluateBatch(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                           const BatchInput& input, const ModelOptions& options,
                           const BatchOutputView& out, const RunControl& control,
                           InvalidSoil invalid) {
    const Prepared prep = prepare(soil, wheel, input, options, out, invalid);
    const std::size_t n = input.count;
    if (n == 0) return {};
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers = std::max<std::size_t>(
        1, std::min<std::size_t>(blocks, control.threads > 0 ? control.threads : hardware));
    std::atomic<std::size_t> next{0}, done{0}, ok{0}, failed{0}, skipped{0};
    std::atomic<bool> stop{false};
    std::mutex progress_mutex;
    std::size_t reported_percent = 0;
    std::vector<std::exception_ptr> failures(workers);
    auto work = [&](std::size_t w) {
        try {
            Sample sample;
            std::size_t my_ok = 0, my_failed = 0, my_skipped = 0;
            for (std::size_t b = next++; b < blocks && !stop.load(std::memory_order_relaxed);
                 b = next++) {
                const std::size_t end = std::min(n, (b + 1) * kBlock);
                for (std::size_t i = b * kBlock; i < end; ++i) {
                    SampleStatus status = SampleStatus::kNotEvaluated;
                    if (!(control.cancel && control.cancel->load(std::memory_order_relaxed))) {
                        status = evaluateSample(prep, options, i, sample);
                    }
                    write(out, i, status, sample);
                    if (status == SampleStatus::kOk) {
                        ++my_ok;
                    } else if (status == SampleStatus::kNotEvaluated) {
                        ++my_skipped;
                    } else {
                        ++my_failed;
                    }
                }
                const std::size_t now = done += end - b * kBlock;
                if (control.progress) {
                    const std::size_t percent = now * 100 / n;
                    std::lock_guard lock(progress_mutex);
                    if (percent > reported_percent) {
                        reported_percent = percent;
                        control.progress(static_cast<double>(now) / n);
                    }
                }
            }
            ok += my_ok, failed += my_failed, skipped += my_skipped;
        } catch (...) {
            failures[w] = std::current_exception();
            stop.store(true);
        }
    };
    {
        std::vector<std::jthread> pool;
        for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
        work(0);
    }
    for (const std::exception_ptr& failure : failures) {
        if (failure) std::rethrow_exception(failure);
    }
    return {ok.load(), failed.load(), skipped.load(), skipped.load() > 0};
}

BatchResult evaluateBatch(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                          const BatchInput& input, const ModelOptions& options,
                          const RunControl& control, InvalidSoil invalid) {
    BatchResult r;
    const std::size_t n = input.count;
    for (std::vector<double>* a : {&r.fx_n, &r.fy_n, &r.fz_n, &r.mx_nm, &r.my_nm, &r.mz_nm, &r.fb_n,
                                   &r.fs_n, &r.entry_angle_rad, &r.exit_angle_rad, &r.sinkage_m}) {
        a->assign(n, 0.0);
    }
    r.status.assign(n, SampleStatus::kNotEvaluated);
    const BatchOutputView view{r.fx_n,      r.fy_n,  r.fz_n, r.mx_nm,           r.my_nm,
                               r.mz_nm,     r.fb_n,  r.fs_n, r.entry_angle_rad, r.exit_angle_rad,
                               r.sinkage_m, r.status};
    r.summary = evaluateBatch(soil, wheel, input, options, view, control, invalid);
    return r;
}

}  // namespace terra::gsa
