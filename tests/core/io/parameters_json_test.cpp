#include "core/io/parameters_json.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/contact/contact_parameters.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
// SI values come from one multiplication of the file value: a few ulps at most.
constexpr double kConversionRelTol = 1e-14;

const fs::path kSoilDir = fs::path(TERRA_RESOURCE_DIR) / "soils";
const fs::path kWheelDir = fs::path(TERRA_RESOURCE_DIR) / "wheels";
const fs::path kData = fs::path(TERRA_TEST_DATA_DIR);

using terra::testing::contains;

std::vector<fs::path> jsonFiles(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

// The preset names of a directory: file stems, sorted as strings.
std::vector<std::string> stems(const fs::path& dir) {
    std::vector<std::string> names;
    for (const fs::path& file : jsonFiles(dir)) names.push_back(file.stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// The required keys of sandy loam (thesis Table 2.1, file units), for building bad inputs.
json sandyLoamJson() {
    return json{{"name", "test soil"}, {"n", 0.7},       {"c_kPa", 1.7}, {"phi_deg", 29.0},
                {"kc", 5.3},           {"kphi", 1515.0}, {"K_m", 0.025}, {"gamma_kN_m3", 15.2}};
}

using terra::testing::TempDir;

void writeText(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

// ---- Presets ---------------------------------------------------------------------------------

TEST(SoilPresets, EveryPresetLoadsWithoutIssues) {
    const std::vector<fs::path> files = jsonFiles(kSoilDir);
    ASSERT_GE(files.size(), 3u) << kSoilDir;  // at least the three thesis soils
    for (const fs::path& file : files) {
        const Result<soil::SoilParameters> soil = loadSoil(file);
        ASSERT_TRUE(soil.ok()) << file << ":\n" << soil.message();
        EXPECT_TRUE(soil.issues().empty()) << file;
        EXPECT_FALSE(soil->name.empty()) << file;
        EXPECT_FALSE(soil->source.empty()) << file;
        EXPECT_TRUE(soil::validate(*soil).empty()) << file << soil::validate(*soil).size();
    }
}

TEST(WheelPresets, EveryPresetLoadsWithoutIssues) {
    const std::vector<fs::path> files = jsonFiles(kWheelDir);
    ASSERT_GE(files.size(), 2u) << kWheelDir;
    for (const fs::path& file : files) {
        const Result<wheel::WheelParameters> wheel = loadWheel(file);
        ASSERT_TRUE(wheel.ok()) << file << ":\n" << wheel.message();
        EXPECT_FALSE(wheel->name.empty()) << file;
        EXPECT_TRUE(wheel::validate(*wheel).empty()) << file;
    }
}

TEST(SoilPresets, SandyLoamMatchesThesisTable21InSi) {
    const Result<soil::SoilParameters> soil = loadSoil(kSoilDir / "sandy-loam.json");
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->name, "sandy loam");
    EXPECT_EQ(soil->sinkage_exponent, 0.7);                                   // n [-]
    EXPECT_EQ(soil->sinkage_exponent_slip, 0.0);                              // n1 not set
    EXPECT_NEAR(soil->cohesion_pa, 1700.0, 1700.0 * kConversionRelTol);       // 1.7 kPa
    EXPECT_NEAR(soil->friction_angle_rad, 0.50614548307835556, 1e-15);        // 29°
    EXPECT_NEAR(soil->cohesive_modulus, 5300.0, 5300.0 * kConversionRelTol);  // 5.3 kN/m^(n+1)
    EXPECT_NEAR(soil->frictional_modulus, 1.515e6, 1.515e6 * kConversionRelTol);
    EXPECT_EQ(soil->shear_modulus_m, 0.025);                                    // K [m]
    EXPECT_NEAR(soil->unit_weight_n_m3, 15200.0, 15200.0 * kConversionRelTol);  // 15.2 kN/m³
    EXPECT_EQ(soil->max_stress_a0, 0.2);
    EXPECT_EQ(soil->max_stress_a1, 0.3);
    EXPECT_EQ(soil->max_shear_deformation_m, 0.02);  // j_max1, Table 2.6
    EXPECT_TRUE(soil->hasShearLimit());
}

TEST(SoilPresets, PresetWithoutJmaxHasNoShearLimit) {
    const Result<soil::SoilParameters> soil = loadSoil(kSoilDir / "snow.json");
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->max_shear_deformation_m, kInf);
    EXPECT_FALSE(soil->hasShearLimit());
    EXPECT_NEAR(soil->unit_weight_n_m3, 2500.0, 2500.0 * kConversionRelTol);  // 2.5 kN/m³
}

TEST(WheelPresets, WheelsMatchThesisTable51) {
    const Result<wheel::WheelParameters> a = loadWheel(kWheelDir / "A.json");
    const Result<wheel::WheelParameters> b = loadWheel(kWheelDir / "B.json");
    ASSERT_TRUE(a.ok()) << a.message();
    ASSERT_TRUE(b.ok()) << b.message();
    EXPECT_EQ(a->radius_m, 0.092);
    EXPECT_EQ(a->width_m, 0.107);
    EXPECT_EQ(b->radius_m, 0.135);
    EXPECT_EQ(b->width_m, 0.165);
}

TEST(Presets, NamesAreTheFileStemsSorted) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    EXPECT_EQ(presetNames(locations, "soils"), stems(kSoilDir));
    const std::vector<std::string> wheels = stems(kWheelDir);
    EXPECT_EQ(presetNames(locations, "wheels"), wheels);
    EXPECT_EQ(std::count(wheels.begin(), wheels.end(), "A"), 1);
    EXPECT_EQ(std::count(wheels.begin(), wheels.end(), "B"), 1);
    EXPECT_TRUE(presetNames(locations, "nothing-here").empty());
}

TEST(Presets, NamesAreMergedAcrossDirectoriesWithoutDuplicates) {
    TempDir temp;
    writeText(temp.path() / "soils" / "sandy-loam.json", sandyLoamJson().dump());
    writeText(temp.path() / "soils" / "my-soil.json", sandyLoamJson().dump());
    writeText(temp.path() / "soils" / "notes.txt", "not a preset");
    const PresetLocations locations{{temp.path(), TERRA_RESOURCE_DIR}};
    const std::vector<std::string> names = presetNames(locations, "soils");
    EXPECT_EQ(std::count(names.begin(), names.end(), "sandy-loam"), 1);
    EXPECT_EQ(std::count(names.begin(), names.end(), "my-soil"), 1);
    EXPECT_EQ(std::count(names.begin(), names.end(), "notes"), 0);
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
}

TEST(Presets, StandardLocationsSearchNextToTheExecutable) {
    const PresetLocations locations = PresetLocations::standard("/opt/terra/bin");
    const auto& dirs = locations.directories;
    const auto share = std::find(dirs.begin(), dirs.end(),
                                 fs::path("/opt/terra/bin") / ".." / "share" / "terrastudio");
    const auto local = std::find(dirs.begin(), dirs.end(), fs::path("/opt/terra/bin/resources"));
    ASSERT_NE(share, dirs.end());
    ASSERT_NE(local, dirs.end());
    EXPECT_LT(share, local);  // an installed share/ wins over a resources/ beside the binary
}

// Regression: toJson() wrote angles that differ from the preset file ("phi_deg":
// 29.999999999999996 for dry sand's 30.0), so saving an unchanged preset rewrote its values.
TEST(SoilPresets, ToJsonWritesTheFileValuesBack) {
    for (const fs::path& file : jsonFiles(kSoilDir)) {
        const json original = json::parse(std::ifstream(file));
        const Result<soil::SoilParameters> soil = loadSoil(file);
        ASSERT_TRUE(soil.ok()) << file;
        const json written = toJson(*soil);
        for (const auto& [key, value] : original.items()) {
            if (!value.is_number()) continue;
            ASSERT_TRUE(written.contains(key)) << file << " " << key;
            EXPECT_EQ(written[key].get<double>(), value.get<double>())
                << file.filename() << " " << key << ": file " << value.dump() << ", written "
                << written[key].dump();
        }
    }
}

// ---- Round trip ------------------------------------------------------------------------------

void expectSameSoil(const soil::SoilParameters& a, const soil::SoilParameters& b,
                    const std::string& what) {
    EXPECT_EQ(a.name, b.name) << what;
    EXPECT_EQ(a.source, b.source) << what;
    for (const soil::SoilField& field : soil::soilFields()) {
        const double x = a.*field.member;
        const double y = b.*field.member;
        if (std::isinf(x)) {
            EXPECT_EQ(x, y) << what << " " << field.key;
        } else {
            EXPECT_DOUBLE_EQ(x, y) << what << " " << field.key;
        }
    }
}

TEST(SoilJson, EveryPresetSurvivesToJsonAndBack) {
    for (const fs::path& file : jsonFiles(kSoilDir)) {
        const Result<soil::SoilParameters> soil = loadSoil(file);
        ASSERT_TRUE(soil.ok()) << file;
        const Result<soil::SoilParameters> again = soilFromJson(toJson(*soil), "round trip");
        ASSERT_TRUE(again.ok()) << file << ":\n" << again.message();
        expectSameSoil(*soil, *again, file.filename().string());
    }
}

TEST(SoilJson, RoundTripKeepsOptionalFields) {
    soil::SoilParameters soil;
    soil.name = "optional fields";
    soil.friction_angle_rad = 31.5 * kDegToRad;
    soil.source = "test";
    soil.sinkage_exponent = 0.9;
    soil.sinkage_exponent_slip = 0.1;
    soil.slip_sinkage_coefficient = 2.5;
    soil.max_shear_deformation_m = 0.015;
    soil.max_stress_a0 = 0.25;
    soil.max_stress_a1 = -0.35;
    const json written = toJson(soil);
    EXPECT_DOUBLE_EQ(written.at("n1").get<double>(), 0.1);
    EXPECT_DOUBLE_EQ(written.at("slip_sinkage").get<double>(), 2.5);
    EXPECT_DOUBLE_EQ(written.at("jmax_m").get<double>(), 0.015);
    EXPECT_DOUBLE_EQ(written.at("c_kPa").get<double>(), 1.7);    // 1700 Pa in kPa
    EXPECT_DOUBLE_EQ(written.at("kphi").get<double>(), 1515.0);  // 1.515e6 in kN/m^(n+2)
    const Result<soil::SoilParameters> again = soilFromJson(written, "");
    ASSERT_TRUE(again.ok()) << again.message();
    expectSameSoil(soil, *again, "optional fields");
}

// Regression: userValue() once rounded to 12 significant digits, so a soil whose SI values are not
// short decimals in file units (φ = 0.5061 rad, any fitted soil) did not survive save and reload.
TEST(SoilJson, RoundTripKeepsFullPrecision) {
    soil::SoilParameters soil;
    soil.name = "fitted";
    soil.friction_angle_rad = 0.5061;           // the default: 28.99735...°
    soil.cohesion_pa = 1234.5678901234567;      // 1.2345678901234567 kPa
    soil.frictional_modulus = 987654.32109876;  // 987.65432109876 kN/m^(n+2)
    soil.shear_modulus_m = 0.0123456789012345;
    const Result<soil::SoilParameters> again = soilFromJson(toJson(soil), "");
    ASSERT_TRUE(again.ok()) << again.message();
    expectSameSoil(soil, *again, "full precision");
}

TEST(SoilJson, UnsetOptionalFieldsAreLeftOut) {
    soil::SoilParameters soil;  // n1 = 0, j_max = +inf: both unset
    soil.name = "defaults";
    const json written = toJson(soil);
    EXPECT_FALSE(written.contains("n1"));
    EXPECT_FALSE(written.contains("slip_sinkage"));  // S = 0: off, and no key (files unchanged)
    EXPECT_FALSE(written.contains("jmax_m"));
    EXPECT_FALSE(written.contains("source"));  // empty source
    const Result<soil::SoilParameters> again = soilFromJson(written, "");
    ASSERT_TRUE(again.ok()) << again.message();
    EXPECT_EQ(again->max_shear_deformation_m, kInf);
    EXPECT_EQ(again->sinkage_exponent_slip, 0.0);
    EXPECT_EQ(again->slip_sinkage_coefficient, 0.0);
}

TEST(WheelJson, RoundTrip) {
    wheel::WheelParameters wheel{"wheel B", "Thesis Table 5.1", 0.135, 0.165};
    const json written = toJson(wheel);
    EXPECT_EQ(written.at("r_m").get<double>(), 0.135);
    EXPECT_EQ(written.at("b_m").get<double>(), 0.165);
    const Result<wheel::WheelParameters> again = wheelFromJson(written, "");
    ASSERT_TRUE(again.ok()) << again.message();
    EXPECT_EQ(again->name, "wheel B");
    EXPECT_EQ(again->source, "Thesis Table 5.1");
    EXPECT_EQ(again->radius_m, 0.135);
    EXPECT_EQ(again->width_m, 0.165);
}

// ---- Good and bad fixture files --------------------------------------------------------------

TEST(SoilFiles, CustomSoilWithEveryOptionalKey) {
    const Result<soil::SoilParameters> soil = loadSoil(kData / "good" / "soil-custom.json");
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->name, "custom soil");
    EXPECT_EQ(soil->sinkage_exponent, 0.9);
    EXPECT_NEAR(soil->cohesion_pa, 2500.0, 2500.0 * kConversionRelTol);
    EXPECT_NEAR(soil->friction_angle_rad, 0.54977871437821381, 1e-15);  // 31.5° = 0.175 π rad
    EXPECT_NEAR(soil->cohesive_modulus, 12000.0, 12000.0 * kConversionRelTol);
    EXPECT_NEAR(soil->frictional_modulus, 9.0e5, 9.0e5 * kConversionRelTol);
    EXPECT_EQ(soil->shear_modulus_m, 0.018);
    EXPECT_NEAR(soil->unit_weight_n_m3, 16500.0, 16500.0 * kConversionRelTol);
    EXPECT_EQ(soil->max_stress_a0, 0.25);
    EXPECT_EQ(soil->max_stress_a1, 0.35);
    EXPECT_EQ(soil->max_shear_deformation_m, 0.015);
    EXPECT_EQ(soil->sinkage_exponent_slip, 0.1);
}

