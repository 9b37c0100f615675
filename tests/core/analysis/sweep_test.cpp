#include "core/analysis/sweep.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/units.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::analysis {
namespace {

using contact::testing::kDeg;

SweepSpec thesisSpec() {
    SweepSpec spec;
    spec.slips = {0.0, 0.25, 0.5, 0.75};
    spec.slip_angles_rad = {5 * kDeg, 15 * kDeg, 30 * kDeg};
    return spec;
}

TEST(Sweep, RowsAreTheModelAtEachPoint) {
    const auto p = contact::testing::sandyLoam();
    const SweepResult result = sweepSlip(p, thesisSpec());
    ASSERT_EQ(result.table.rows.size(), 12u);
    EXPECT_TRUE(result.warnings.empty());
    const auto& t = result.table;
    for (const auto& row : t.rows) {
        const double beta = row[t.column("slip_angle_deg")] * kDeg;
        const double s = row[t.column("slip")];
        const double tf = row[t.column("entry_angle_deg")] * kDeg;
        EXPECT_NEAR(row[t.column("Fz_N")], 58.86, 1e-8);  // solved: F_z = W
        const auto f = contact::computeForces(
            p, contact::OperatingPoint<double>{s, beta, tf, 0.0, std::nullopt});
        EXPECT_NEAR(row[t.column("Fx_N")], f.fx, 1e-9);
        EXPECT_NEAR(row[t.column("Fs_N")], f.fs, 1e-9);
        EXPECT_NEAR(row[t.column("sinkage_m")], 0.092 * (1 - std::cos(tf)), 1e-15);
    }
}

TEST(Sweep, ThreadCountDoesNotChangeResults) {
    const auto p = contact::testing::clayeySoil();
    SweepSpec one = thesisSpec(), many = thesisSpec();
    one.threads = 1;
    many.threads = 3;
    EXPECT_EQ(sweepSlip(p, one).table.rows, sweepSlip(p, many).table.rows);
}

TEST(Sweep, PointsWithoutEquilibriumAreListedNotPlotted) {
    SweepSpec spec = thesisSpec();
    spec.load_n = 2000.0;  // far more than dry sand can carry under wheel A
    const SweepResult result = sweepSlip(contact::testing::drySand(), spec);
    EXPECT_TRUE(result.table.rows.empty());
    EXPECT_EQ(result.warnings.size(), 12u);
    EXPECT_NE(result.warnings[0].find("no equilibrium"), std::string::npos);
}

TEST(Sweep, BadSpecIsRejectedWithTheField) {
    SweepSpec spec = thesisSpec();
    spec.slips.push_back(1.5);  // s = 1 is in the domain (docs/model.md, "Full slip"); 1.5 is not
    try {
        sweepSlip(contact::testing::sandyLoam(), spec);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("slip: 1.5 is outside the allowed range [-1, 1]"),
                  std::string::npos)
            << e.what();
    }
}

// Regression: the exit condition and θ_m were not validated, and solveEntryAngle's exception for
// a rut ratio of 1.5 escaped a std::jthread worker: std::terminate killed the process.
TEST(Sweep, BadExitConditionAndMaxStressAngleAreRejectedUpFront) {
    struct Bad {
        contact::ExitCondition exit;
        std::optional<double> theta_m;
        const char* field;
        const char* range;
    };
    const Bad cases[] = {
        {{contact::ExitCondition::Kind::kRutRatio, 1.5}, std::nullopt, "rut_ratio: 1.5", "[0, 1]"},
        {{contact::ExitCondition::Kind::kRutRatio, -0.1},
         std::nullopt,
         "rut_ratio: -0.1",
         "[0, 1]"},
        {{contact::ExitCondition::Kind::kAngle, 5 * kDeg},
         std::nullopt,
         "exit_angle_deg: 5",
         "[-90, 0]"},
        {{}, 120 * kDeg, "max_stress_angle_deg: 120", "[-90, 90]"},
    };
    for (const Bad& bad : cases) {
        for (bool with_load : {true, false}) {
            SweepSpec spec = thesisSpec();
            spec.exit = bad.exit;
            spec.max_stress_angle_rad = bad.theta_m;
            if (!with_load) spec.load_n.reset();
            try {
                sweepSlip(contact::testing::sandyLoam(), spec);
                FAIL() << bad.field << " accepted";
            } catch (const std::invalid_argument& e) {
                EXPECT_NE(std::string(e.what()).find(bad.field), std::string::npos) << e.what();
                EXPECT_NE(std::string(e.what()).find(bad.range), std::string::npos) << e.what();
            }
        }
    }
}

