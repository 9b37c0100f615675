#include "core/soil/soil_profile.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"

namespace terra::soil {
namespace {

constexpr double kDepthTolerance = 1e-9;  // [m]: layers meet when tops and bottoms agree to this

void checkOptional(std::vector<Issue>& issues, const std::string& where,
                   const std::optional<double>& value, const Range& range, const char* unit,
                   double to_user = 1.0) {
    if (value) checkRange(issues, where, *value * to_user, range, unit);
}

}  // namespace

const SoilLayer* SoilProfile::layerAt(double depth_m) const {
    const int i = layerIndexAt(depth_m);
    return i < 0 ? nullptr : &layers[static_cast<std::size_t>(i)];
}

int SoilProfile::layerIndexAt(double depth_m) const {
    for (std::size_t i = 0; i < layers.size(); ++i) {
        if (depth_m >= layers[i].top_m && depth_m <= layers[i].bottom_m) return static_cast<int>(i);
    }
    return -1;
}

std::vector<Issue> validate(const SoilProfile& profile, const std::string& prefix) {
    std::vector<Issue> issues;
    if (profile.layers.empty()) {
        issues.push_back({prefix + ".layers", "a profile needs at least one layer"});
        return issues;
    }
    double expected_top = 0.0;
    for (std::size_t i = 0; i < profile.layers.size(); ++i) {
        const SoilLayer& l = profile.layers[i];
        const std::string at = prefix + ".layers[" + std::to_string(i) + "]";
        const std::size_t before = issues.size();
        checkRange(issues, at + ".top_m", l.top_m, Range{0.0, 10.0}, "m");
        checkRange(issues, at + ".bottom_m", l.bottom_m, Range{0.0, 10.0}, "m");
        if (issues.size() == before) {
            if (!(l.bottom_m > l.top_m)) {
                issues.push_back({at + ".bottom_m", "bottom " + formatNumber(l.bottom_m) +
                                                        " m must be below the top " +
                                                        formatNumber(l.top_m) + " m"});
            }
            if (std::abs(l.top_m - expected_top) > kDepthTolerance) {
                const bool overlap = l.top_m < expected_top;
                issues.push_back(
                    {at + ".top_m",
                     "top " + formatNumber(l.top_m) + " m " +
                         (i == 0 ? std::string("must be 0 (the first layer starts at the surface)")
                                 : std::string(overlap ? "overlaps" : "leaves a gap after") +
                                       " the layer above, which ends at " +
                                       formatNumber(expected_top) + " m")});
            }
            expected_top = l.bottom_m;
        }
        if (l.clay_kg_kg) {
            const double clay = *l.clay_kg_kg;
            if (!(clay >= 0.0 && clay <= 1.0)) {
                issues.push_back(
                    {at + ".clay_kg_kg",
                     formatNumber(clay) + " is outside [0, 1]: clay is a mass fraction (kg/kg)" +
                         (clay > 1.0 && clay <= 100.0
                              ? "; " + formatNumber(clay) + " % is " + formatNumber(clay / 100.0)
                              : std::string())});
            }
        }
        checkRange(issues, at + ".bulk_density_Mg_m3", l.bulk_density_kg_m3 / 1e3, Range{0.5, 2.2},
                   "Mg/m3");
        checkRange(issues, at + ".particle_density_Mg_m3", l.particle_density_kg_m3 / 1e3,
                   Range{2.0, 3.0}, "Mg/m3");
        if (l.bulk_density_kg_m3 >= l.particle_density_kg_m3) {
            issues.push_back({at + ".bulk_density_Mg_m3",
                              "bulk density must be below the particle density (" +
                                  formatNumber(l.particle_density_kg_m3 / 1e3) + " Mg/m3)"});
        }
        if (l.matric_suction_pa && !(*l.matric_suction_pa > 0.0)) {
            issues.push_back({at + ".matric_suction_hPa",
                              formatNumber(*l.matric_suction_pa / 100.0) +
                                  " hPa: matric suction is a positive pressure (the tension of "
                                  "the soil water), in (0, 1e6] hPa"});
        } else {
            checkOptional(issues, at + ".matric_suction_hPa", l.matric_suction_pa, Range{1e-3, 1e6},
                          "hPa", 0.01);
        }
        checkOptional(issues, at + ".sigma_pc_kPa", l.precompression_pa, Range{1.0, 5000.0}, "kPa",
                      1e-3);
        checkOptional(issues, at + ".nu", l.concentration, Range{2.5, 12.0}, "");
        if (!l.precompression_pa && !(l.clay_kg_kg && l.matric_suction_pa)) {
            issues.push_back({at,
                              "give sigma_pc_kPa, or clay_kg_kg and matric_suction_hPa for "
                              "the pedotransfer function of Schjonning & Lamande 2018"});
        }
        if (l.compression) {
            const CompressionLaw& c = *l.compression;
            const std::string cat = at + ".compression";
            checkOptional(issues, cat + ".N", c.virgin_n, Range{1.0, 5.0}, "");
            checkRange(issues, cat + ".lambda", c.lambda, Range{1e-4, 1.0}, "");
            checkRange(issues, cat + ".kappa", c.kappa, Range{0.0, 1.0}, "");
            checkOptional(issues, cat + ".kappa2", c.kappa_steep, Range{0.0, 1.0}, "");
            checkRange(issues, cat + ".m", c.yield_offset, Range{0.0, 10.0}, "");
            if (!(c.kappa < c.lambda)) {
                issues.push_back(
                    {cat + ".kappa", "kappa = " + formatNumber(c.kappa) +
                                         " must be below lambda = " + formatNumber(c.lambda)});
            }
            if (c.kappa_steep && !(*c.kappa_steep >= c.kappa && *c.kappa_steep < c.lambda)) {
                issues.push_back({cat + ".kappa2", "kappa2 = " + formatNumber(*c.kappa_steep) +
                                                       " must lie in [kappa, lambda)"});
            }
        }
    }
    return issues;
}

double precompressionStress(double clay, double bulk_density_kg_m3, double matric_suction_pa) {
    if (!(clay >= 0.0 && clay <= 1.0) || !(bulk_density_kg_m3 > 0.0) ||
        !(matric_suction_pa > 0.0)) {
        throw std::invalid_argument(
            "precompressionStress: clay in [0, 1] kg/kg, density and "
            "suction > 0 (clay " +
            formatNumber(clay) + ")");
    }
    const double pf = std::log10(matric_suction_pa / 100.0);  // h in hPa
    const double root =
        -26.51 + 25.57 * (bulk_density_kg_m3 / 1e3) - 20.40 * clay + 10.26 * clay * pf;
    const double kpa = root > 0.0 ? root * root : 0.0;
    return kpa * 1e3;
}

double precompressionStress(const SoilLayer& layer) {
    if (layer.precompression_pa) return *layer.precompression_pa;
    if (!layer.clay_kg_kg || !layer.matric_suction_pa) {
        throw std::invalid_argument(
            "precompressionStress: the layer has neither sigma_pc nor "
            "clay and suction");
    }
    return precompressionStress(*layer.clay_kg_kg, layer.bulk_density_kg_m3,
                                *layer.matric_suction_pa);
}

double compactedDensity(double particle_density, double bulk_density, const CompressionLaw& law,
                        double stress_pa) {
    if (!law.virgin_n) throw std::invalid_argument("compactedDensity: N is not set");
    const double p_kpa = stress_pa / 1e3;
    if (!(p_kpa > 1.0)) return bulk_density;  // at or below the reference 1 kPa: no yield
    const double n = *law.virgin_n, lambda = law.lambda, kappa = law.kappa;
    const double kappa2 = law.kappa_steep.value_or(kappa);
    const double v_i = particle_density / bulk_density;
    const double x = std::log(p_kpa);
    // K1: the recompression line v_i − κ x meets the yield line (N − λ m) − λ x at x₁; the
    // steeper line κ′ from there meets the VCL at x₂.
    const double x1 = (n - lambda * law.yield_offset - v_i) / (lambda - kappa);
    if (x <= x1) return bulk_density;
    const double v1 = v_i - kappa * x1;
    const double n2 = v1 + kappa2 * x1;
    const double x2 = kappa2 < lambda ? (n - n2) / (lambda - kappa2) : x1;
    // K3: on the steeper line or the VCL at p, then the elastic rebound κ back to 1 kPa.
    const double v_f = x <= x2 ? n2 - kappa2 * x + kappa * x : n - lambda * x + kappa * x;
    return v_f < v_i ? particle_density / v_f : bulk_density;
}

double compactedDensity(const SoilLayer& layer, double stress_pa) {
    if (!layer.compression) return layer.bulk_density_kg_m3;
    CompressionLaw law = *layer.compression;
    if (!law.virgin_n) {
        // K2: the VCL through the layer's state at its precompression stress, so that it yields
        // exactly at σ_pc: N = v_i + (λ − κ) ln σ_pc + λ m.
        const double v_i = layer.particle_density_kg_m3 / layer.bulk_density_kg_m3;
        const double sigma_pc_kpa = std::max(precompressionStress(layer) / 1e3, 1.0);
        law.virgin_n =
            v_i + (law.lambda - law.kappa) * std::log(sigma_pc_kpa) + law.lambda * law.yield_offset;
    }
    return compactedDensity(layer.particle_density_kg_m3, layer.bulk_density_kg_m3, law, stress_pa);
}

}  // namespace terra::soil