TEST(SoilFiles, PhiOutOfRange) {
    const fs::path file = kData / "bad" / "soil-phi-out-of-range.json";
    const Result<soil::SoilParameters> soil = loadSoil(file);
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_EQ(soil.issues()[0].where, file.string() + ": phi_deg");
    EXPECT_EQ(soil.issues()[0].message, "75 is outside the allowed range [0, 60) deg");
}

TEST(SoilFiles, WrongType) {
    const Result<soil::SoilParameters> soil = loadSoil(kData / "bad" / "soil-wrong-type.json");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    const std::string message = soil.message();
    EXPECT_TRUE(contains(message, "phi_deg: expected a number in [0, 60)")) << message;
    EXPECT_TRUE(contains(message, "string \"29\"")) << message;
}

TEST(SoilFiles, MissingKey) {
    const Result<soil::SoilParameters> soil = loadSoil(kData / "bad" / "soil-missing-key.json");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_TRUE(contains(soil.message(), "c_kPa: missing; expected a number in [0, 200] kPa"))
        << soil.message();
}

TEST(SoilFiles, UnknownKeyAndTheMissingKeyItReplaced) {
    const Result<soil::SoilParameters> soil = loadSoil(kData / "bad" / "soil-unknown-key.json");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 2u) << soil.message();
    const std::string message = soil.message();
    EXPECT_TRUE(contains(message, "phi: unknown key; did you mean \"phi_deg\"? Allowed keys: "))
        << message;
    EXPECT_TRUE(contains(message, "phi_deg: missing; expected a number in [0, 60) deg")) << message;
}