TEST(Sweep, ExceptionInAWorkerReachesTheCaller) {
    // A NaN modulus passes the spec checks but makes the root finder throw inside the workers
    // (Boost: "do not bracket the root"); it must arrive here as an exception, with any number
    // of threads, instead of terminating the process.
    auto p = contact::testing::sandyLoam();
    p.pressure_modulus = std::nan("");
    for (int threads : {1, 2, 3}) {
        SweepSpec spec = thesisSpec();
        spec.threads = threads;
        EXPECT_THROW(sweepSlip(p, spec), std::exception) << threads << " threads";
    }
}

TEST(Sweep, CancelKeepsWhatWasComputed) {
    std::atomic<bool> cancel{true};
    SweepSpec spec = thesisSpec();
    spec.cancel = &cancel;
    const SweepResult result = sweepSlip(contact::testing::sandyLoam(), spec);
    EXPECT_TRUE(result.cancelled);
    EXPECT_TRUE(result.table.rows.empty());
}

TEST(Sweep, LinspaceAndThesisSlips) {
    const auto v = linspace(0.0, 0.99, 100);
    ASSERT_EQ(v.size(), 100u);
    EXPECT_EQ(v[27], 0.27);  // decimal grids land on the decimal value
    EXPECT_EQ(v.back(), 0.99);
    const auto s = thesisSlips();
    EXPECT_EQ(s.size(), 100u);
    EXPECT_EQ(s.back(), 0.99);
}

soil::SoilParameters sandyLoamSoil() {
    soil::SoilParameters soil;  // Table 2.1 sandy loam, by hand in SI
    soil.sinkage_exponent = 0.7;
    soil.cohesion_pa = 1.7e3;
    soil.friction_angle_rad = 29.0 * kDeg;
    soil.cohesive_modulus = 5.3e3;
    soil.frictional_modulus = 1.515e6;
    soil.shear_modulus_m = 0.025;
    soil.unit_weight_n_m3 = 15.2e3;
    soil.max_shear_deformation_m = 0.02;
    return soil;
}

TEST(Sensitivity, FrictionAndCohesionRaiseDrawbarPull) {
    // Section 4.2: F_x grows with φ and with c (they scale the shear strength, Eq. 2.21).
    const wheel::WheelParameters wheel{"A", "", 0.092, 0.107};
    SweepSpec spec;
    spec.slips = {0.3};
    spec.slip_angles_rad = {15 * kDeg};
    for (const char* key : {"phi_deg", "c_kPa"}) {
        SensitivityParameter parameter;
        for (const auto& p : thesisSensitivityParameters()) {
            if (p.key == key) parameter = p;
        }
        const SweepResult r = sensitivity(sandyLoamSoil(), wheel, parameter, spec);
        ASSERT_EQ(r.table.rows.size(), 4u) << key;
        EXPECT_EQ(r.table.columns[0], key);
        const auto fx = r.table.values("Fx_N");
        for (std::size_t i = 1; i < fx.size(); ++i) EXPECT_GT(fx[i], fx[i - 1]) << key;
    }
}

TEST(Sensitivity, Table41HasSixParametersOfFourValues) {
    const auto table = thesisSensitivityParameters();
    ASSERT_EQ(table.size(), 6u);
    for (const auto& p : table) {
        EXPECT_EQ(p.values.size(), 4u);
        EXPECT_NE(soil::findSoilField(p.key), nullptr) << p.key;
    }
    EXPECT_THROW(
        sensitivity(sandyLoamSoil(), {"A", "", 0.092, 0.107}, {"nope", {1.0}}, thesisSpec()),
        std::invalid_argument);
}

}  // namespace
}  // namespace terra::analysis
