#include "core/soil/soil_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "core/wheel/wheel_parameters.h"

namespace terra::soil {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A unit conversion is one multiplication: a few ulps at most.
constexpr double kConversionRelTol = 1e-14;
// Values shown to the user may be rounded to 12 significant digits (29, not 29.000000000000004).
constexpr double kUserValueRelTol = 1e-11;

const SoilField& field(const std::string& key) {
    const SoilField* f = findSoilField(key);
    if (f == nullptr) throw std::logic_error("no soil field " + key);
    return *f;
}

// The SI value that a file value of `key` becomes.
double toSi(const std::string& key, double user_value) {
    SoilParameters soil;
    setUserValue(soil, field(key), user_value);
    return soil.*field(key).member;
}

// The first issue located at `where`, or nullptr.
const Issue* issueAt(const std::vector<Issue>& issues, const std::string& where) {
    for (const Issue& issue : issues) {
        if (issue.where == where) return &issue;
    }
    return nullptr;
}

TEST(SoilFields, TableHoldsTheTwelveDocumentedKeys) {
    std::set<std::string> required, optional;
    for (const SoilField& f : soilFields()) (f.required ? required : optional).insert(f.key);
    EXPECT_EQ(soilFields().size(), 12u);
    EXPECT_EQ(required,
              (std::set<std::string>{"n", "c_kPa", "phi_deg", "kc", "kphi", "K_m", "gamma_kN_m3"}));
    EXPECT_EQ(optional, (std::set<std::string>{"a0", "a1", "jmax_m", "n1", "slip_sinkage"}));
}

TEST(SoilFields, FindByKey) {
    EXPECT_STREQ(field("phi_deg").unit, "deg");
    EXPECT_EQ(findSoilField("phi"), nullptr);
    EXPECT_EQ(findSoilField(""), nullptr);
    EXPECT_EQ(findSoilField("PHI_DEG"), nullptr);
}

TEST(SoilFields, ConvertFileUnitsToSi) {
    // 29° = 29 π / 180 rad = 0.50614548307835556 rad.
    EXPECT_NEAR(toSi("phi_deg", 29.0), 0.50614548307835556, 1e-15);
    EXPECT_NEAR(toSi("c_kPa", 1.7), 1700.0, 1700.0 * kConversionRelTol);           // Pa
    EXPECT_NEAR(toSi("kc", 5.3), 5300.0, 5300.0 * kConversionRelTol);              // N/m^(n+1)
    EXPECT_NEAR(toSi("kphi", 1515.0), 1.515e6, 1.515e6 * kConversionRelTol);       // N/m^(n+2)
    EXPECT_NEAR(toSi("gamma_kN_m3", 15.2), 15200.0, 15200.0 * kConversionRelTol);  // N/m³
    // Dimensionless and metre fields are stored as given.
    EXPECT_EQ(toSi("n", 0.7), 0.7);
    EXPECT_EQ(toSi("K_m", 0.025), 0.025);
    EXPECT_EQ(toSi("jmax_m", 0.02), 0.02);
    EXPECT_EQ(toSi("a0", 0.2), 0.2);
    EXPECT_EQ(toSi("a1", -0.3), -0.3);
    EXPECT_EQ(toSi("n1", 0.1), 0.1);
    EXPECT_EQ(toSi("slip_sinkage", 2.5), 2.5);
}

TEST(SoilFields, FieldsWriteTheirOwnMember) {
    SoilParameters soil;
    setUserValue(soil, field("c_kPa"), 4.14);
    setUserValue(soil, field("kphi"), 692.2);
    EXPECT_NEAR(soil.cohesion_pa, 4140.0, 4140.0 * kConversionRelTol);
    EXPECT_NEAR(soil.frictional_modulus, 692200.0, 692200.0 * kConversionRelTol);
    // Untouched members keep their defaults (sandy loam, thesis Table 2.1).
    EXPECT_EQ(soil.sinkage_exponent, 0.7);
    EXPECT_EQ(soil.cohesive_modulus, 5.3e3);
}

TEST(SoilFields, UserValueConvertsSiBack) {
    SoilParameters soil;
    soil.friction_angle_rad = 0.5;  // 0.5 × 180 / π = 90 / π deg
    soil.cohesion_pa = 2500.0;
    soil.frictional_modulus = 9.0e5;
    soil.unit_weight_n_m3 = 16180.0;
    EXPECT_NEAR(userValue(soil, field("phi_deg")), 28.647889756541160,
                28.647889756541160 * kUserValueRelTol);
    EXPECT_NEAR(userValue(soil, field("c_kPa")), 2.5, 2.5 * kUserValueRelTol);
    EXPECT_NEAR(userValue(soil, field("kphi")), 900.0, 900.0 * kUserValueRelTol);
    EXPECT_NEAR(userValue(soil, field("gamma_kN_m3")), 16.18, 16.18 * kUserValueRelTol);
}

TEST(SoilFields, UserValueGivesBackTheTypedDegrees) {
    // 29 × (π/180) / (π/180) is 29.000000000000004 in doubles; the user typed 29.
    for (double deg : {29.0, 30.0, 31.1, 29.8, 13.0}) {
        SoilParameters soil;
        setUserValue(soil, field("phi_deg"), deg);
        EXPECT_EQ(userValue(soil, field("phi_deg")), deg);
    }
}

TEST(SoilValidate, DefaultsAreValid) {
    const SoilParameters soil;
    EXPECT_TRUE(validate(soil).empty()) << formatIssues(validate(soil));
    EXPECT_NO_THROW(requireValid(soil));
}

TEST(SoilValidate, ReportsEveryOutOfRangeFieldWithValueAndRange) {
    SoilParameters soil;
    setUserValue(soil, field("phi_deg"), 75.0);
    soil.cohesion_pa = -1000.0;       // -1 kPa
    soil.shear_modulus_m = 0.0;       // K = 0 excluded
    soil.unit_weight_n_m3 = 31000.0;  // 31 kN/m³
    soil.frictional_modulus = 2.0e8;  // 2e5 kN/m^(n+2)
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 5u) << formatIssues(issues);