TEST(SoilFiles, InvalidJsonIsReportedWithItsPositionWithoutThrowing) {
    const fs::path file = kData / "bad" / "soil-not-json.json";
    Result<soil::SoilParameters> soil = std::vector<Issue>{};
    EXPECT_NO_THROW(soil = loadSoil(file));
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u);
    // The second ',' of ",," on line 3 (core/io/json.h: positions as FILE:LINE:COLUMN).
    EXPECT_EQ(soil.issues()[0].where.rfind(file.string() + ":3:", 0), 0u) << soil.message();
    EXPECT_TRUE(contains(soil.issues()[0].message, "invalid JSON")) << soil.message();
}

TEST(SoilFiles, MissingFile) {
    const fs::path file = kData / "bad" / "does-not-exist.json";
    const Result<soil::SoilParameters> soil = loadSoil(file);
    ASSERT_FALSE(soil.ok());
    EXPECT_TRUE(contains(soil.message(), file.string())) << soil.message();
    EXPECT_TRUE(contains(soil.message(), "cannot open")) << soil.message();
}

TEST(WheelFiles, NegativeRadius) {
    const fs::path file = kData / "bad" / "wheel-negative-radius.json";
    const Result<wheel::WheelParameters> wheel = loadWheel(file);
    ASSERT_FALSE(wheel.ok());
    ASSERT_EQ(wheel.issues().size(), 1u) << wheel.message();
    EXPECT_EQ(wheel.issues()[0].where, file.string() + ": r_m");
    EXPECT_EQ(wheel.issues()[0].message, "-0.092 is outside the allowed range [0.01, 5] m");
}

