// The identification study of issue #13: the figures of docs/identification.md, printed as
// Markdown tables. Not a test (the tests assert smaller versions of the same studies); run
//   terra_identification_study [thesis|starts|coverage|priors|holdout|streaming]...
// (all sections when none is given). Fixed seeds: the output is the same on every run except the
// times.
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/identify.h"
#include "core/identification/profile_interval.h"
#include "core/identification/streaming_estimator.h"
#include "core/identification/synthetic.h"
#include "core/io/parameters_json.h"

namespace {

using namespace terra;
using namespace terra::identification;
using contact::ContactParameters;
constexpr double kDeg = std::numbers::pi / 180.0;

struct Wheel {
    const char* name;
    double r, b;
};
constexpr Wheel kA{"A", 0.092, 0.107}, kB{"B", 0.135, 0.165};

// Table 2.1 (n, c kPa, φ deg, k_c, k_φ, K m) with Table 2.6's a₀, a₁, j_max.
struct Soil {
    const char* name;
    double n, c_kpa, phi_deg, kc, kphi, k_m, jmax;
};
constexpr Soil kSandyLoam{"sandy loam", 0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 0.02};
constexpr Soil kDrySand{"dry sand", 1.1, 1.0, 30.0, 0.9, 1523.4, 0.025, 0.02};
constexpr Soil kClayeySoil{"clayey soil", 0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 0.009};

ContactParameters<double> contactOf(const Soil& s, const Wheel& w, double jmax) {
    return {
        w.r, w.b, s.n, 0.0, s.kc * 1e3 / w.b + s.kphi * 1e3, s.c_kpa * 1e3, s.phi_deg * kDeg, s.k_m,
        0.0, 0.2, 0.3, jmax};
}
wheel::WheelParameters wheelOf(const Wheel& w) { return {w.name, "", w.r, w.b}; }
soil::SoilParameters soilOf(const Soil& s) {
    soil::SoilParameters p;
    p.name = s.name;
    p.sinkage_exponent = s.n;
    p.cohesion_pa = s.c_kpa * 1e3;
    p.friction_angle_rad = s.phi_deg * kDeg;
    p.cohesive_modulus = s.kc * 1e3;
    p.frictional_modulus = s.kphi * 1e3;
    p.shear_modulus_m = s.k_m;
    p.max_stress_a0 = 0.2;
    p.max_stress_a1 = 0.3;
    p.max_shear_deformation_m = s.jmax;
    return p;
}
ParameterVector truthOf(const ContactParameters<double>& p) {
    return {p.max_stress_a0, p.max_stress_a1,      p.pressure_modulus, p.sinkage_exponent,
            p.cohesion_pa,   p.friction_angle_rad, p.shear_modulus_m,  p.max_shear_deformation_m};
}

DataSet sweeps(const ContactParameters<double>& soil, std::vector<double> loads, double noise,
               std::uint64_t seed, int slips) {
    SyntheticSpec spec;
    for (int i = 0; i < slips; ++i) spec.slips.push_back(0.9 * i / (slips - 1));
    spec.loads_n = std::move(loads);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = noise;
    spec.seed = seed;
    return synthesize(soil, spec).data;
}

DataSet fromLoad(DataSet d, double load) {
    d.columns.entry_angle = false;
    d.columns.fz = false;
    for (Sample& s : d.samples) s.load_n = s.load_n.value_or(load);
    return d;
}

std::string user(int k, double si) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", si * parameterInfo()[k].to_user);
    return text;
}

ParameterVector thesisGuess() {
    const DecoupledParameters t;
    return {t.a0,
            t.a1,
            t.pressure_modulus,
            t.n0,
            t.cohesion_pa,
            t.friction_angle_rad,
            t.shear_modulus_m,
            t.max_shear_deformation_m};
}

