#include "core/soil/soil_profile.h"

#include <gtest/gtest.h>

#include <cmath>

namespace terra::soil {
namespace {

TEST(SoilProfile, PrecompressionStressOfSchjonningAndLamande) {
    // √σ_pc = −26.51 + 25.57 ρ_b − 20.40 C + 10.26 C pF (kPa, Mg/m³, kg/kg, pF = log10 h/hPa):
    // the R package soilphysics' example (1.46 Mg/m³, 100 hPa, 0.3 kg/kg) gives 117.90 kPa, and
    // by hand: pF 2, √σ = −26.51 + 37.3322 − 6.12 + 6.156 = 10.8582.
    EXPECT_NEAR(precompressionStress(0.30, 1460.0, 100e2) / 1e3, 117.90, 0.005);
    EXPECT_NEAR(precompressionStress(0.30, 1460.0, 100e2) / 1e3, 10.8582 * 10.8582, 1e-9);
    EXPECT_NEAR(precompressionStress(0.30, 1460.0, 60e2) / 1e3, 103.54, 0.005);
    EXPECT_NEAR(precompressionStress(0.30, 1460.0, 300e2) / 1e3, 151.95, 0.005);
    EXPECT_NEAR(precompressionStress(0.10, 1500.0, 100e2) / 1e3, 140.59, 0.005);
    EXPECT_NEAR(precompressionStress(0.20, 1600.0, 100e2) / 1e3, 208.11, 0.005);
    // A negative root is 0 (the function's own floor).
    EXPECT_EQ(precompressionStress(0.9, 900.0, 10e2), 0.0);
}

TEST(SoilProfile, OSullivanCompressionMatchesItsWorkedExample) {
    // soilphysics' soilDeformation example: p = 300 kPa, ρ_s 2.67, ρ_b 1.55, N 1.9392,
    // λ 0.06037, κ 0.00608, κ′ 0.01916, m 1.3 → ρ_b 1.6385 (v 1.72258 → 1.62954).
    CompressionLaw law;
    law.virgin_n = 1.9392;
    law.lambda = 0.06037;
    law.kappa = 0.00608;
    law.kappa_steep = 0.01916;
    law.yield_offset = 1.3;
    EXPECT_NEAR(compactedDensity(2670.0, 1550.0, law, 300e3) / 1e3, 1.6385, 5e-5);
    EXPECT_NEAR(2.67 / (compactedDensity(2670.0, 1550.0, law, 300e3) / 1e3), 1.62954, 5e-5);
    // On the steeper line below the VCL (p₁ = 12.7 kPa < p < p₂ = 85.5 kPa), and at 100 kPa.
    EXPECT_NEAR(compactedDensity(2670.0, 1550.0, law, 20e3) / 1e3, 1.55533, 5e-5);
    EXPECT_NEAR(compactedDensity(2670.0, 1550.0, law, 50e3) / 1e3, 1.56626, 5e-5);
    EXPECT_NEAR(compactedDensity(2670.0, 1550.0, law, 100e3) / 1e3, 1.58064, 5e-5);
    // Below yield nothing changes.
    EXPECT_EQ(compactedDensity(2670.0, 1550.0, law, 10e3), 1550.0);
}

TEST(SoilProfile, ADerivedVirginLineYieldsAtThePrecompressionStress) {
    SoilLayer layer;
    layer.bulk_density_kg_m3 = 1450.0;
    layer.precompression_pa = 80e3;
    layer.compression = CompressionLaw{std::nullopt, 0.05, 0.005, std::nullopt, 0.0};
    EXPECT_EQ(compactedDensity(layer, 79e3), 1450.0);
    // Above σ_pc: on the VCL through (v at σ_pc), then the rebound: v_f = v_i − (λ − κ) ln(p/σ_pc).
    const double v_i = 2650.0 / 1450.0;
    const double v_f = v_i - (0.05 - 0.005) * std::log(160.0 / 80.0);
    EXPECT_NEAR(compactedDensity(layer, 160e3), 2650.0 / v_f, 1e-9);
    // Loading again to the same stress after that compaction changes nothing more.
    SoilLayer after = layer;
    after.bulk_density_kg_m3 = compactedDensity(layer, 160e3);
    after.precompression_pa = 160e3;
    EXPECT_NEAR(compactedDensity(after, 160e3), after.bulk_density_kg_m3, 1e-9);
}

SoilProfile twoLayers() {
    SoilProfile p;
    SoilLayer top;
    top.top_m = 0.0;
    top.bottom_m = 0.3;
    top.clay_kg_kg = 0.15;
    top.matric_suction_pa = 100e2;
    SoilLayer sub = top;
    sub.top_m = 0.3;
    sub.bottom_m = 1.0;
    p.layers = {top, sub};
    return p;
}

TEST(SoilProfile, BadProfilesNameTheLayerAndTheField) {
    EXPECT_TRUE(validate(twoLayers()).empty());
    auto first = [](const SoilProfile& p) {
        const std::vector<Issue> issues = validate(p);
        return issues.empty() ? Issue{} : issues.front();
    };
    SoilProfile overlap = twoLayers();
    overlap.layers[1].top_m = 0.25;
    EXPECT_EQ(first(overlap).where, "profile.layers[1].top_m");
    EXPECT_NE(first(overlap).message.find("overlaps"), std::string::npos);
    SoilProfile percent = twoLayers();
    percent.layers[0].clay_kg_kg = 15.0;
    EXPECT_EQ(first(percent).where, "profile.layers[0].clay_kg_kg");
    EXPECT_NE(first(percent).message.find("15 % is 0.15"), std::string::npos);
    SoilProfile suction = twoLayers();
    suction.layers[1].matric_suction_pa = -100e2;
    EXPECT_EQ(first(suction).where, "profile.layers[1].matric_suction_hPa");
    SoilProfile nothing = twoLayers();
    nothing.layers[0].clay_kg_kg.reset();
    EXPECT_EQ(first(nothing).where, "profile.layers[0]");
    SoilProfile gap = twoLayers();
    gap.layers[0].top_m = 0.1;
    EXPECT_EQ(first(gap).where, "profile.layers[0].top_m");
    EXPECT_TRUE(validate(SoilProfile{}).size() == 1);
}

TEST(SoilProfile, TheLayerAtADepth) {
    const SoilProfile p = twoLayers();
    EXPECT_EQ(p.layerIndexAt(0.0), 0);
    EXPECT_EQ(p.layerIndexAt(0.3), 0);
    EXPECT_EQ(p.layerIndexAt(0.31), 1);
    EXPECT_EQ(p.layerIndexAt(1.2), -1);
}

}  // namespace
}  // namespace terra::soil