// ---- Bad values in memory --------------------------------------------------------------------

TEST(SoilJson, NullValue) {
    json j = sandyLoamJson();
    j["kc"] = nullptr;
    const Result<soil::SoilParameters> soil = soilFromJson(j, "s.json");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_EQ(soil.issues()[0].where, "s.json: kc");
    EXPECT_TRUE(contains(soil.issues()[0].message, "expected a number in [-500, 5000]"));
    EXPECT_TRUE(contains(soil.issues()[0].message, "null")) << soil.message();
}

TEST(SoilJson, BooleanIsNotANumber) {
    json j = sandyLoamJson();
    j["n"] = true;
    const Result<soil::SoilParameters> soil = soilFromJson(j, "");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_EQ(soil.issues()[0].where, "n");
    EXPECT_TRUE(contains(soil.issues()[0].message, "expected a number in [0.1, 2]"));
}

TEST(SoilJson, OutOfRangeValuesNameFieldValueAndRange) {
    struct Case {
        const char* key;
        double value;
        const char* message;
    };
    for (const Case& c : {Case{"phi_deg", 75.0, "75 is outside the allowed range [0, 60) deg"},
                          Case{"phi_deg", 60.0, "60 is outside the allowed range [0, 60) deg"},
                          Case{"n", 0.0, "0 is outside the allowed range [0.1, 2]"},
                          Case{"K_m", 0.0, "0 is outside the allowed range [1e-04, 0.5] m"},
                          Case{"c_kPa", -0.5, "-0.5 is outside the allowed range [0, 200] kPa"},
                          Case{"jmax_m", 0.0, "0 is outside the allowed range [1e-04, 1] m"},
                          Case{"slip_sinkage", -0.5, "-0.5 is outside the allowed range [0, 10]"},
                          Case{"slip_sinkage", 12.0, "12 is outside the allowed range [0, 10]"}}) {
        json j = sandyLoamJson();
        j[c.key] = c.value;
        const Result<soil::SoilParameters> soil = soilFromJson(j, "f.json");
        ASSERT_FALSE(soil.ok()) << c.key << " = " << c.value;
        ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
        EXPECT_EQ(soil.issues()[0].where, std::string("f.json: ") + c.key);
        EXPECT_EQ(soil.issues()[0].message, c.message);
    }
}