void thesis() {
    std::printf(
        "\n## Thesis data (Table 5.2: one load of 58.86 N, s = 0 : 0.01 : 0.9, noise-free)\n");
    std::printf(
        "| soil | wheel | method | a0 | a1 | Ks | n | c_kPa | phi_deg | K_m | max rel. error | "
        "time ms |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Soil* s : {&kSandyLoam, &kDrySand, &kClayeySoil}) {
        for (const Wheel* w : {&kA, &kB}) {
            const ContactParameters<double> p = contactOf(*s, *w, s->jmax);
            const DataSet d = sweeps(p, {58.86}, 0.0, 1, 91);
            const ParameterVector truth = truthOf(p);
            const auto t0 = std::chrono::steady_clock::now();
            const DecoupledFit dec = fitDecoupled(d, wheelOf(*w), DecoupledParameters{});
            const double t_dec =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            const DecoupledParameters& q = dec.parameters;
            std::printf(
                "| %s | %s | decoupled | %.4f | %.4f | %.1f | %.4f (n1 %.4f) | %.3f | %.2f | "
                "%.4f | — | %.1f |\n",
                s->name, w->name, q.a0, q.a1, q.pressure_modulus / 1e3, q.n0, q.n1,
                q.cohesion_pa / 1e3, q.friction_angle_rad / kDeg, q.shear_modulus_m, t_dec);
            IdentifyOptions o;
            o.max_shear_deformation_m = s->jmax;
            o.starts = {{"thesis guess", thesisGuess()}};
            const IdentificationReport r = identify(d, wheelOf(*w), o);
            double worst = 0.0;
            for (int k = 0; k < kFullParameterCount; ++k)
                worst = std::max(worst, std::abs(r.parameters[k] / truth[k] - 1.0));
            std::printf("| | | global | ");
            for (int k = 0; k < kFullParameterCount; ++k)
                std::printf("%s | ", user(k, r.parameters[k]).c_str());
            std::printf("%.1e | %.1f |\n", worst, r.timing.total_ms);
        }
    }
}

void starts() {
    std::printf("\n## Start dependence: 1 %% noise (seed 7), three loads, 31 slips per load\n");
    std::printf(
        "| case | start (preset) | local: decoupled from the start, then refined: phi_deg, "
        "c_kPa | global: phi_deg, c_kPa, K_m |\n|---|---|---|---|\n");
    struct Case {
        const Soil* soil;
        const Wheel* wheel;
        std::vector<double> loads;
    };
    const Case cases[] = {{&kSandyLoam, &kA, {30, 58.86, 90}}, {&kClayeySoil, &kB, {60, 98, 140}}};
    const io::PresetLocations presets{{TERRA_RESOURCE_DIR}};
    for (const Case& c : cases) {
        const ContactParameters<double> p = contactOf(*c.soil, *c.wheel, c.soil->jmax);
        const DataSet d = sweeps(p, c.loads, 0.01, 7, 31);
        for (const char* name :
             {"sandy-loam", "dry-sand", "lete-sand", "heavy-clay", "clayey-soil", "snow"}) {
            const soil::SoilParameters preset = io::resolveSoil(presets, name).value();
            const ParameterVector g = fromSoil(preset, wheelOf(*c.wheel));
            const DecoupledParameters guess{g[kA0], g[kA1], g[kKs],  g[kN],
                                            0.0,    g[kC],  g[kPhi], g[kK]};
            const DecoupledFit dec = fitDecoupled(d, wheelOf(*c.wheel), guess);
            RefineOptions ro;
            ro.max_shear_deformation_m = c.soil->jmax;
            const RefineResult local = refineFullModel(d, wheelOf(*c.wheel), dec.parameters, ro);
            IdentifyOptions o;
            o.max_shear_deformation_m = c.soil->jmax;
            o.starts = startsFromSoils({preset}, wheelOf(*c.wheel));
            const IdentificationReport r = identify(d, wheelOf(*c.wheel), o);
            std::printf("| %s on %s | %s | %.2f, %.3f | %.3f ± %.3f, %.4f ± %.4f, %.5f |\n",
                        c.soil->name, c.wheel->name, name,
                        local.parameters.friction_angle_rad / kDeg,
                        local.parameters.cohesion_pa / 1e3, r.parameters[kPhi] / kDeg,
                        r.uncertainty.std[kPhi] / kDeg, r.parameters[kC] / 1e3,
                        r.uncertainty.std[kC] / 1e3, r.parameters[kK]);
        }
    }
}