    const Issue* phi = issueAt(issues, "phi_deg");
    ASSERT_NE(phi, nullptr);
    EXPECT_EQ(phi->message, "75 is outside the allowed range [0, 60) deg");
    const Issue* c = issueAt(issues, "c_kPa");
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->message, "-1 is outside the allowed range [0, 200] kPa");
    const Issue* k = issueAt(issues, "K_m");
    ASSERT_NE(k, nullptr);
    EXPECT_EQ(k->message, "0 is outside the allowed range [1e-04, 0.5] m");
    const Issue* gamma = issueAt(issues, "gamma_kN_m3");
    ASSERT_NE(gamma, nullptr);
    EXPECT_EQ(gamma->message, "31 is outside the allowed range [0.5, 30] kN/m³");
    const Issue* kphi = issueAt(issues, "kphi");
    ASSERT_NE(kphi, nullptr);
    EXPECT_EQ(kphi->message, "2e+05 is outside the allowed range [0, 1e+05] kN/m^(n+2)");
}

TEST(SoilValidate, PrefixIsPrependedToTheField) {
    SoilParameters soil;
    soil.cohesion_pa = 250e3;  // 250 kPa
    const std::vector<Issue> issues = validate(soil, "soil.");
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "soil.c_kPa");
    EXPECT_EQ(issues[0].message, "250 is outside the allowed range [0, 200] kPa");
}

TEST(SoilValidate, NonFiniteValuesAreReported) {
    SoilParameters soil;
    soil.cohesion_pa = kNaN;
    soil.cohesive_modulus = -kInf;
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 2u) << formatIssues(issues);
    const Issue* c = issueAt(issues, "c_kPa");
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->message, "nan is not a finite number; allowed range [0, 200] kPa");
    const Issue* kc = issueAt(issues, "kc");
    ASSERT_NE(kc, nullptr);
    EXPECT_NE(kc->message.find("-inf is not a finite number"), std::string::npos) << kc->message;
}

TEST(SoilValidate, RangeEndsOfTheTable) {
    SoilParameters soil;
    setUserValue(soil, field("phi_deg"), 0.0);  // [0, ...: allowed
    soil.cohesion_pa = 200e3;                   // ..., 200]: allowed
    soil.shear_modulus_m = 0.5;                 // ..., 0.5]: allowed
    soil.sinkage_exponent = 2.0;                // [0.1, 2]: allowed
    soil.max_stress_a1 = -1.0;                  // [-1, ...: allowed
    EXPECT_TRUE(validate(soil).empty()) << formatIssues(validate(soil));
}