TEST(SoilJson, EveryProblemIsReportedAtOnce) {
    json j = sandyLoamJson();
    j["phi_deg"] = 75.0;
    j["n"] = 0.0;
    j.erase("gamma_kN_m3");
    j["kphi"] = "1515";
    j["phi"] = 29.0;
    const Result<soil::SoilParameters> soil = soilFromJson(j, "");
    ASSERT_FALSE(soil.ok());
    EXPECT_EQ(soil.issues().size(), 5u) << soil.message();
    std::vector<std::string> where;
    for (const Issue& issue : soil.issues()) where.push_back(issue.where);
    std::sort(where.begin(), where.end());
    EXPECT_EQ(where, (std::vector<std::string>{"gamma_kN_m3", "kphi", "n", "phi", "phi_deg"}));
}

TEST(SoilJson, SlipDependentExponentOutOfRangeAtFullSlip) {
    json j = sandyLoamJson();
    j["n"] = 1.5;
    j["n1"] = 0.75;  // N(s = 1) = 2.25 > 2
    const Result<soil::SoilParameters> soil = soilFromJson(j, "f.json");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_EQ(soil.issues()[0].where, "f.json: n1");
    EXPECT_TRUE(contains(soil.issues()[0].message, "2.25")) << soil.message();
    EXPECT_TRUE(contains(soil.issues()[0].message, "[0.1, 2]")) << soil.message();
}