void coverage() {
    std::printf("\n## Coverage: sandy loam on A, 1 %% noise, 20 seeds, noise levels estimated\n");
    struct Setting {
        const char* name;
        std::vector<double> loads;
        bool from_load;
        int slips;
        bool profile;
    };
    const Setting settings[] = {{"one load, theta_f", {58.86}, false, 46, true},
                                {"three loads, theta_f", {30, 58.86, 90}, false, 31, true},
                                {"three loads, from the load", {30, 58.86, 90}, true, 31, false}};
    const ContactParameters<double> p = contactOf(kSandyLoam, kA, 0.02);
    const ParameterVector truth = truthOf(p);
    for (const Setting& s : settings) {
        std::array<double, kFullParameterCount> sum{}, sum2{}, std_sum{};
        std::array<int, kFullParameterCount> covered{};
        int runs = 0, ambiguous = 0;
        double time = 0.0;
        std::array<int, kFullParameterCount> profiled{}, profile_covered{}, flagged_count{}, fits{},
            open{}, hybrid{};
        std::array<double, kFullParameterCount> width{};
        double profile_ms = 0.0;
        for (std::uint64_t seed = 1; seed <= 20; ++seed) {
            DataSet d = sweeps(p, s.loads, 0.01, seed, s.slips);
            if (s.from_load) d = fromLoad(std::move(d), 58.86);
            IdentifyOptions o;
            o.max_shear_deformation_m = 0.02;
            const IdentificationReport r = identify(d, wheelOf(kA), o);
            if (!r.usable() || !r.uncertainty.computed) continue;
            ++runs;
            ambiguous += !r.ambiguity.empty();
            time += r.timing.total_ms;
            for (int k = 0; k < kFullParameterCount; ++k) {
                const double e = r.parameters[k] / truth[k] - 1.0;
                sum[k] += e;
                sum2[k] += e * e;
                std_sum[k] += r.uncertainty.std[k] / truth[k];
                covered[k] += std::abs(r.parameters[k] - truth[k]) <= 3 * r.uncertainty.std[k];
            }
            if (!s.profile) continue;
            // Profile-likelihood intervals (Δχ² = 9) of every parameter, and of those identify
            // flags (a trade-off pair or a bound).
            const auto begin = std::chrono::steady_clock::now();
            std::array<bool, kFullParameterCount> all{};
            all.fill(true);
            const auto flagged = tradeOffParameters(r);
            const auto intervals = profileIntervals(d, wheelOf(kA), o, r, all);
            profile_ms +=
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
                    .count();
            for (int k = 0; k < kFullParameterCount; ++k) {
                const ProfileInterval& i = intervals[k];
                if (!i.computed) continue;
                ++profiled[k];
                flagged_count[k] += flagged[k];
                fits[k] += i.fits;
                const bool in = i.lower <= truth[k] && truth[k] <= i.upper;
                profile_covered[k] += in;
                width[k] += (i.upper - i.lower) / truth[k];
                open[k] += i.lower_at_bound || i.upper_at_bound;
                // The 3σ interval where identify flags the parameter, the profile elsewhere.
                hybrid[k] += flagged[k]
                                 ? in
                                 : std::abs(r.parameters[k] - truth[k]) <= 3 * r.uncertainty.std[k];
            }
        }
        std::printf("\n%s: %d usable runs, %d with an ambiguity, %.0f ms each on average\n\n",
                    s.name, runs, ambiguous, time / std::max(runs, 1));
        std::printf(
            "| parameter | mean error | rms error | mean reported std | truth within 3 std "
            "|\n|---|---|---|---|---|\n");
        for (int k = 0; k < kFullParameterCount; ++k) {
            std::printf("| %s | %+.2f %% | %.2f %% | %.2f %% | %d / %d |\n",
                        parameterInfo()[k].name, 100 * sum[k] / runs,
                        100 * std::sqrt(sum2[k] / runs), 100 * std_sum[k] / runs, covered[k], runs);
        }
        if (!s.profile) continue;
        std::printf(
            "\nProfile-likelihood intervals (profile_interval.h, Δχ² = 9), %.0f ms per run on "
            "average:\n\n| parameter | profiled | truth inside | mean width | open at a bound | "
            "flagged | profile where flagged, 3σ elsewhere | fits per parameter |\n"
            "|---|---|---|---|---|---|---|---|\n",
            profile_ms / std::max(runs, 1));
        for (int k = 0; k < kFullParameterCount; ++k) {
            const int n = std::max(profiled[k], 1);
            std::printf("| %s | %d | %d / %d | %.2f %% | %d | %d | %d / %d | %.1f |\n",
                        parameterInfo()[k].name, profiled[k], profile_covered[k], profiled[k],
                        100 * width[k] / n, open[k], flagged_count[k], hybrid[k], profiled[k],
                        static_cast<double>(fits[k]) / n);
        }
    }
}