TEST(SoilValidate, RequireValidThrowsInvalidArgumentNamingTheField) {
    SoilParameters soil;
    setUserValue(soil, field("phi_deg"), 75.0);
    soil.shear_modulus_m = -0.01;
    try {
        requireValid(soil);
        FAIL() << "requireValid accepted phi = 75 deg and K = -0.01 m";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("soil.phi_deg: 75 is outside the allowed range [0, 60) deg"),
                  std::string::npos)
            << what;
        EXPECT_NE(what.find("soil.K_m: -0.01 is outside the allowed range [1e-04, 0.5] m"),
                  std::string::npos)
            << what;
    }
}

TEST(SoilValidate, SlipDependentExponentMustStayInRangeAtFullSlip) {
    SoilParameters soil;
    soil.sinkage_exponent = 1.5;
    soil.sinkage_exponent_slip = 0.8;  // N(s = 1) = 2.3 > 2
    std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "n1");
    EXPECT_NE(issues[0].message.find("2.3"), std::string::npos) << issues[0].message;
    EXPECT_NE(issues[0].message.find("[0.1, 2]"), std::string::npos) << issues[0].message;

    soil.sinkage_exponent = 0.5;
    soil.sinkage_exponent_slip = -0.4375;  // N(s = 1) = 0.0625 < 0.1 (exact in binary)
    issues = validate(soil, "soil.");
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "soil.n1");
    EXPECT_NE(issues[0].message.find("0.0625"), std::string::npos) << issues[0].message;
    EXPECT_THROW(requireValid(soil), std::invalid_argument);

    soil.sinkage_exponent = 1.5;
    soil.sinkage_exponent_slip = 0.5;  // N(s = 1) = 2 exactly, N(s = −1) = 1: allowed
    EXPECT_TRUE(validate(soil).empty()) << formatIssues(validate(soil));
}

// Regression: only n + n1 (s → 1) was checked, but braking slips reach s → −1, where
// N = n − n1: n = 0.3, n1 = 0.5 gave N = −0.2 < 0.1 at strong braking, accepted.
TEST(SoilValidate, SlipDependentExponentMustStayInRangeWhenBraking) {
    SoilParameters soil;
    soil.sinkage_exponent = 0.3;
    soil.sinkage_exponent_slip = 0.5;  // N(s = 1) = 0.8 fine, N(s = −1) = −0.2 < 0.1
    std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "n1");
    EXPECT_NE(issues[0].message.find("n - n1 = -0.2"), std::string::npos) << issues[0].message;
    EXPECT_NE(issues[0].message.find("[0.1, 2]"), std::string::npos) << issues[0].message;
    EXPECT_NE(issues[0].message.find("[-1, 1]"), std::string::npos) << issues[0].message;

    soil.sinkage_exponent = 1.75;
    soil.sinkage_exponent_slip = -0.5;  // N(s = −1) = 2.25 > 2
    issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_NE(issues[0].message.find("2.25"), std::string::npos) << issues[0].message;

    soil.sinkage_exponent = 0.6;
    soil.sinkage_exponent_slip =
        0.5;  // N from 0.1 (0.6 − 0.5 in binary: 0.0999…98) to 1.1: allowed
    EXPECT_TRUE(validate(soil).empty()) << formatIssues(validate(soil));
}

TEST(SoilValidate, InfiniteShearLimitMeansNoLimit) {
    SoilParameters soil;
    soil.max_shear_deformation_m = kInf;
    EXPECT_FALSE(soil.hasShearLimit());
    EXPECT_TRUE(validate(soil).empty()) << formatIssues(validate(soil));

    soil.max_shear_deformation_m = 0.02;
    EXPECT_TRUE(soil.hasShearLimit());
    EXPECT_TRUE(validate(soil).empty());
}