TEST(SoilJson, NameMustBeText) {
    json j = sandyLoamJson();
    j["name"] = 42;
    const Result<soil::SoilParameters> soil = soilFromJson(j, "");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u) << soil.message();
    EXPECT_EQ(soil.issues()[0].where, "name");
    EXPECT_TRUE(contains(soil.issues()[0].message, "expected a string")) << soil.message();
}

TEST(SoilJson, NotAnObject) {
    for (const json& j : {json::array({0.7, 1.7}), json("sandy-loam"), json(3.5), json(nullptr)}) {
        Result<soil::SoilParameters> soil = std::vector<Issue>{};
        EXPECT_NO_THROW(soil = soilFromJson(j, "f.json")) << j.dump();
        ASSERT_FALSE(soil.ok()) << j.dump();
        ASSERT_EQ(soil.issues().size(), 1u);
        EXPECT_EQ(soil.issues()[0].where, "f.json");
        EXPECT_EQ(soil.issues()[0].message.rfind("expected a JSON object, got ", 0), 0u)
            << soil.message();
    }
    EXPECT_FALSE(wheelFromJson(json::array(), "w.json").ok());
}

// K_s = kc/b + kphi depends on the wheel, so a negative kc loads, and the soil–wheel pair is
// rejected where they meet: kc = -500, kphi = 10 with b = 0.1 m gives K_s = -4990 kN/m^(n+2).
TEST(SoilJson, NonPositiveSinkageModulusIsRejectedWithTheWheel) {
    json j = sandyLoamJson();
    j["kc"] = -500.0;
    j["kphi"] = 10.0;
    const Result<soil::SoilParameters> soil = soilFromJson(j, "");
    ASSERT_TRUE(soil.ok()) << soil.message();
    const wheel::WheelParameters narrow{"narrow", "", 0.1, 0.1};
    try {
        contact::makeContactParameters(soil.value(), narrow);
        FAIL() << "K_s = -4990 kN/m^(n+2) for b = 0.1 m was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_TRUE(contains(e.what(), "K_s")) << e.what();
    }
}

TEST(WheelJson, BadInputs) {
    const json good{{"name", "w"}, {"r_m", 0.092}, {"b_m", 0.107}};
    json missing = good;
    missing.erase("b_m");
    Result<wheel::WheelParameters> wheel = wheelFromJson(missing, "w.json");
    ASSERT_FALSE(wheel.ok());
    ASSERT_EQ(wheel.issues().size(), 1u);
    EXPECT_EQ(wheel.issues()[0].where, "w.json: b_m");
    EXPECT_EQ(wheel.issues()[0].message, "missing; expected a number in [0.005, 5] m");

    json typo = good;
    typo["radius"] = 0.1;
    wheel = wheelFromJson(typo, "w.json");
    ASSERT_FALSE(wheel.ok());
    ASSERT_EQ(wheel.issues().size(), 1u);
    EXPECT_EQ(wheel.issues()[0].where, "w.json: radius");
    EXPECT_TRUE(contains(wheel.issues()[0].message, "unknown key; allowed keys: "));
    EXPECT_TRUE(contains(wheel.issues()[0].message, "r_m")) << wheel.message();

    json text = good;
    text["r_m"] = "0.092";
    wheel = wheelFromJson(text, "");
    ASSERT_FALSE(wheel.ok());
    EXPECT_EQ(wheel.issues()[0].where, "r_m");
    EXPECT_TRUE(contains(wheel.issues()[0].message, "expected a number in [0.01, 5]"));
}