void priors() {
    std::printf(
        "\n## Priors: sandy loam on A, 1 %% noise, prior = the sandy-loam preset with the "
        "default spreads (seed 1)\n");
    const ContactParameters<double> p = contactOf(kSandyLoam, kA, 0.02);
    const soil::SoilParameters preset = soilOf(kSandyLoam);
    for (const auto& loads : {std::vector<double>{58.86}, std::vector<double>{30, 58.86, 90}}) {
        IdentifyOptions o;
        o.max_shear_deformation_m = 0.02;
        o.priors = priorsFromSoil(preset, wheelOf(kA));
        const IdentificationReport r = identify(sweeps(p, loads, 0.01, 1, 31), wheelOf(kA), o);
        std::printf(
            "\n%zu load(s)\n\n| parameter | prior | posterior | shift (prior std) | "
            "posterior/prior std |\n|---|---|---|---|---|\n",
            loads.size());
        for (int k = 0; k < kFullParameterCount; ++k) {
            const PriorComparison& c = r.prior[k];
            std::printf("| %s | %s ± %s | %s ± %s | %+.2f | %.2f |\n", parameterInfo()[k].name,
                        user(k, c.prior_mean).c_str(), user(k, c.prior_std).c_str(),
                        user(k, c.posterior_mean).c_str(), user(k, c.posterior_std).c_str(),
                        c.shift_in_prior_std, c.std_ratio);
        }
    }
}

void holdout() {
    std::printf(
        "\n## Held-out error: sandy loam on A, three loads, 1 %% noise, 5 folds; RMS over the "
        "noise levels of the all-free fit\n\n| model | Fx held out (in fit) | Fz held out (in "
        "fit) | My held out (in fit) |\n|---|---|---|---|\n");
    const ContactParameters<double> p = contactOf(kSandyLoam, kA, 0.02);
    const DataSet d = sweeps(p, {30, 58.86, 90}, 0.01, 3, 31);
    ChannelValues noise{};
    for (int wrong = 0; wrong < 2; ++wrong) {
        IdentifyOptions o;
        o.max_shear_deformation_m = 0.02;
        o.folds = 5;
        if (wrong) o.fixed[kPhi] = 20 * kDeg;
        const IdentificationReport r = identify(d, wheelOf(kA), o);
        if (!wrong) noise = r.noise;
        std::printf("| %s |", wrong ? "phi held at 20 deg" : "all free");
        for (int c : {kFxChannel, kFzChannel, kMyChannel}) {
            std::printf(" %.2f (%.2f) |", r.holdout.rms[c] / noise[c],
                        r.holdout.rms_in_fit[c] / noise[c]);
        }
        std::printf("\n");
    }
}