TEST(SoilValidate, InvalidShearLimitsAreReported) {
    for (double jmax : {0.0, -0.02, 1.5, -kInf, kNaN}) {
        SoilParameters soil;
        soil.max_shear_deformation_m = jmax;
        const std::vector<Issue> issues = validate(soil);
        ASSERT_EQ(issues.size(), 1u) << jmax << ": " << formatIssues(issues);
        EXPECT_EQ(issues[0].where, "jmax_m");
        EXPECT_NE(issues[0].message.find("[1e-04, 1] m"), std::string::npos) << issues[0].message;
    }
}

TEST(SoilValidate, InfinityIsNoLimitOnlyForTheShearLimit) {
    SoilParameters soil;
    soil.max_stress_a0 = kInf;  // optional like j_max, but +inf is not a "no limit" here
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "a0");
    EXPECT_NE(issues[0].message.find("inf is not a finite number"), std::string::npos);
}

// Regression: validate() flagged n1 when only n was out of range (n = 0, n1 = 0 gave a second
// issue "n1: n + n1 = 0 leaves the allowed range ..."), so an editor marked the untouched n1
// invalid.
TEST(SoilValidate, OutOfRangeExponentIsReportedOnlyOnN) {
    SoilParameters soil;
    soil.sinkage_exponent = 0.0;
    soil.sinkage_exponent_slip = 0.0;
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "n");
}

// Regression: validate() appended the unit "-" of dimensionless fields to its messages
// ("n: 3 is outside the allowed range [0.1, 2] -"), while the JSON loader drops it.
TEST(SoilValidate, DimensionlessFieldsHaveNoUnitSuffix) {
    SoilParameters soil;
    soil.sinkage_exponent = 3.0;
    soil.sinkage_exponent_slip = -1.0;  // keeps N(s = 1) = 2 inside the range
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].message, "3 is outside the allowed range [0.1, 2]");
}

// Regression: phi_deg's range is [0, 60), but validate() accepted φ = 60° once in radians, because
// 60 × (π/180) / (π/180) = 59.99999999999999 < 60. The JSON loader rejects the same 60°.
TEST(SoilValidate, SixtyDegreesIsOutsideTheRangeAlsoInRadians) {
    SoilParameters soil;
    setUserValue(soil, field("phi_deg"), 60.0);
    const std::vector<Issue> issues = validate(soil);
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "phi_deg");
    EXPECT_THROW(requireValid(soil), std::invalid_argument);
}

}  // namespace
}  // namespace terra::soil

namespace terra::wheel {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(WheelValidate, DefaultsAreValid) {
    const WheelParameters wheel;
    EXPECT_TRUE(validate(wheel).empty());
    EXPECT_NO_THROW(requireValid(wheel));
}

TEST(WheelValidate, NonPositiveRadiusIsReported) {
    for (double r : {0.0, -0.092}) {
        WheelParameters wheel;
        wheel.radius_m = r;
        const std::vector<Issue> issues = validate(wheel);
        ASSERT_EQ(issues.size(), 1u) << r;
        EXPECT_EQ(issues[0].where, "r_m");
        EXPECT_EQ(issues[0].message, (r == 0.0 ? "0" : "-0.092") +
                                         std::string(" is outside the allowed range [0.01, 5] m"));
    }
}

TEST(WheelValidate, NonPositiveOrNaNWidthIsReported) {
    WheelParameters wheel;
    wheel.width_m = 0.0;
    std::vector<Issue> issues = validate(wheel, "wheel.");
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "wheel.b_m");
    EXPECT_EQ(issues[0].message, "0 is outside the allowed range [0.005, 5] m");

    wheel.width_m = kNaN;
    issues = validate(wheel);
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "b_m");
    EXPECT_EQ(issues[0].message, "nan is not a finite number; allowed range [0.005, 5] m");
}

TEST(WheelValidate, BothFieldsReportedAndRequireValidThrows) {
    WheelParameters wheel;
    wheel.radius_m = kNaN;
    wheel.width_m = -0.1;
    EXPECT_EQ(validate(wheel).size(), 2u);
    try {
        requireValid(wheel);
        FAIL() << "requireValid accepted r = NaN, b = -0.1";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("wheel.r_m: nan is not a finite number"), std::string::npos) << what;
        EXPECT_NE(what.find("wheel.b_m: -0.1 is outside the allowed range [0.005, 5] m"),
                  std::string::npos)
            << what;
    }
}

}  // namespace
}  // namespace terra::wheel