// ---- Resolving a name or a path --------------------------------------------------------------

TEST(ResolveSoil, PresetName) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const Result<soil::SoilParameters> soil = resolveSoil(locations, "sandy-loam");
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->name, "sandy loam");
    EXPECT_NEAR(soil->cohesion_pa, 1700.0, 1700.0 * kConversionRelTol);
}

TEST(ResolveSoil, FilePath) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const Result<soil::SoilParameters> soil =
        resolveSoil(locations, (kData / "good" / "soil-custom.json").string());
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->name, "custom soil");
    EXPECT_NEAR(soil->friction_angle_rad, 31.5 * kDegToRad, 1e-15);
}

TEST(ResolveSoil, BadFilePathReportsTheFileProblem) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const Result<soil::SoilParameters> soil =
        resolveSoil(locations, (kData / "bad" / "soil-phi-out-of-range.json").string());
    ASSERT_FALSE(soil.ok());
    EXPECT_TRUE(contains(soil.message(), "phi_deg: 75 is outside")) << soil.message();
}

TEST(ResolveSoil, UnknownNameListsThePresets) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const Result<soil::SoilParameters> soil = resolveSoil(locations, "sandy-lome");
    ASSERT_FALSE(soil.ok());
    ASSERT_EQ(soil.issues().size(), 1u);
    EXPECT_EQ(soil.issues()[0].where, "soil");
    const std::string message = soil.issues()[0].message;
    EXPECT_TRUE(contains(message, "'sandy-lome' is neither a file nor a preset")) << message;
    std::string names;  // every preset, sorted, comma-joined
    for (const std::string& name : stems(kSoilDir)) names += (names.empty() ? "" : ", ") + name;
    EXPECT_TRUE(contains(message, "presets: " + names)) << message;
    EXPECT_TRUE(contains(message, "sandy-loam")) << message;
}

TEST(ResolveSoil, NoPresetDirectories) {
    const Result<soil::SoilParameters> soil = resolveSoil(PresetLocations{}, "sandy-loam");
    ASSERT_FALSE(soil.ok());
    EXPECT_TRUE(contains(soil.message(), "(none found)")) << soil.message();
}

TEST(ResolveSoil, FirstDirectoryWins) {
    TempDir temp;
    json override_soil = sandyLoamJson();
    override_soil["name"] = "overridden sandy loam";
    override_soil["c_kPa"] = 2.0;
    writeText(temp.path() / "soils" / "sandy-loam.json", override_soil.dump());
    const PresetLocations locations{{temp.path(), TERRA_RESOURCE_DIR}};
    const Result<soil::SoilParameters> soil = resolveSoil(locations, "sandy-loam");
    ASSERT_TRUE(soil.ok()) << soil.message();
    EXPECT_EQ(soil->name, "overridden sandy loam");
    EXPECT_NEAR(soil->cohesion_pa, 2000.0, 2000.0 * kConversionRelTol);
    // A preset only in the second directory is still found.
    EXPECT_TRUE(resolveSoil(locations, "dry-sand").ok());
}

TEST(ResolveWheel, PresetNameAndUnknownName) {
    const PresetLocations locations{{TERRA_RESOURCE_DIR}};
    const Result<wheel::WheelParameters> a = resolveWheel(locations, "A");
    ASSERT_TRUE(a.ok()) << a.message();
    EXPECT_EQ(a->radius_m, 0.092);

    const Result<wheel::WheelParameters> c = resolveWheel(locations, "C");
    ASSERT_FALSE(c.ok());
    ASSERT_EQ(c.issues().size(), 1u);
    EXPECT_EQ(c.issues()[0].where, "wheel");
    EXPECT_TRUE(contains(c.issues()[0].message, "presets: A, B")) << c.message();
}

}  // namespace
}  // namespace terra::io