std::vector<Sample> drive(const ContactParameters<double>& soil, int blocks, std::uint64_t seed) {
    const double loads[3] = {30.0, 58.86, 90.0};
    const double noise[3] = {0.136, 0.90, 0.0195};
    boost::random::mt19937_64 engine(seed);
    boost::random::normal_distribution<double> normal(0.0, 1.0);
    std::vector<Sample> out;
    for (int b = 0; b < blocks; ++b) {
        SyntheticSpec spec;
        spec.loads_n = {loads[b % 3]};
        for (int i = 0; i < 50; ++i) spec.slips.push_back(0.05 + 0.8 * (b % 2 ? 49 - i : i) / 49.0);
        for (Sample s : synthesize(soil, spec).data.samples) {
            s.load_n = loads[b % 3];
            s.fx_n += noise[0] * normal(engine);
            s.fz_n += noise[1] * normal(engine);
            s.my_nm += noise[2] * normal(engine);
            out.push_back(s);
        }
    }
    return out;
}

void streaming() {
    std::printf(
        "\n## Streaming: wheel A, loads 30/58.86/90 N every 50 samples, slip sweeps, 1 %% "
        "noise\n");
    StreamingEstimatorOptions o;
    o.fit.max_shear_deformation_m = 0.02;
    // False alarms: 10 runs of 5000 samples of one soil.
    int confirmed = 0, rejected = 0;
    long samples = 0;
    double update = 0.0, worst = 0.0;
    long updates = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const ContactParameters<double> soil =
            contactOf(seed % 2 ? kSandyLoam : kClayeySoil, kA, 0.02);
        StreamingEstimator estimator(wheelOf(kA), o);
        for (const Sample& s : drive(soil, 100, seed)) {
            const StreamEstimate e = estimator.push(s);
            ++samples;
            confirmed += e.change_detected;
            rejected += e.change_rejected;
            if (e.estimated && !e.initialised && !e.refitted && !e.change_rejected) {
                update += e.update_ms;
                worst = std::max(worst, e.update_ms);
                ++updates;
            }
        }
    }
    std::printf(
        "\none soil (sandy loam and clay, j_max 0.02 m), %ld samples: %d confirmed changes "
        "(false alarms), %d CUSUM alarms rejected by the likelihood-ratio test; update "
        "%.3f ms mean, %.2f ms worst (wall)\n",
        samples, confirmed, rejected, update / updates, worst);
    // Borders: 1000 samples of one soil, then 400 of another.
    std::printf("\n| border | seed | change at | confirmed at | delay |\n|---|---|---|---|---|\n");
    const std::pair<const Soil*, const Soil*> borders[] = {
        {&kSandyLoam, &kClayeySoil}, {&kClayeySoil, &kSandyLoam}, {&kSandyLoam, &kDrySand}};
    for (const auto& [from, to] : borders) {
        for (std::uint64_t seed = 1; seed <= 3; ++seed) {
            std::vector<Sample> run = drive(contactOf(*from, kA, 0.02), 20, seed);
            const std::size_t border = run.size();
            const std::vector<Sample> next = drive(contactOf(*to, kA, 0.02), 8, seed + 100);
            run.insert(run.end(), next.begin(), next.end());
            StreamingEstimator estimator(wheelOf(kA), o);
            std::string at = "none", when = "none", delay = "—";
            for (std::size_t i = 0; i < run.size(); ++i) {
                const StreamEstimate e = estimator.push(run[i]);
                if (!e.change_detected) continue;
                at = std::to_string(*e.change_at);
                when = std::to_string(i);
                delay = std::to_string(static_cast<long>(i) - static_cast<long>(border));
            }
            std::printf("| %s → %s (at %zu) | %llu | %s | %s | %s |\n", from->name, to->name,
                        border, static_cast<unsigned long long>(seed), at.c_str(), when.c_str(),
                        delay.c_str());
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    const std::vector<std::pair<const char*, void (*)()>> sections = {
        {"thesis", thesis}, {"starts", starts},   {"coverage", coverage},
        {"priors", priors}, {"holdout", holdout}, {"streaming", streaming}};
    for (const auto& [name, run] : sections) {
        bool wanted = argc == 1;
        for (int a = 1; a < argc; ++a) wanted |= std::strcmp(argv[a], name) == 0;
        if (wanted) run();
    }
}
